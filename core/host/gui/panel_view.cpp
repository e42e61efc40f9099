// The view panel: title, the view chooser and its settings, the picture with the orbit camera
// and the pixel inspector, the legend, and the statistics line.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "panels.h"
#include "render/display.h"
#include "term_views.h"
#include "view_status.h"

namespace pbrlab {

namespace {

void viewChooser(const Lab& lab, GuiState& state, Requests& requests) {
    const std::vector<TermView>& terms = lab.termViews();
    ImGui::SetNextItemWidth(150);
    if (ImGui::BeginCombo("view", viewName(state.view, state.term, terms).c_str())) {
        for (View v : kImageViews)
            if (ImGui::Selectable(viewName(v, 0).c_str(), state.view == v)) {
                state.view = v;
                requests.recompose = requests.viewChosen = true;
            }
        ImGui::Separator();
        for (size_t i = 0; i < terms.size(); ++i)
            if (ImGui::Selectable(terms[i].name.c_str(),
                                  state.view == View::Term && state.term == int(i))) {
                state.view = View::Term;
                state.term = int(i);
                requests.recompose = requests.viewChosen = true;
            }
        ImGui::EndCombo();
    }
    // The student's picture and the solution's, one click apart (either, from any other view).
    ImGui::SameLine();
    const bool solution = state.view == View::Solution;
    const ImVec2 at = ImGui::GetCursorScreenPos();
    if (ImGui::Button(solution ? "show yours" : "show the solution")) {
        state.view = solution ? View::Student : View::Solution;
        requests.recompose = requests.viewChosen = true;
    }
    const ImVec2 size = ImGui::GetItemRectSize();
    state.layout.viewToggle = {at.x, at.y, size.x, size.y};
}

// Drag: orbit; wheel: zoom; hover: the pixel inspector, on the settled picture. The picture is
// an invisible button drawn over the image, so that a drag that began on it goes on orbiting
// when the pointer leaves it (an image is no item: the orbit stopped at its edge, and the
// evaluation ran while the student was still dragging).
void handleCamera(const Lab& lab, GuiState& state, Requests& requests, ImVec2 origin, float side) {
    ImGuiIO& io = ImGui::GetIO();
    OrbitCamera& camera = state.camera;
    // (Held still, the drag has not moved: Requests::holding says it is held.)
    if (ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left) &&
        (io.MouseDelta.x != 0 || io.MouseDelta.y != 0)) {
        camera.yaw -= io.MouseDelta.x * 0.01;
        camera.pitch = std::clamp(camera.pitch + io.MouseDelta.y * 0.01, -1.5, 1.5);
        requests.moved = true;
    }
    if (!ImGui::IsItemHovered()) return;
    if (io.MouseWheel != 0) {
        camera.distance = std::clamp(camera.distance * std::pow(0.9, io.MouseWheel), 1.2, 200.0);
        requests.moved = true;
    }
    const Shown& shown = lab.shown();
    int x = int((io.MousePos.x - origin.x) / side * shown.imageWidth);
    int y = int((io.MousePos.y - origin.y) / side * shown.imageHeight);
    if (x < 0 || y < 0 || x >= shown.imageWidth || y >= shown.imageHeight ||
        shown.solutionValue.pixels.empty() || shown.liveTexture)
        return;
    size_t i = size_t(y) * shown.solutionValue.width + x;
    const std::vector<Surface>& surfaces = *shown.surfaces;
    if (i >= surfaces.size() || !surfaces[i].covered) return;
    const Surface& s = surfaces[i];
    auto value = [&](const Image& im) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "%.6g %.6g %.6g", im.pixels[i * 4], im.pixels[i * 4 + 1],
                      im.pixels[i * 4 + 2]);
        return std::string(buf);
    };
    ImGui::BeginTooltip();
    ImGui::Text("pixel (%d, %d)", x, y);
    if (!shown.studentValue.pixels.empty())
        ImGui::Text("student   %s", value(shown.studentValue).c_str());
    ImGui::Text("solution  %s", value(shown.solutionValue).c_str());
    ImGui::Text("reference %s", value(shown.referenceValue).c_str());
    ImGui::Separator();
    ImGui::Text("N (%.3f %.3f %.3f)  N.V %.3f  N.L %.3f", s.normal.x, s.normal.y, s.normal.z,
                glm::dot(s.normal, s.view), glm::dot(s.normal, s.light));
    ImGui::Text("roughness %.3f  metallic %.3f  ao %.3f", s.roughness, s.metallic, s.ao);
    ImGui::EndTooltip();
}

