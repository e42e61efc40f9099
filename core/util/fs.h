// Paths on disk.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace pbrlab {

// The whole file's bytes. Throws pbrlab::Error naming the file when it cannot be read.
std::string readFile(const std::filesystem::path& file);

// True when `path` (made canonical) lies inside `root` (made canonical). A path that cannot be
// resolved (a symlink loop, a component that is not a folder) is not inside anything.
bool isInside(const std::filesystem::path& path, const std::filesystem::path& root);

// What tells that a file changed (hot reload, the badges): its modification time, size and a
// hash of its bytes. The time alone is not enough where a file system keeps it to the second
// (Emscripten's in-memory one, in a page; FAT): a file rewritten within the same second, as
// the page's editor and the grader's copies of the typical mistakes do, must read as changed.
// A folder or a missing file has its time only (missing: the smallest, so that its
// appearance is a change).
struct FileStamp {
    std::filesystem::file_time_type time = std::filesystem::file_time_type::min();
    std::uintmax_t size = 0;
    std::size_t hash = 0;
    bool operator==(const FileStamp&) const = default;
    static FileStamp of(const std::filesystem::path& file);
};

}  // namespace pbrlab
