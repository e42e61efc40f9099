// normalmap: a tangent-space normal-map texel turned into a world-space normal
// through the TBN frame (T made perpendicular to N, B = N x T times the handedness).
#include "pbrlab/module.h"

#include <cmath>

using namespace pbrlab;

namespace {

constexpr int kPanel = 33;              // texel columns (and rows) per handedness panel
constexpr int kWidth = 2 * kPanel + 1;  // two panels and a background column between
constexpr int kHeight = kPanel;

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Normal mapping through the TBN frame";
    d.components = 3;
    d.nonNegative = false;
    d.display = {DisplayMode::SignedVector, -1, 1};
    d.needs = NeedsNormalMap;
    // Band: +- 1e-3 of each component, at least 1e-6, or the spread of 8 ulps of the inputs
    // (README.md).
    d.tolerance = {1e-6, 1e-3, 8};
    // N anywhere; a tangent at least 25 degrees away from N and not perpendicular to it (the
    // function makes it so), either handedness; the texel of a unit normal within 70 degrees
    // of the surface's, stored in 8 bits as normal maps are.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        const glm::dvec3 t = r.around(s.normal, -0.9, 0.9);
        s.tangent = {t, r.uniform() < 0.5 ? -1 : 1};
        const glm::dvec3 n = r.around({0, 0, 1}, 0.35, 1);
        s.normalTexel = glm::round((n * 0.5 + 0.5) * 255.0) / 255.0;
        return s;
    };
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return ref::normalFromMap(s.normal, s.tangent, s.normalTexel);
    };
    // Two panels, handedness +1 (left) and -1 (right); in each, x and y are the texel's red
    // and green from 0 to 1, blue is what a unit normal stores (0.5 + 0.5 sqrt(1 - x'^2 -
    // y'^2), x' = 2 r - 1; 0.5 beyond the unit disc). The frame is tilted (N away from +z, a
    // tangent not perpendicular to it) so that tangent and world space differ.
    d.probe.xAxis = "texel red 0..1 (left: handedness +1, right: -1)";
    d.probe.yAxis = "texel green 0..1";
    d.probe.width = kWidth;
    d.probe.height = kHeight;
    d.probe.at = [](double x, double y) {
        const int column = int(std::lround(x * (kWidth - 1)));
        Surface s;
        if (column == kPanel) return s;  // the gap between the panels
        const bool mirrored = column > kPanel;
        const double r = double(mirrored ? column - kPanel - 1 : column) / (kPanel - 1);
        const double nx = 2 * r - 1, ny = 2 * y - 1;
        s.covered = true;
        s.normal = glm::normalize(glm::dvec3(0.3, -0.2, 1));
        s.tangent = {glm::normalize(glm::dvec3(1, 0.4, 0)), mirrored ? -1 : 1};
        s.normalTexel = {r, y, 0.5 + 0.5 * std::sqrt(std::max(1 - nx * nx - ny * ny, 0.0))};
        return s;
    };
    d.termViews = {{"mapped normal", TermView::Encode::None, [](const Surface& s) {
                        return 0.5 + 0.5 * ref::normalFromMap(s.normal, s.tangent, s.normalTexel);
                    }}};
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
