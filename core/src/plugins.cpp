#include "plugins.h"

#include <dlfcn.h>

#include <algorithm>

#include "pbrlab/contract.h"
#include "pbrlab/error.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// Empty when the descriptor keeps the contract; otherwise what is wrong with it.
std::string validate(const ModuleDesc& d, const fs::path& sourceDir) {
    const ContractStep* step = findContractStep(d.id);
    if (!step) return "id '" + d.id + "' is not in the assignment contract";
    if (step->step != d.step)
        return "step " + std::to_string(d.step) + " should be " + std::to_string(step->step);
    if (step->function != d.function)
        return "function '" + d.function + "' differs from the contract's '" + step->function + "'";
    if (!d.reference) return "no CPU reference";
    if (!d.probe.at || d.probe.width < 2 || d.probe.height < 2) return "no probe";
    for (const char* file : {"solution.glsl", "view.glsl"})
        if (!fs::exists(sourceDir / file)) return "missing " + (sourceDir / file).string();
    return {};
}

}  // namespace

ModuleRegistry::ModuleRegistry(const fs::path& moduleDir, const fs::path& labsRoot,
                               const std::string& onlyId) {
    std::error_code ec;
    if (!fs::is_directory(moduleDir, ec))
        throw Error("module directory " + moduleDir.string() + " does not exist");
    std::vector<fs::path> libraries;
    for (const auto& entry : fs::directory_iterator(moduleDir, ec)) {
        std::string name = entry.path().filename().string();
        if (name.rfind("pbrlab-", 0) == 0 && entry.path().extension() == ".so")
            libraries.push_back(entry.path());
    }
    std::sort(libraries.begin(), libraries.end());
    if (!onlyId.empty()) {
        const std::string suffix = "-" + onlyId + ".so";
        auto named = std::find_if(libraries.begin(), libraries.end(), [&](const fs::path& lib) {
            const std::string name = lib.filename().string();
            return name.size() > suffix.size() &&
                   name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
        });
        if (named != libraries.end()) libraries = {*named};
    }
    for (const auto& lib : libraries) {
        void* handle = dlopen(lib.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            failures_.push_back({lib, std::string("cannot load: ") + dlerror()});
            continue;
        }
        auto abi = reinterpret_cast<int (*)()>(dlsym(handle, "pbrlab_module_abi"));
        auto get = reinterpret_cast<const ModuleDesc* (*)()>(dlsym(handle, "pbrlab_module"));
        std::string reason;
        if (!abi || !get) {
            reason = "not a pbrlab module (no pbrlab_module_abi/pbrlab_module symbols)";
        } else if (abi() != kModuleAbiVersion) {
            reason = "ABI version " + std::to_string(abi()) + ", this host needs " +
                     std::to_string(kModuleAbiVersion) + "; rebuild the module";
        } else {
            const ModuleDesc* desc = get();
            const ContractStep* step = desc ? findContractStep(desc->id) : nullptr;
            fs::path sourceDir = step ? labsRoot / step->folder() : fs::path();
            reason = desc ? validate(*desc, sourceDir) : "pbrlab_module() returned null";
            if (reason.empty()) {
                auto dup =
                    std::find_if(modules_.begin(), modules_.end(),
                                 [&](const LoadedModule& m) { return m.desc->id == desc->id; });
                if (dup != modules_.end())
                    reason = "id '" + desc->id + "' already loaded from " + dup->library.string();
            }
            if (reason.empty()) {
                modules_.push_back({desc, lib, sourceDir});
                handles_.push_back(handle);
                continue;
            }
        }
        failures_.push_back({lib, reason});
        dlclose(handle);
    }
    std::sort(modules_.begin(), modules_.end(), [](const LoadedModule& a, const LoadedModule& b) {
        return a.desc->step < b.desc->step;
    });
}

ModuleRegistry::~ModuleRegistry() {
    // Descriptors hold std::function objects whose code lives in the libraries: drop our
    // pointers first, then unload.
    modules_.clear();
    for (void* h : handles_) dlclose(h);
}

const LoadedModule& ModuleRegistry::find(const std::string& id) const {
    for (const auto& m : modules_)
        if (m.desc->id == id) return m;
    std::string known;
    for (const auto& m : modules_) known += (known.empty() ? "" : ", ") + m.desc->id;
    throw Error("no module '" + id + "'" +
                (known.empty() ? " (no modules loaded)" : "; loaded: " + known));
}

}  // namespace pbrlab
