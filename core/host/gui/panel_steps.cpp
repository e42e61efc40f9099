// The steps panel: the workspace, each lab's steps with their badges, previous / next.
#include <imgui.h>

#include <cstdio>

#include "panels.h"

namespace pbrlab {

namespace {

ImVec4 badgeColor(Status s) {
    switch (s) {
        case Status::Passes:
            return {0.35f, 0.85f, 0.4f, 1};
        case Status::Fails:
            return {1.0f, 0.55f, 0.2f, 1};
        case Status::CompileError:
            return {1.0f, 0.3f, 0.3f, 1};
        default:
            return {0.6f, 0.6f, 0.6f, 1};
    }
}

void badgeLabel(const Lab& lab, const ModuleDesc& d) {
    const Status s = lab.badges().of(d.id).status;
    ImGui::TextColored(badgeColor(s), "%s", badgeText(s));
}

}  // namespace

// The steps in one line, for a window too narrow for the steps panel: the step on screen and
// its badge, the list (with every badge) a click away, previous / next.
void drawStepsLine(const Lab& lab, GuiState& state, Requests& requests) {
    const auto& ms = lab.registry().modules();
    const ModuleDesc& on = lab.module(state);
    char label[128];
    std::snprintf(label, sizeof label, "%d  %s", on.step, on.id.c_str());
    if (ImGui::ArrowButton("previous", ImGuiDir_Left))
        requests.selectStep = std::max(0, state.step - 1);
    ImGui::SameLine(0, 2);
    ImGui::SetNextItemWidth(150);
    if (ImGui::BeginCombo("##step", label, ImGuiComboFlags_HeightLarge)) {
        std::string labName;
        for (size_t i = 0; i < ms.size(); ++i) {
            const ModuleDesc& d = *ms[i].desc;
            if (d.lab != labName) {
                labName = d.lab;
                ImGui::TextColored(ImVec4(1, 0.8f, 0.45f, 1), "lab: %s", labName.c_str());
            }
            ImGui::PushID(int(i));
            std::snprintf(label, sizeof label, "%2d  %s", d.step, d.id.c_str());
            if (ImGui::Selectable(label, int(i) == state.step, 0, ImVec2(130, 0)))
                requests.selectStep = int(i);
            ImGui::SameLine(150);
            badgeLabel(lab, d);
            ImGui::PopID();
        }
        if (!lab.shown().messages.empty()) {
            ImGui::Separator();
            ImGui::TextWrapped("%s", lab.shown().messages.c_str());
        }
        ImGui::EndCombo();
    }
    ImGui::SameLine(0, 2);
    if (ImGui::ArrowButton("next", ImGuiDir_Right)) requests.selectStep = state.step + 1;
    ImGui::SameLine();
    badgeLabel(lab, on);
}

void drawStepsPanel(const Lab& lab, GuiState& state, Requests& requests) {
    ImGui::TextDisabled("workspace");
    ImGui::TextWrapped("%s", lab.submission().empty() ? "(no student folder: solutions only)"
                                                      : lab.submission().string().c_str());
    ImGui::Separator();
    std::string labName;
    const auto& ms = lab.registry().modules();
    for (size_t i = 0; i < ms.size(); ++i) {
        const ModuleDesc& d = *ms[i].desc;
        if (d.lab != labName) {
            labName = d.lab;
            ImGui::Spacing();
            ImGui::TextColored(ImVec4(1, 0.8f, 0.45f, 1), "lab: %s", labName.c_str());
        }
        ImGui::PushID(int(i));
        char label[128];
        std::snprintf(label, sizeof label, "%2d  %s", d.step, d.id.c_str());
        if (ImGui::Selectable(label, int(i) == state.step, 0, ImVec2(130, 0)))
            requests.selectStep = int(i);
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("%s\n%s", d.title.c_str(), d.function.c_str());
        ImGui::SameLine(150);
        Status s = lab.badges().of(d.id).status;
        ImGui::TextColored(badgeColor(s), "%s", badgeText(s));
        ImGui::PopID();
    }
    ImGui::Spacing();
    ImGui::Separator();
    // select() clamps to the first and the last step.
    if (ImGui::Button("< previous")) requests.selectStep = std::max(0, state.step - 1);
    ImGui::SameLine();
    if (ImGui::Button("next >")) requests.selectStep = state.step + 1;
    const std::string& messages = lab.shown().messages;
    if (!messages.empty()) {
        ImGui::Separator();
        ImGui::TextWrapped("%s", messages.c_str());
    }
}

}  // namespace pbrlab
