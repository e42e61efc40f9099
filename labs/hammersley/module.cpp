// hammersley: the Hammersley point set (i / n, radical inverse of i).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "pbrlab/ibl_reference.h"

using namespace pbrlab;

namespace {

constexpr int kMaxPoints = 1024;  // the view's cap on n (scene parameter and probe rows)

// What the view computes (view.glsl), for the Hammersley set in double precision:
//   x: the local discrepancy of the n points at the box [0, a) x [0, b), in points
//      (how many lie inside minus n a b);
//   y: n x_i - i for the point i whose column [i / n, (i + 1) / n) holds a (0 for x_i = i / n).
glm::dvec3 discrepancyView(double a, double b, std::uint32_t n) {
    int inside = 0;
    for (std::uint32_t j = 0; j < n; ++j) {
        const glm::dvec2 p = ref::hammersley(j, n);
        if (p.x < a && p.y < b) ++inside;
    }
    const auto slot = std::min(std::uint32_t(a * n), n - 1);
    return {inside - double(n) * a * b, ref::hammersley(slot, n).x * n - slot, 0};
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Hammersley points";
    d.params = {intParam("samples", 64, 1, kMaxPoints, "Number of points n in the set")};
    d.components = 2;
    // Both channels in points; mid grey = 0, saturated at +-4 points.
    d.display = {DisplayMode::Grey, -4, 4};
    d.needs = NeedsGeometry;
    // Judged by properties, not point by point (README.md): x = i / n exactly (the slot
    // offset, channel 2: within 1e-3 of 0, float rounding of i / n), and a low-discrepancy y
    // (channel 1: the box counts within 8 points of the Hammersley set's: measured <= 5 for
    // other low-discrepancy sequences, 27-30 for white noise at n = 1024).
    d.tolerance = {8, 0, 0};
    d.componentTolerances = {{8, 0, 0}, {1e-3, 0, 0}};
    d.nonNegative = false;
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        if (s.extra != glm::dvec4(0)) {  // probe and stability inputs
            const double a = std::clamp(s.extra.x, 0.0, 1.0);
            return discrepancyView(a, a, std::uint32_t(std::clamp(s.extra.y, 1.0, 1024.0)));
        }
        // The corner as the shader derives it from the (float) uv.
        const float a = std::abs(2.0f * float(s.uv.x) - 1.0f), b = 1.0f - float(s.uv.y);
        const int n = std::clamp(int(c.params.number("samples")), 1, kMaxPoints);
        return discrepancyView(a, b, std::uint32_t(n));
    };
    // x: box corner a from 0 to 1 (the square box [0, a)^2; the column's point i runs from 0 to
    // n - 1); y: n from 1 to 1024 on a log scale (rounded: 1, 1, 1, 1, 2, ... 1024).
    d.probe.xAxis = "box [0,a)^2, a 0..1 (point i = 0..n-1)";
    d.probe.yAxis = "n 1..1024 (log)";
    d.probe.width = 129;
    d.probe.height = 65;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.extra = {x, std::round(std::exp2(10.0 * y)), 0, 1};  // w = 1: never all zero
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
