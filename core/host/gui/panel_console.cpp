// The Console tab: the console's output and a line to type commands into (console.h).
#include <imgui.h>

#include "panels.h"

namespace pbrlab {

namespace {

// Up and down recall the lines typed before.
int recallHistory(ImGuiInputTextCallbackData* data) {
    Console& console = *static_cast<Console*>(data->UserData);
    if (console.history.empty()) return 0;
    int& i = console.historyIndex;
    const int last = int(console.history.size()) - 1;
    if (data->EventKey == ImGuiKey_UpArrow) i = i < 0 ? last : std::max(0, i - 1);
    if (data->EventKey == ImGuiKey_DownArrow) i = i < 0 || i >= last ? -1 : i + 1;
    data->DeleteChars(0, data->BufTextLen);
    if (i >= 0) data->InsertChars(0, console.history[size_t(i)].c_str());
    return 0;
}

}  // namespace

void drawConsoleTab(const Lab& lab, Console& console) {
    const float inputHeight = ImGui::GetFrameHeightWithSpacing() * 2;
    ImGui::BeginChild("console output", ImVec2(0, -inputHeight), true);
    const std::string text = console.text();
    if (text.empty()) {
        ImGui::PushTextWrapPos(0);
        ImGui::TextDisabled(
            "The shell's commands run here as `pbrlab ...` would (`check ndf`, `render ndf "
            "--out x.png`); `step`, `set`, `scene` and `view` change the lab. `help` lists "
            "them all.");
        if (lab.submission().empty())
            ImGui::TextDisabled("No workspace is open: commands use the reference solutions.");
        else
            ImGui::TextDisabled(
                "Commands that take --submission (check, render, stability, gallery, grade) "
                "work on the workspace, %s, unless the line gives one (--submission '' for the "
                "reference solutions).",
                lab.submission().string().c_str());
        ImGui::PopTextWrapPos();
    }
    ImGui::PushTextWrapPos(0);
    ImGui::TextUnformatted(text.data(), text.data() + text.size());
    ImGui::PopTextWrapPos();
    if (text.size() != console.shownSize) {  // new output: follow it
        ImGui::SetScrollHereY(1.0f);
        console.shownSize = text.size();
    }
    ImGui::EndChild();
    ImGui::SetNextItemWidth(-1);
    const ImGuiInputTextFlags flags =
        ImGuiInputTextFlags_EnterReturnsTrue | ImGuiInputTextFlags_CallbackHistory;
    const char* hint = lab.submission().empty() ? "a command, e.g. check ndf"
                                                : "a command, e.g. check ndf (your workspace's)";
    if (ImGui::InputTextWithHint("##line", hint, console.input.data(), console.input.size(), flags,
                                 recallHistory, &console)) {
        const std::string line = console.input.data();
        if (!line.empty()) {
            console.submit(line);
            console.history.push_back(line);
        }
        console.historyIndex = -1;
        console.input.fill(0);
        ImGui::SetKeyboardFocusHere(-1);  // keep typing
    }
    if (console.running())
        ImGui::TextDisabled("running ... (the lab stays usable)");
    else
        ImGui::TextDisabled("enter: run   up/down: earlier lines");
}

}  // namespace pbrlab
