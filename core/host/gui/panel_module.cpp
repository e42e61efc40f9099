// The module panel: the step's parameters (widgets generated from their declarations) and the
// scene: chooser (scenes and glTF models), the first light, the environment, the camera.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "panels.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// A small 2D pad for directions: the disk is the hemisphere seen from +z (towards the
// viewer); dragging sets x and y, z follows on the chosen side.
bool directionPad(const char* id, glm::dvec3& dir) {
    const float radius = 52;
    ImVec2 origin = ImGui::GetCursorScreenPos();
    ImVec2 centre(origin.x + radius, origin.y + radius);
    ImGui::InvisibleButton(id, ImVec2(2 * radius, 2 * radius));
    bool changed = false;
    if (ImGui::IsItemActive()) {
        ImVec2 m = ImGui::GetIO().MousePos;
        glm::dvec2 p((m.x - centre.x) / radius, -(m.y - centre.y) / radius);
        if (glm::length(p) > 1) p = glm::normalize(p);
        double z = std::sqrt(std::max(0.0, 1 - glm::dot(p, p)));
        dir = glm::dvec3(p, dir.z < 0 ? -z : z);
        changed = true;
    }
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddCircleFilled(centre, radius, IM_COL32(40, 44, 52, 255));
    dl->AddCircle(centre, radius, IM_COL32(120, 120, 130, 255));
    dl->AddLine(ImVec2(centre.x - radius, centre.y), ImVec2(centre.x + radius, centre.y),
                IM_COL32(70, 70, 80, 255));
    dl->AddLine(ImVec2(centre.x, centre.y - radius), ImVec2(centre.x, centre.y + radius),
                IM_COL32(70, 70, 80, 255));
    ImVec2 dot(centre.x + float(dir.x) * radius, centre.y - float(dir.y) * radius);
    if (dir.z >= 0)
        dl->AddCircleFilled(dot, 5, IM_COL32(255, 210, 90, 255));
    else
        dl->AddCircle(dot, 5, IM_COL32(255, 210, 90, 255), 12, 2);
    return changed;
}

// One parameter's widget; true when the student changed the value.
bool paramWidget(const ParamDecl& p, glm::dvec3& v) {
    bool changed = false;
    switch (p.type) {
        case ParamType::Float: {
            float f = float(v.x);
            changed = ImGui::SliderFloat(p.name.c_str(), &f, float(p.min), float(p.max), "%.4g",
                                         p.logScale ? ImGuiSliderFlags_Logarithmic : 0);
            v.x = f;
            break;
        }
        case ParamType::Int: {
            int i = int(v.x);
            changed = ImGui::SliderInt(p.name.c_str(), &i, int(p.min), int(p.max));
            v.x = i;
            break;
        }
        case ParamType::Bool: {
            bool b = v.x != 0;
            changed = ImGui::Checkbox(p.name.c_str(), &b);
            v.x = b;
            break;
        }
        case ParamType::Enum: {
            int i = int(v.x);
            if (ImGui::BeginCombo(p.name.c_str(), p.choices[size_t(i)].c_str())) {
                for (size_t k = 0; k < p.choices.size(); ++k)
                    if (ImGui::Selectable(p.choices[k].c_str(), int(k) == i)) {
                        v.x = double(k);
                        changed = true;
                    }
                ImGui::EndCombo();
            }
            break;
        }
        case ParamType::Color: {
            float c[3] = {float(v.x), float(v.y), float(v.z)};
            changed = ImGui::ColorEdit3(
                p.name.c_str(), c,
                p.max > 1 ? ImGuiColorEditFlags_HDR | ImGuiColorEditFlags_Float : 0);
            v = glm::clamp(glm::dvec3(c[0], c[1], c[2]), 0.0, p.max);
            break;
        }
        case ParamType::Direction: {
            ImGui::TextUnformatted(p.name.c_str());
            changed = directionPad("pad", v);
            ImGui::SameLine();
            ImGui::BeginGroup();
            float f[3] = {float(v.x), float(v.y), float(v.z)};
            ImGui::SetNextItemWidth(std::min(200.0f, ImGui::GetContentRegionAvail().x));
            if (ImGui::DragFloat3("##xyz", f, 0.01f, -1, 1) &&
                glm::length(glm::dvec3(f[0], f[1], f[2])) > 1e-6) {
                v = glm::dvec3(f[0], f[1], f[2]);
                changed = true;
            }
            if (ImGui::Button(v.z < 0 ? "lower hemisphere" : "upper hemisphere")) {
                v.z = -v.z;
                changed = true;
            }
            ImGui::EndGroup();
            if (changed) v = glm::normalize(v);
            break;
        }
    }
    return changed;
}

void drawParams(const Lab& lab, GuiState& state, Requests& requests) {
    const ModuleDesc& d = lab.module(state);
    ParamValues& params = state.params.at(d.id);
    if (d.params.empty()) ImGui::TextDisabled("this step has no parameters");
    for (const ParamDecl& p : d.params) {
        ImGui::PushID(p.name.c_str());
        glm::dvec3 v = params.vector(p.name);
        bool changed = paramWidget(p, v);
        if (ImGui::IsItemHovered() && !p.description.empty())
            ImGui::SetTooltip("%s", p.description.c_str());
        ImGui::SameLine();
        if (ImGui::SmallButton("reset")) {
            v = p.defaultValue;
            changed = true;
        }
        if (changed) {
            params.set(p.name, v);
            requests.moved = true;
        }
        ImGui::TextDisabled("  %s", p.description.c_str());
        ImGui::PopID();
    }
}

