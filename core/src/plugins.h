// The plugin host: finds module shared libraries (pbrlab-*.so) in a directory, checks their
// ABI version and descriptor against the contract, and keeps the ones that pass. A module
// that fails is recorded with its path and reason; the others still load.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "pbrlab/module.h"

namespace pbrlab {

struct LoadedModule {
    const ModuleDesc* desc = nullptr;
    std::filesystem::path library;
    std::filesystem::path sourceDir;  // labs/NN-id: solution.glsl, view.glsl, README.md
};

struct ModuleLoadFailure {
    std::filesystem::path library;
    std::string reason;
};

class ModuleRegistry {
public:
    // `labsRoot` holds the module folders (labs/NN-id) with their GLSL and handouts. When
    // `onlyId` is given and a library's name ends in -<onlyId>.so, only that library is opened
    // (a command about one module need not pay ~1 ms per library to open and close them all);
    // otherwise every library is.
    ModuleRegistry(const std::filesystem::path& moduleDir, const std::filesystem::path& labsRoot,
                   const std::string& onlyId = {});
    ModuleRegistry(const ModuleRegistry&) = delete;
    ModuleRegistry& operator=(const ModuleRegistry&) = delete;
    ~ModuleRegistry();

    const std::vector<LoadedModule>& modules() const { return modules_; }  // in step order
    const std::vector<ModuleLoadFailure>& failures() const { return failures_; }
    // Throws pbrlab::Error listing the known ids when `id` is not loaded.
    const LoadedModule& find(const std::string& id) const;

private:
    std::vector<LoadedModule> modules_;
    std::vector<ModuleLoadFailure> failures_;
    std::vector<void*> handles_;
};

}  // namespace pbrlab
