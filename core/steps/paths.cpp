#include "steps/paths.h"

#include <cstdlib>

namespace fs = std::filesystem;

namespace pbrlab {

fs::path DataPaths::scene(const std::string& name) const {
    if (name.find('/') != std::string::npos || fs::path(name).extension() == ".json") return name;
    return assets() / "scenes" / (name + ".json");
}

fs::path executableDir() {
    std::error_code ec;
    fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? fs::current_path() : exe.parent_path();
}

namespace {

// <prefix>/bin/pbrlab installed by cmake --install: its data in <prefix>/share/pbrlab.
fs::path installedData() {
    std::error_code ec;
    const fs::path share = executableDir().parent_path() / "share" / "pbrlab";
    return fs::is_directory(share / "shaders", ec) ? share : fs::path();
}

}  // namespace

DataPaths DataPaths::locate() {
    if (const char* env = std::getenv("PBRLAB_DATA"); env && *env) return {env};
    if (fs::path installed = installedData(); !installed.empty()) return {installed};
    return {PBRLAB_SOURCE_DIR};
}

std::vector<fs::path> moduleDirs(const std::vector<fs::path>& extra) {
    std::vector<fs::path> dirs;
    std::error_code ec;
    const fs::path exe = executableDir();
    if (fs::is_directory(exe / "modules", ec))
        dirs.push_back(exe / "modules");
    else
        dirs.push_back(exe.parent_path() / "lib" / "pbrlab" / "modules");
    if (const char* env = std::getenv("PBRLAB_MODULES"); env && *env) {
        const std::string list = env;
        size_t start = 0;
        while (start <= list.size()) {
            const size_t end = std::min(list.find(':', start), list.size());
            if (end > start) dirs.push_back(list.substr(start, end - start));
            start = end + 1;
        }
    }
    dirs.insert(dirs.end(), extra.begin(), extra.end());
    // A folder named twice (the GUI passes its folders on to the processes it starts) once.
    std::vector<fs::path> unique;
    for (const fs::path& dir : dirs) {
        bool seen = false;
        for (const fs::path& known : unique)
            seen = seen || known == dir || fs::equivalent(known, dir, ec);
        if (!seen) unique.push_back(dir);
    }
    return unique;
}

}  // namespace pbrlab