// The legend's labels: the top value, the bottom one (with "log" on a log scale).
struct LegendLabels {
    char top[32], bottom[32];
    LegendLabels(double lo, double hi, bool logScale) {
        std::snprintf(top, sizeof top, "%.2g", hi);
        std::snprintf(bottom, sizeof bottom, "%.2g%s", lo, logScale ? " log" : "");
    }
    // The width beside the picture: the bar, or the wider label (a narrow window cut "1e+02").
    float width() const {
        return std::max({28.0f, ImGui::CalcTextSize(top).x, ImGui::CalcTextSize(bottom).x});
    }
};

void drawLegend(const LegendLabels& labels, float height) {
    ImVec2 p = ImGui::GetCursorScreenPos();
    ImDrawList* dl = ImGui::GetWindowDrawList();
    const int steps = 64;
    for (int i = 0; i < steps; ++i) {
        glm::dvec3 c = falseColor(1.0 - (i + 0.5) / steps);
        float y0 = p.y + height * i / steps, y1 = p.y + height * (i + 1) / steps;
        dl->AddRectFilled(ImVec2(p.x, y0), ImVec2(p.x + 14, y1),
                          IM_COL32(int(c.r * 255), int(c.g * 255), int(c.b * 255), 255));
    }
    dl->AddText(ImVec2(p.x - 2, p.y - 14), IM_COL32(220, 220, 220, 255), labels.top);
    dl->AddText(ImVec2(p.x - 2, p.y + height + 1), IM_COL32(220, 220, 220, 255), labels.bottom);
    ImGui::Dummy(ImVec2(labels.width(), height));
}

// The statistics under the picture; with a compile error, they say that they are of the last
// program that compiled. Wrapped: a narrow window cuts nothing. The grade's message is its
// first sentence (what is wrong), the details folded under it.
void drawStats(const ViewStatus& status) {
    ImGui::PushTextWrapPos(0);
    if (status.lastGood)
        ImGui::TextColored(ImVec4(1, 0.6f, 0.35f, 1), "%s", status.statsHeading.c_str());
    else
        ImGui::TextDisabled("%s", status.statsHeading.c_str());
    // Outside the band with the solution outside it too: the band cannot judge here (amber,
    // not the red of a file that fails), and the note under the rows says why.
    const ImVec4 green(0.4f, 0.9f, 0.45f, 1), red(1, 0.5f, 0.3f, 1), amber(0.95f, 0.8f, 0.35f, 1);
    for (const ViewStatus::Row& row : status.rows)
        ImGui::TextColored(row.ok                    ? green
                           : status.bandNote.empty() ? red
                                                     : amber,
                           "%s", row.text.c_str());
    if (!status.bandNote.empty()) ImGui::TextColored(amber, "%s", status.bandNote.c_str());
    if (!status.grade.empty()) {
        ImGui::TextUnformatted(status.grade.c_str());
        if (!status.gradeDetails.empty() && ImGui::TreeNode("details")) {
            ImGui::TextUnformatted(status.gradeDetails.c_str());
            ImGui::TreePop();
        }
    }
    ImGui::PopTextWrapPos();
}

