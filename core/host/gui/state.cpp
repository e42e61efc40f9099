#include "state.h"

#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "steps/plugin_host.h"

namespace fs = std::filesystem;

namespace pbrlab {

fs::path configFile() {
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    fs::path base = xdg && *xdg ? fs::path(xdg) : fs::path(home ? home : ".") / ".config";
    return base / "pbrlab" / "gui.json";
}

fs::path canonicalFile(const fs::path& file) {
    std::error_code ec;
    fs::path absolute = fs::absolute(file, ec);
    if (ec) return file;
    fs::path canonical = fs::weakly_canonical(absolute, ec);
    return ec ? absolute : canonical;
}

RememberedChoice restoreState(const ModuleRegistry& registry, GuiState& state,
                              std::string& messages) {
    std::ifstream in(configFile());
    if (!in) return {};
    RememberedChoice remembered;
    try {
        nlohmann::json j = nlohmann::json::parse(in);
        if (j.contains("model")) remembered.model = j["model"].get<std::string>();
        const nlohmann::json& all = j.contains("params") ? j["params"] : nlohmann::json();
        if (!all.is_object()) return remembered;
        for (auto& [id, params] : all.items()) {
            auto it = state.params.find(id);
            if (it == state.params.end()) continue;
            for (auto& [name, value] : params.items()) try {
                    applyAssignment(registry.find(id).desc->params, it->second,
                                    name + "=" + value.get<std::string>());
                } catch (const std::exception&) {
                    // A value from an older version of the module: keep the default.
                }
        }
        if (j.contains("module")) remembered.step = j["module"].get<std::string>();
        if (j.contains("views") && j["views"].is_object())
            for (auto& [id, view] : j["views"].items())
                if (view.is_string()) state.chosenViews[id] = view.get<std::string>();
    } catch (const std::exception& e) {
        messages += configFile().string() + ": ignored (" + e.what() + ")\n";
    }
    return remembered;
}

void saveState(const ModuleRegistry& registry, const GuiState& state) {
    nlohmann::json j;
    j["module"] = registry.modules()[size_t(state.step)].desc->id;
    if (!state.model.empty()) j["model"] = state.model.string();  // the model stays across steps
    for (const auto& m : registry.modules())
        for (const auto& p : m.desc->params)
            j["params"][m.desc->id][p.name] = p.format(state.params.at(m.desc->id).vector(p.name));
    for (const auto& [id, view] : state.chosenViews) j["views"][id] = view;
    std::error_code ec;
    fs::create_directories(configFile().parent_path(), ec);
    fs::path tmp = configFile();
    tmp += ".tmp";
    std::ofstream(tmp) << j.dump(2);
    fs::rename(tmp, configFile(), ec);
}

}  // namespace pbrlab
