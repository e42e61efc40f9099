// Step 5, ndf: the GGX (Trowbridge-Reitz) normal distribution D(N, H, roughness).
#include "pbrlab/module.h"

#include <cmath>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "ndf";
    d.step = 5;
    d.lab = "direct";
    d.title = "GGX normal distribution D";
    d.function = "float distributionGGX(vec3 N, vec3 H, float roughness)";
    d.params = {directionParam("light_dir", {5, 5, 8},
                               "Direction from the scene centre to the light (moves light 0)",
                               ParamBinding::LightDirection)};
    d.components = 1;
    d.display = {DisplayMode::FalseColor, 0.01, 100, true};  // D spans decades: log scale
    d.needs = NeedsRoughness;
    // Near its peak D amplifies the 1-ulp rounding of |H| by 4 / alpha^2: 5.8% measured at
    // roughness 0.05 (sphere grid); 0.25 covers 2-ulp drivers, every mistake is off by >= 0.9.
    d.tolerance = {1e-2, 0.25};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return glm::dvec3(
            ref::distributionGGX(s.normal, ref::halfwayVector(s.light, s.view), s.roughness));
    };
    // x: N·H from 0 (H in the tangent plane) to 1 (H = N); y: roughness 0.05 to 1. N = z and
    // L = V = H, so the view's halfwayVector(L, V) returns that H.
    d.probe.xAxis = "N·H 0..1";
    d.probe.yAxis = "roughness 0.05..1";
    d.probe.width = 129;
    d.probe.height = 65;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = s.light = {std::sqrt(1 - x * x), 0, x};
        s.roughness = 0.05 + 0.95 * y;
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