// The student's compile error, above the picture until the file compiles again: what the
// picture is, then the compiler's text (file:line), scrolled when long; a click copies a line.
void drawCompileError(const ViewStatus& status) {
    const ImVec4 red(1, 0.4f, 0.4f, 1);
    const ImGuiStyle& style = ImGui::GetStyle();
    const float wrap = ImGui::GetContentRegionAvail().x - 2 * style.WindowPadding.x;
    // The log's lines wrapped (a long one would run off a narrow window), up to 6 lines'
    // height (then it scrolls).
    float logHeight = 0;
    for (size_t start = 0; start < status.errorLog.size();) {
        size_t end = status.errorLog.find('\n', start);
        if (end == std::string::npos) end = status.errorLog.size();
        logHeight += ImGui::CalcTextSize(status.errorLog.c_str() + start,
                                         status.errorLog.c_str() + end, false, wrap)
                         .y +
                     style.ItemSpacing.y;
        start = end + 1;
    }
    const float height = ImGui::CalcTextSize(status.error.c_str(), nullptr, false, wrap).y +
                         std::min(logHeight, 6 * ImGui::GetTextLineHeightWithSpacing()) +
                         style.ItemSpacing.y + style.WindowPadding.y * 2;
    ImGui::PushStyleColor(ImGuiCol_Border, red);
    ImGui::PushStyleColor(ImGuiCol_ChildBg, ImVec4(0.25f, 0.08f, 0.08f, 1));
    ImGui::BeginChild("compile error", ImVec2(0, height), true);
    ImGui::PushStyleColor(ImGuiCol_Text, red);
    ImGui::TextWrapped("%s", status.error.c_str());
    ImGui::PopStyleColor();
    size_t start = 0;
    for (int n = 0; start < status.errorLog.size(); ++n) {
        size_t end = status.errorLog.find('\n', start);
        if (end == std::string::npos) end = status.errorLog.size();
        const std::string line = status.errorLog.substr(start, end - start);
        start = end + 1;
        ImGui::PushID(n);
        ImGui::PushTextWrapPos(0);
        ImGui::TextUnformatted(line.c_str());
        ImGui::PopTextWrapPos();
        if (ImGui::IsItemHovered()) {
            ImGui::GetWindowDrawList()->AddRectFilled(
                ImGui::GetItemRectMin(), ImGui::GetItemRectMax(),
                ImGui::GetColorU32(ImGuiCol_HeaderHovered, 0.4f));
            ImGui::SetTooltip("click to copy the line");
        }
        if (ImGui::IsItemClicked()) ImGui::SetClipboardText(line.c_str());
        ImGui::PopID();
    }
    ImGui::EndChild();
    ImGui::PopStyleColor(2);
}

// The view's line: the view chosen, its slider (difference, split), the screenshot button and
// the frame's times where they fit.
void viewToolbar(const Lab& lab, GuiState& state, Requests& requests) {
    const Shown& shown = lab.shown();
    viewChooser(lab, state, requests);
    if (state.view == View::Difference) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(160);
        if (ImGui::SliderFloat("range", &state.differenceRange, 1e-6f, 1.0f, "%.1e",
                               ImGuiSliderFlags_Logarithmic))
            requests.recompose = true;
    }
    if (state.view == View::Split) {
        ImGui::SameLine();
        ImGui::SetNextItemWidth(160);
        if (ImGui::SliderFloat("split", &state.split, 0, 1)) requests.recompose = true;
    }
    ImGui::SameLine();
    if (ImGui::Button("screenshot")) requests.screenshot = true;
    // The frame's times where they fit (not in a narrow window beside a range slider).
    char times[64];
    std::snprintf(times, sizeof times, "frame %.1f ms, render %.0f ms", shown.frameMs,
                  shown.renderMs);
    const float room = ImGui::GetWindowPos().x + ImGui::GetWindowContentRegionMax().x -
                       ImGui::GetItemRectMax().x - ImGui::GetStyle().ItemSpacing.x;
    if (room >= ImGui::CalcTextSize(times).x) {
        ImGui::SameLine();
        ImGui::TextDisabled("%s", times);
    }
}

// Why the picture is not what the step's file should give: a compile error, a notice, a
// render error, NaN and Inf pixels.
void viewNotes(const Shown& shown, const ViewStatus& status) {
    if (!status.error.empty()) drawCompileError(status);
    if (!status.notice.empty())
        ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "%s", status.notice.c_str());
    if (!shown.renderError.empty())
        ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%s", shown.renderError.c_str());
    if (shown.nanCount + shown.infCount > 0)
        ImGui::TextColored(ImVec4(1, 0.3f, 1, 1),
                           "%d NaN pixels (magenta), %d Inf pixels (cyan) in the student image",
                           shown.nanCount, shown.infCount);
}

