// The Plot tab: one row of the step's probe, as curves, or as a lobe in the plane of incidence
// when the probe's x is the light's angle.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "panels.h"

namespace pbrlab {

namespace {

const ImU32 kComponentColors[3] = {IM_COL32(255, 110, 90, 255), IM_COL32(110, 230, 120, 255),
                                   IM_COL32(110, 160, 255, 255)};

// The probe row as a lobe in the plane of incidence: the light's direction at each angle from
// N, its length the value (scaled to the row's largest). N points up, V and the mirror
// direction R are drawn, so students see the lobe lean towards R and widen with roughness.
void drawPolarLobe(const Lab& lab, const GuiState& state, ImDrawList* dl, ImVec2 p, ImVec2 size,
                   bool haveStudent) {
    const ModuleDesc& d = lab.module(state);
    const Probe& probe = d.probe;
    const Image& probeSolution = lab.shown().probeSolution;
    const Image& probeStudent = lab.shown().probeStudent;
    const ImVec2 centre(p.x + size.x * 0.5f, p.y + size.y - 18);
    const float radius = std::min(size.x * 0.5f, size.y - 26) - 6;
    auto at = [&](double degrees, double length) {
        const double a = glm::radians(degrees);
        return ImVec2(centre.x + float(std::sin(a) * length) * radius,
                      centre.y - float(std::cos(a) * length) * radius);
    };
    const ImU32 grid = IM_COL32(70, 74, 84, 255), label = IM_COL32(200, 200, 200, 255);
    for (double ring : {0.5, 1.0}) {
        std::vector<ImVec2> arc;
        for (int i = 0; i <= 64; ++i) arc.push_back(at(-90 + 180.0 * i / 64, ring));
        dl->AddPolyline(arc.data(), int(arc.size()), grid, 0, 1.0f);
    }
    dl->AddLine(at(-90, 1), at(90, 1), grid);  // the surface
    const struct {
        double degrees;
        const char* name;
    } rays[] = {{0, "N"}, {probe.viewAngle, "V"}, {-probe.viewAngle, "R"}};
    for (const auto& r : rays) {
        dl->AddLine(centre, at(r.degrees, 1.0), grid, 1.5f);
        dl->AddText(at(r.degrees, 1.06), label, r.name);
    }
    auto degreesAt = [&](int x) { return -90 + 180.0 * x / (probe.width - 1); };
    auto valueAt = [&](const Image& im, int x, int c) {
        double v = im.at(x, state.plotRow, c);
        return state.polarTimesCosine ? v * std::cos(glm::radians(degreesAt(x))) : v;
    };
    double hi = 0;
    for (int x = 0; x < probe.width; ++x)
        for (int c = 0; c < d.components; ++c)
            for (const Image* im : {&probeSolution, haveStudent ? &probeStudent : &probeSolution}) {
                double v = valueAt(*im, x, c);
                if (std::isfinite(v)) hi = std::max(hi, v);
            }
    if (!(hi > 0)) hi = 1;
    auto lobe = [&](const Image& im, int c) {
        std::vector<ImVec2> points;
        for (int x = 0; x < probe.width; ++x) {
            double v = valueAt(im, x, c);
            points.push_back(at(degreesAt(x), std::isfinite(v) ? std::max(v, 0.0) / hi : 0));
        }
        return points;
    };
    for (int c = 0; c < d.components; ++c) {
        auto solution = lobe(probeSolution, c);
        ImU32 col = d.components == 1 ? IM_COL32(255, 210, 90, 255) : kComponentColors[c];
        dl->AddPolyline(solution.data(), int(solution.size()), col, 0, 3.0f);
        if (haveStudent) {
            auto student = lobe(probeStudent, c);
            dl->AddPolyline(student.data(), int(student.size()), IM_COL32(255, 255, 255, 200), 0,
                            1.2f);
        }
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "outer ring: %.3g", hi);
    dl->AddText(ImVec2(p.x + 4, p.y + 2), label, buf);
    ImGui::TextDisabled("thick: solution%s; length: value at that light direction",
                        haveStudent ? ", thin white: your function" : "");
}

}  // namespace

void drawPlotTab(const Lab& lab, GuiState& state) {
    const ModuleDesc& d = lab.module(state);
    const Probe& probe = d.probe;
    const Image& probeSolution = lab.shown().probeSolution;
    const Image& probeStudent = lab.shown().probeStudent;
    if (probeSolution.pixels.empty()) return;
    ImGui::TextWrapped("The function along one row of the probe: x = %s; the row picks y = %s.",
                       probe.xAxis.c_str(), probe.yAxis.c_str());
    ImGui::SliderInt("row", &state.plotRow, 0, probe.height - 1);
    state.plotRow = std::clamp(state.plotRow, 0, probe.height - 1);
    ImGui::TextDisabled("y = %.3f (of 0..1)", 1.0 - double(state.plotRow) / (probe.height - 1));
    if (probe.xIsLightAngle) {
        ImGui::SameLine();
        ImGui::Checkbox("polar", &state.polarPlot);
        if (state.polarPlot) {
            ImGui::SameLine();
            // The BRDF alone grows towards grazing; times the cosine it is the light actually
            // reflected, the lobe textbooks draw.
            ImGui::Checkbox("× N·L", &state.polarTimesCosine);
        }
    }
    ImVec2 p = ImGui::GetCursorScreenPos();
    ImVec2 size(ImGui::GetContentRegionAvail().x, 260);
    ImGui::InvisibleButton("plot", size);
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(p, ImVec2(p.x + size.x, p.y + size.y), IM_COL32(25, 27, 32, 255));
    bool haveStudent =
        !lab.shown().studentValue.pixels.empty() && probeStudent.width == probeSolution.width;
    if (probe.xIsLightAngle && state.polarPlot) {
        drawPolarLobe(lab, state, dl, p, size, haveStudent);
        return;
    }
    double lo = 1e300, hi = -1e300;
    auto valueAt = [&](const Image& im, int x, int c) {
        return double(im.at(x, state.plotRow, c));
    };
    for (int x = 0; x < probe.width; ++x)
        for (int c = 0; c < d.components; ++c)
            for (const Image* im : {&probeSolution, haveStudent ? &probeStudent : &probeSolution}) {
                double v = valueAt(*im, x, c);
                if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
            }
    if (!(hi > lo)) hi = lo + 1;
    auto point = [&](int x, double v) {
        return ImVec2(p.x + size.x * float(x) / float(probe.width - 1),
                      p.y + size.y - size.y * float((v - lo) / (hi - lo)));
    };
    for (int c = 0; c < d.components; ++c) {
        std::vector<ImVec2> solution, student;
        for (int x = 0; x < probe.width; ++x) {
            solution.push_back(point(x, valueAt(probeSolution, x, c)));
            if (haveStudent) student.push_back(point(x, valueAt(probeStudent, x, c)));
        }
        ImU32 col = d.components == 1 ? IM_COL32(255, 210, 90, 255) : kComponentColors[c];
        dl->AddPolyline(solution.data(), int(solution.size()), col, 0, 3.0f);
        if (haveStudent)
            dl->AddPolyline(student.data(), int(student.size()), IM_COL32(255, 255, 255, 200), 0,
                            1.2f);
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g", hi);
    dl->AddText(ImVec2(p.x + 4, p.y + 2), IM_COL32(200, 200, 200, 255), buf);
    std::snprintf(buf, sizeof buf, "%.3g", lo);
    dl->AddText(ImVec2(p.x + 4, p.y + size.y - 16), IM_COL32(200, 200, 200, 255), buf);
    ImGui::TextDisabled("thick: solution%s", haveStudent ? ", thin white: your function" : "");
}

}  // namespace pbrlab
