// Helpers shared by the tests: temporary folders and a headless GL session.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "ibl/precompute.h"

namespace pbrlab::test {

// Small environment maps, quick to precompute: for tests of a mechanism (caches, bands,
// dialects), not of the maps' accuracy.
inline IblSettings smallMaps() {
    IblSettings s;
    s.environmentSize = 64;
    s.irradianceSize = 8;
    s.prefilterSize = 16;
    s.prefilterMips = 3;
    s.lutWidth = s.lutHeight = 16;
    return s;
}

// A fresh, empty folder under the system temp dir, removed when the object dies.
struct TempDir {
    std::filesystem::path path;
    TempDir() {
        std::random_device rd;
        path = std::filesystem::temp_directory_path() /
               ("pbrlab-test-" + std::to_string(rd()) + std::to_string(rd()));
        std::filesystem::create_directories(path);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    std::filesystem::path write(const std::string& name, const std::string& text) const {
        std::filesystem::path p = path / name;
        std::filesystem::create_directories(p.parent_path());
        std::ofstream(p, std::ios::binary) << text;
        return p;
    }
};

// A shell command run to its end, its output kept (stdin from /dev/null: nothing it starts can
// wait for input).
struct CommandRun {
    int status = -1;
    std::string output;  // stdout and stderr
};

inline CommandRun run(const TempDir& dir, const std::string& command) {
    const std::filesystem::path log = dir.path / "log.txt";
    const int status = std::system((command + " > " + log.string() + " 2>&1 < /dev/null").c_str());
    std::ifstream in(log);
    std::stringstream text;
    text << in.rdbuf();
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

}  // namespace pbrlab::test
