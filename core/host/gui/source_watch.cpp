#include "source_watch.h"

#include "shader/preprocess.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab {

void SourceWatch::scan(const fs::path& file, const fs::path& folder) {
    std::vector<fs::path> files;
    try {
        ShaderPart part(file);
        part.studentFolder = folder;  // screened, as the renderer reads a student's file
        files = ShaderPreprocessor({folder}).expand({part}, {}).files;
    } catch (const Error&) {
        // A missing include (or the file itself missing): the renderer says why. The folder
        // is watched as well, so the file that was missing is noticed when it is created.
        files = {file, folder};
    }
    stamps_.clear();
    for (const fs::path& f : files) stamps_.emplace_back(f, FileStamp::of(f));
}

bool SourceWatch::stale(const fs::path& file) const {
    bool changed = file != file_ || stamps_.empty();
    for (const auto& [f, stamp] : stamps_) changed = changed || FileStamp::of(f) != stamp;
    return changed;
}

SourceWatch::Stamps SourceWatch::current() const {
    Stamps now;
    for (const auto& [f, stamp] : stamps_) now.emplace_back(f, FileStamp::of(f));
    return now;
}

bool SourceWatch::changed(const fs::path& file, const fs::path& folder) {
    if (!stale(file)) return false;
    file_ = file;
    scan(file, folder);  // an edit may add or remove an #include
    return true;
}

}  // namespace pbrlab
