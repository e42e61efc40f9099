// The plugin host: finds module shared libraries (pbrlab-<id>.so) in its folders, checks their
// ABI version, gives each the identity its step folder declares (step.json: id, lab, position,
// signature) and keeps the ones that pass. A module that fails is recorded with its path and
// reason; the others still load.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "pbrlab/module.h"

namespace pbrlab {

struct ContractStep;

struct LoadedModule {
    const ModuleDesc* desc = nullptr;
    std::filesystem::path library;
    std::filesystem::path sourceDir;  // its step folder: step.json, solution.glsl, view.glsl, ...
};

struct ModuleLoadFailure {
    std::filesystem::path library;
    std::string reason;
};

class ModuleRegistry {
public:
    // Loads pbrlab-<id>.so from each folder, in order; a folder may also hold step folders
    // (<id>/step.json: an out-of-tree step, added to the contract). When `onlyId` is given and
    // a library is named pbrlab-<onlyId>.so, only that library is opened (a command about one
    // module need not pay ~1 ms per library to open and close them all); otherwise every one.
    explicit ModuleRegistry(const std::vector<std::filesystem::path>& moduleDirs,
                            const std::string& onlyId = {});
    explicit ModuleRegistry(const std::filesystem::path& moduleDir, const std::string& onlyId = {})
        : ModuleRegistry(std::vector<std::filesystem::path>{moduleDir}, onlyId) {}
    ModuleRegistry(const ModuleRegistry&) = delete;
    ModuleRegistry& operator=(const ModuleRegistry&) = delete;
    ~ModuleRegistry();

    const std::vector<LoadedModule>& modules() const { return modules_; }  // in step order
    const std::vector<ModuleLoadFailure>& failures() const { return failures_; }
    // Throws pbrlab::Error listing the known ids when `id` is not loaded.
    const LoadedModule& find(const std::string& id) const;

private:
    // Keeps a copy of the descriptor with its identity from step.json (the library's own, or
    // the linked-in step's, stays untouched).
    void adopt(const ModuleDesc& desc, const ContractStep& step,
               const std::filesystem::path& library);
    std::vector<LoadedModule> modules_;
    std::vector<ModuleLoadFailure> failures_;
    std::vector<void*> handles_;
    // The descriptors with their identity from step.json (the libraries' own stay untouched).
    std::vector<std::unique_ptr<ModuleDesc>> descs_;
};

}  // namespace pbrlab
