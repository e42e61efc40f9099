// The side tabs under the parameters: Handout, Plot, Log, Programs and Console.
#include <imgui.h>

#include <sstream>

#include "handout.h"
#include "panels.h"
#include "util/log.h"
#include "view_status.h"

namespace pbrlab {

void drawSideTabs(const Lab& lab, GuiState& state, SideTabsMemory& memory, Console& console) {
    if (!ImGui::BeginTabBar("tabs")) return;
    // --tab opens one tab on the first frame; after that the student's clicks decide.
    auto opened = [&](const char* tab) {
        return state.openTab == tab ? ImGuiTabItemFlags_SetSelected : 0;
    };
    if (ImGui::BeginTabItem("Handout", nullptr, opened("handout"))) {
        ImGui::BeginChild("handout");
        drawHandout(lab.shown().handout);
        ImGui::EndChild();
        ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Plot", nullptr, opened("plot"))) {
        drawPlotTab(lab, state);
        ImGui::EndTabItem();
    }
    // A new compile error selects the Log tab once.
    const std::string& compileLog = lab.shown().compileLog;
    ImGuiTabItemFlags logFlags = compileLog.empty() ? 0 : ImGuiTabItemFlags_SetSelected;
    if (compileLog != memory.shownLog)
        memory.shownLog = compileLog;
    else
        logFlags = 0;
    if (ImGui::BeginTabItem(compileLog.empty() ? "Log###log" : "Log (error)###log", nullptr,
                            logFlags | opened("log"))) {
        drawLogTab(lab, state);
        ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Programs", nullptr, opened("programs"))) {
        ImGui::BeginChild("programs");
        drawProgramsTab(lab);
        ImGui::EndChild();
        ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Console", nullptr, opened("console"))) {
        drawConsoleTab(lab, console);
        ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
    state.openTab.clear();
}

void drawLogTab(const Lab& lab, const GuiState& state) {
    const std::string& compileLog = lab.shown().compileLog;
    if (compileLog.empty()) {
        ImGui::TextDisabled("no errors");
    } else {
        ImGui::PushTextWrapPos(0);
        ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", viewStatus(lab, state).error.c_str());
        ImGui::PopTextWrapPos();
        ImGui::TextDisabled("click a line to copy it");
        std::istringstream in(compileLog);
        std::string line;
        int n = 0;
        while (std::getline(in, line)) {
            ImGui::PushID(n++);
            if (ImGui::Selectable(line.c_str())) ImGui::SetClipboardText(line.c_str());
            ImGui::PopID();
        }
    }
    ImGui::Separator();
    ImGui::TextDisabled("host log");
    ImGui::TextWrapped("%s", journal().c_str());
}

// Every program compiled so far (the cache compiles each recipe once per define set, so a
// scene with texture maps or more lights adds programs), with the ones the step uses for the
// scene on screen listed on top and highlighted; then what else the GPU had to do.
void drawProgramsTab(const Lab& lab) {
    const auto& permutation = lab.shown().permutation;
    const ImVec4 used(1, 0.8f, 0.45f, 1);
    ImGui::TextDisabled("this step on this scene uses (highlighted below):");
    for (const auto& [label, defines] : permutation) {
        ImGui::TextColored(used, "%s", label.c_str());
        ImGui::SameLine();
        ImGui::TextWrapped("%s", defines.empty() ? "(no defines)" : defines.c_str());
    }
    ImGui::Spacing();
    // The window's renderer (live pictures) and the evaluation thread's each compile what they
    // draw: the window's first, in order, then the evaluation's.
    std::vector<CompiledProgram> compiled = lab.renderer().programs().compiled();
    compiled.insert(compiled.end(), lab.evaluationPrograms().begin(),
                    lab.evaluationPrograms().end());
    ImGui::TextDisabled(
        "%zu programs compiled, in order, the window's then the evaluation's (a hot reload "
        "compiles again):",
        compiled.size());
    const ImGuiTableFlags flags =
        ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingFixedFit;
    if (ImGui::BeginTable("compiled", 2, flags)) {
        // Two columns, the compile time under the label: the side panel is narrow, and a
        // third column would break the longest define (HAS_METALLIC_ROUGHNESS_MAP=1) or label
        // word (equirect_to_cube) in the middle.
        ImGui::TableSetupColumn("program, compile", ImGuiTableColumnFlags_WidthFixed, 132);
        ImGui::TableSetupColumn("defines", ImGuiTableColumnFlags_WidthStretch);
        ImGui::TableHeadersRow();
        for (const CompiledProgram& p : compiled) {
            ImGui::TableNextRow();
            bool isUsed = permutation.count({p.label, p.defines}) > 0;
            if (isUsed)
                ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg0, IM_COL32(60, 52, 30, 255));
            ImGui::TableNextColumn();
            ImGui::PushStyleColor(ImGuiCol_Text,
                                  isUsed ? used : ImGui::GetStyleColorVec4(ImGuiCol_Text));
            ImGui::TextWrapped("%s", p.label.c_str());
            ImGui::PopStyleColor();
            ImGui::TextDisabled("%.1f ms", p.milliseconds);
            ImGui::TableNextColumn();
            ImGui::TextWrapped("%s", p.defines.empty() ? "-" : p.defines.c_str());
        }
        ImGui::EndTable();
    }
    ImGui::Spacing();
    ImGui::Text("textures loaded: %d   precompute passes: %d", eventCount(Counter::TextureLoads),
                eventCount(Counter::PrecomputePasses));
    // The journal's lines for that work, with sizes and times.
    std::istringstream in(journal());
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("[texture]", 0) == 0 || line.rfind("[precompute]", 0) == 0)
            ImGui::TextWrapped("%s", line.c_str());
}

}  // namespace pbrlab
