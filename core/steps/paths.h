// Where pbrlab finds its files: the data root (shaders, assets, the built-in step folders) and
// the module libraries. A build tree and an installed tree (cmake --install) are both found.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pbrlab {

struct DataPaths {
    std::filesystem::path root;
    std::filesystem::path shaders() const { return root / "shaders"; }
    std::filesystem::path labs() const { return root / "labs"; }  // the built-in step folders
    std::filesystem::path assets() const { return root / "assets"; }
    std::filesystem::path scene(const std::string& name) const;  // a name or a .json path
    // $PBRLAB_DATA; else <prefix>/share/pbrlab beside an installed executable; else the source
    // tree this was built from.
    static DataPaths locate();
};

// The folder of the running executable.
std::filesystem::path executableDir();

// The folders the module libraries (pbrlab-<id>.so) are loaded from, in order: the built-in
// ones (build/modules beside a build-tree executable, <prefix>/lib/pbrlab/modules installed),
// then every folder of $PBRLAB_MODULES (colon-separated), then `extra` (--modules). Each may
// also hold step folders (<id>/step.json, a link to an out-of-tree step's source folder).
std::vector<std::filesystem::path> moduleDirs(const std::vector<std::filesystem::path>& extra = {});

}  // namespace pbrlab
