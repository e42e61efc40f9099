// Hot reload: the files a student's step file is made of (the file and every file it
// #includes, as the shader preprocessor reads them) and their stamps (util/fs.h, FileStamp).
#pragma once

#include <filesystem>
#include <utility>
#include <vector>

#include "util/fs.h"

namespace pbrlab {

class SourceWatch {
public:
    // True on the first call for a file, and whenever the file or one it includes changed,
    // appeared or disappeared since the last call. `folder` is the submission folder, the
    // only place a student's #include may read from.
    bool changed(const std::filesystem::path& file, const std::filesystem::path& folder);
    void forget() { stamps_.clear(); }
    // What changed() would say now, without rescanning: for a caller that only asks.
    bool stale(const std::filesystem::path& file) const;

    using Stamps = std::vector<std::pair<std::filesystem::path, FileStamp>>;
    // The watched files' stamps on disk now (the files of the last scan).
    Stamps current() const;

private:
    void scan(const std::filesystem::path& file, const std::filesystem::path& folder);
    std::filesystem::path file_;
    Stamps stamps_;
};

}  // namespace pbrlab
