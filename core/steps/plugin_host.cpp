#include "steps/plugin_host.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstring>

#include "steps/contract.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

constexpr const char* kPrefix = "pbrlab-";
constexpr const char* kSuffix = ".so";

// "pbrlab-ndotl.so" -> "ndotl".
std::string idOfLibrary(const fs::path& library) {
    const std::string name = library.filename().string();
    return name.substr(std::strlen(kPrefix),
                       name.size() - std::strlen(kPrefix) - std::strlen(kSuffix));
}

// Empty when the descriptor may be the step's; otherwise what is wrong with it. Identity lives in
// step.json: a descriptor that still sets it must agree.
std::string validate(const ModuleDesc& d, const ContractStep& step) {
    if (!d.id.empty() && d.id != step.id)
        return "descriptor id '" + d.id + "' differs from step.json's '" + step.id + "'";
    if (!d.lab.empty() && d.lab != step.lab)
        return "descriptor lab '" + d.lab + "' differs from the contract's '" + step.lab + "'";
    if (!d.function.empty() && d.function != step.function)
        return "function '" + d.function + "' differs from the contract's '" + step.function +
               "' (" + (step.folder / "step.json").string() + ")";
    if (!d.reference) return "no CPU reference";
    if (!d.probe.at || d.probe.width < 2 || d.probe.height < 2) return "no probe";
    // (An assignment's site withholds solution.glsl and carries the starter: contract.h.)
    const char* solution = solutionWithheld(step) ? "starter.glsl" : "solution.glsl";
    for (const char* file : {solution, "view.glsl"})
        if (!fs::exists(step.folder / file)) return "missing " + (step.folder / file).string();
    return {};
}

// The libraries named pbrlab-<id>.so in a folder, in order of their names.
std::vector<fs::path> librariesIn(const fs::path& dir) {
    std::error_code ec;
    std::vector<fs::path> here;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(kPrefix, 0) == 0 && entry.path().extension() == kSuffix &&
            name.size() > std::strlen(kPrefix) + std::strlen(kSuffix))
            here.push_back(entry.path());
    }
    std::sort(here.begin(), here.end());
    return here;
}

// Empty when the opened library is a module that may be step `id` (`desc` is then its
// descriptor); otherwise why not: its symbols, ABI version and descriptor, and whether a module
// of that id is `loaded` already.
std::string libraryProblem(void* handle, const ContractStep& step, const std::string& id,
                           const std::vector<LoadedModule>& loaded, const ModuleDesc*& desc) {
    auto abi = reinterpret_cast<int (*)()>(dlsym(handle, "pbrlab_module_abi"));
    auto get = reinterpret_cast<const ModuleDesc* (*)()>(dlsym(handle, "pbrlab_module"));
    if (!abi || !get) return "not a pbrlab module (no pbrlab_module_abi/pbrlab_module symbols)";
    if (abi() != kModuleAbiVersion)
        return "ABI version " + std::to_string(abi()) + ", this host needs " +
               std::to_string(kModuleAbiVersion) + "; rebuild the module";
    desc = get();
    std::string reason = desc ? validate(*desc, step) : "pbrlab_module() returned null";
    if (reason.empty()) {
        auto dup = std::find_if(loaded.begin(), loaded.end(),
                                [&](const LoadedModule& m) { return m.desc->id == id; });
        if (dup != loaded.end())
            reason = "id '" + id + "' already loaded from " + dup->library.string();
    }
    return reason;
}

}  // namespace

ModuleRegistry::ModuleRegistry(const std::vector<fs::path>& moduleDirs, const std::string& onlyId) {
    std::error_code ec;
    std::vector<fs::path> libraries;
    for (const fs::path& dir : moduleDirs) {
        if (!fs::is_directory(dir, ec))
            throw Error("module directory " + dir.string() + " does not exist");
        addStepRoot(dir);
        const std::vector<fs::path> here = librariesIn(dir);
        libraries.insert(libraries.end(), here.begin(), here.end());
    }
    if (!onlyId.empty()) {
        auto named = std::find_if(libraries.begin(), libraries.end(),
                                  [&](const fs::path& lib) { return idOfLibrary(lib) == onlyId; });
        if (named != libraries.end()) libraries = {*named};
    }
    for (const auto& lib : libraries) {
        const std::string id = idOfLibrary(lib);
        const ContractStep* step = findContractStep(id);
        if (!step) {
            failures_.push_back({lib, "no step folder declares '" + id +
                                          "' (a folder <id>/ with step.json, in labs/ or beside "
                                          "the library)"});
            continue;
        }
        void* handle = dlopen(lib.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            failures_.push_back({lib, std::string("cannot load: ") + dlerror()});
            continue;
        }
        const ModuleDesc* desc = nullptr;
        const std::string reason = libraryProblem(handle, *step, id, modules_, desc);
        if (reason.empty()) {
            adopt(*desc, *step, lib);
            handles_.push_back(handle);
            continue;
        }
        failures_.push_back({lib, reason});
        dlclose(handle);
    }
    // The steps linked into the program (the browser's build): taken as libraries are, named
    // "(linked in)" where a library's path would be.
    for (const StaticModule& linked : staticModules()) {
        if (!onlyId.empty() && linked.id != onlyId) continue;
        const fs::path lib = std::string("(linked in) ") + linked.id;
        const ContractStep* step = findContractStep(linked.id);
        // An assignment's site leaves out the folders of steps not released yet: their code
        // is linked in, and not offered.
        if (!step) continue;
        const ModuleDesc* desc = linked.get();
        std::string reason = validate(*desc, *step);
        if (reason.empty() && std::any_of(modules_.begin(), modules_.end(),
                                          [&](const auto& m) { return m.desc->id == linked.id; }))
            reason = "id '" + std::string(linked.id) + "' is also loaded from a library";
        if (!reason.empty()) {
            failures_.push_back({lib, reason});
            continue;
        }
        adopt(*desc, *step, lib);
    }
    std::sort(modules_.begin(), modules_.end(), [](const LoadedModule& a, const LoadedModule& b) {
        return a.desc->step < b.desc->step;
    });
}

void ModuleRegistry::adopt(const ModuleDesc& desc, const ContractStep& step,
                           const fs::path& library) {
    auto owned = std::make_unique<ModuleDesc>(desc);
    owned->id = step.id;
    owned->step = step.step;
    owned->lab = step.lab;
    owned->function = step.function;
    modules_.push_back({owned.get(), library, step.folder});
    descs_.push_back(std::move(owned));
}

ModuleRegistry::~ModuleRegistry() {
    // Descriptors hold std::function objects whose code lives in the libraries: drop our
    // pointers first, then unload.
    modules_.clear();
    descs_.clear();
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