// The picture at the largest side that fits, the camera's drag on it, and its legend.
void viewPicture(const Lab& lab, GuiState& state, Requests& requests) {
    const ModuleDesc& d = lab.module(state);
    const Shown& shown = lab.shown();
    const bool difference = state.view == View::Difference;
    const LegendLabels labels(difference ? 0.0 : d.display.lo,
                              difference ? state.differenceRange : d.display.hi,
                              !difference && d.display.logScale);
    const float legend =
        (difference || d.display.mode == DisplayMode::FalseColor) ? labels.width() : 0;
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    float side = std::max(64.0f, std::min(avail.x - legend, avail.y - 150));
    state.layout.pictureSide = side;
    ImVec2 origin = ImGui::GetCursorScreenPos();
    state.layout.pictureOrigin = {origin.x, origin.y};
    const GLuint shownTexture = shown.liveTexture ? shown.liveTexture : shown.imageTexture.id();
    ImGui::InvisibleButton("picture", ImVec2(side, side));
    ImGui::GetWindowDrawList()->AddImage(
        reinterpret_cast<ImTextureID>(static_cast<intptr_t>(shownTexture)), origin,
        ImVec2(origin.x + side, origin.y + side));
    handleCamera(lab, state, requests, origin, side);
    // Beside the picture (before the line under it, which would push it down).
    if (legend > 0) {
        ImGui::SameLine();
        drawLegend(labels, side);
    }
}

// The line under a live picture: whose it is, its size, and what follows when the input stops
// (or, stopped, when the evaluation under it arrives: its progress is the line below).
void liveLine(const Lab& lab, const GuiState& state) {
    const Shown& shown = lab.shown();
    if (shown.liveWaitsForMaps)
        ImGui::TextDisabled("moving: the picture follows when the environment's maps arrive");
    else if (shown.liveTexture && lab.evaluating())
        ImGui::TextDisabled("%s picture at %dx%d; the %s view, %dx%d, when evaluated",
                            shown.liveWho, shown.liveSide, shown.liveSide,
                            viewName(state.view, state.term, lab.termViews()).c_str(), kRenderSize,
                            kRenderSize);
    else if (shown.liveTexture && state.view != View::Student && state.view != View::Solution)
        ImGui::TextDisabled("moving: %s picture at %dx%d; the %s view, %dx%d, when you stop",
                            shown.liveWho, shown.liveSide, shown.liveSide,
                            viewName(state.view, state.term, lab.termViews()).c_str(), kRenderSize,
                            kRenderSize);
    else if (shown.liveTexture && shown.liveSide < kRenderSize)
        ImGui::TextDisabled("moving: %s picture at %dx%d; %dx%d when you stop", shown.liveWho,
                            shown.liveSide, shown.liveSide, kRenderSize, kRenderSize);
    else if (shown.liveTexture)
        ImGui::TextDisabled("moving: %s picture at %dx%d, full size", shown.liveWho, shown.liveSide,
                            shown.liveSide);
}

}  // namespace

void drawViewPanel(const Lab& lab, GuiState& state, Requests& requests) {
    const ModuleDesc& d = lab.module(state);
    if (state.layout.compact) ImGui::SameLine();  // after the steps' line (drawStepsLine)
    ImGui::PushTextWrapPos(0);
    ImGui::Text("%d. %s", d.step, d.title.c_str());
    ImGui::TextDisabled("%s", d.function.c_str());
    ImGui::PopTextWrapPos();
    viewToolbar(lab, state, requests);
    const ViewStatus status = viewStatus(lab, state);
    viewNotes(lab.shown(), status);
    viewPicture(lab, state, requests);
    liveLine(lab, state);
    drawStats(status);
}

}  // namespace pbrlab