// The glTF models the chooser offers: the project's own (assets/models), the --model file,
// and the one chosen (it may come from the saved state).
std::vector<fs::path> modelChoices(const Lab& lab, const GuiState& state) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(lab.paths().assets() / "models", ec))
        if (e.path().extension() == ".glb" || e.path().extension() == ".gltf")
            files.push_back(canonicalFile(e.path()));
    std::sort(files.begin(), files.end());
    const fs::path& option = lab.options().model;
    fs::path given = option.empty() ? fs::path() : canonicalFile(option);
    for (const fs::path& f : {given, state.model})
        if (!f.empty() && std::find(files.begin(), files.end(), f) == files.end())
            files.push_back(f);
    return files;
}

void sceneChooser(const Lab& lab, GuiState& state, Requests& requests,
                  const std::string& sceneShown) {
    std::string current = state.model.empty() ? sceneShown : state.model.filename().string();
    ImGui::SetNextItemWidth(std::min(220.0f, ImGui::CalcItemWidth()));
    if (!ImGui::BeginCombo("scene", current.c_str())) return;
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(lab.paths().assets() / "scenes"))
        if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
    std::sort(names.begin(), names.end());
    for (const auto& n : names)
        if (ImGui::Selectable(n.c_str(), state.model.empty() && n == sceneShown)) {
            state.sceneName = n;
            state.model.clear();
            requests.reloadScene = true;
        }
    // A model is lit like the step's own scene, so any model works with any step.
    ImGui::Separator();
    ImGui::TextDisabled("glTF models");
    std::vector<fs::path> models = modelChoices(lab, state);
    for (size_t i = 0; i < models.size(); ++i) {
        ImGui::PushID(int(i));  // two folders may hold the same file name
        if (ImGui::Selectable(models[i].filename().string().c_str(), models[i] == state.model)) {
            state.model = models[i];
            state.sceneName.clear();
            requests.reloadScene = true;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", models[i].string().c_str());
        ImGui::PopID();
    }
    ImGui::EndCombo();
}

void drawScenePanel(const Lab& lab, GuiState& state, Requests& requests) {
    const Scene& scene = lab.shown().scene;
    ImGui::TextDisabled("scene");
    std::string sceneShown = state.sceneName.empty() ? lab.module(state).scene : state.sceneName;
    sceneChooser(lab, state, requests, sceneShown);
    if (!state.model.empty()) ImGui::TextDisabled("glTF model, lit like %s", sceneShown.c_str());
    const std::string& sceneError = lab.shown().sceneError;
    if (!sceneError.empty()) {  // wrapped: a model's error names its full path
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.3f, 0.3f, 1));
        ImGui::TextWrapped("%s", sceneError.c_str());
        ImGui::PopStyleColor();
    }
    if (!scene.lights.empty()) {
        PointLightDesc light = scene.lights[0];
        float pos[3] = {float(light.position.x), float(light.position.y), float(light.position.z)};
        if (ImGui::DragFloat3("light 0 position", pos, 0.05f)) {
            light.position = glm::dvec3(pos[0], pos[1], pos[2]);
            requests.firstLight = light;
        }
        // Colour and intensity apart: light colours are in the hundreds (thousands for a
        // large model), which neither fits nor edits well in a colour widget.
        const glm::dvec3 color = light.color;
        float intensity = float(std::max({color.x, color.y, color.z}));
        const glm::dvec3 hue = intensity > 0 ? color / double(intensity) : glm::dvec3(1);
        float col[3] = {float(hue.x), float(hue.y), float(hue.z)};
        bool edited = ImGui::ColorEdit3("light 0 colour", col, ImGuiColorEditFlags_Float);
        edited |= ImGui::DragFloat("light 0 intensity", &intensity, intensity * 0.01f + 0.01f, 0.0f,
                                   1e7f, "%.1f", ImGuiSliderFlags_AlwaysClamp);
        if (edited) {
            light.color = glm::max(glm::dvec3(col[0], col[1], col[2]), 0.0) * double(intensity);
            requests.firstLight = light;
        }
    }
    if (lab.module(state).needs & NeedsEnvironment) {
        char* input = state.environmentInput.data();
        if (input[0] == 0)
            std::snprintf(input, state.environmentInput.size(), "%s", scene.environment.c_str());
        ImGui::SetNextItemWidth(std::min(220.0f, ImGui::CalcItemWidth() - 50));
        ImGui::InputText("environment", input, state.environmentInput.size());
        ImGui::SameLine();
        if (ImGui::Button("load")) requests.environment = std::string(input);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("\"sky\" (the project's own) or an equirectangular .hdr/.exr");
    }
    if (ImGui::Button("reset camera")) requests.reloadScene = true;
    ImGui::SameLine();
    ImGui::TextDisabled("drag: orbit, wheel: zoom");
}

}  // namespace

void drawModulePanel(const Lab& lab, GuiState& state, Requests& requests) {
    // Every control leaves room for the longest label beside it, and the descriptions wrap:
    // in a narrow window (a laptop's page) nothing runs off the edge.
    ImGui::PushItemWidth(-ImGui::CalcTextSize("light 0 intensity").x -
                         ImGui::GetStyle().ItemInnerSpacing.x);
    ImGui::PushTextWrapPos(0);
    drawParams(lab, state, requests);
    ImGui::Separator();
    drawScenePanel(lab, state, requests);
    ImGui::PopTextWrapPos();
    ImGui::PopItemWidth();
}

}  // namespace pbrlab
