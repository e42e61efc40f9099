// Step 10, specular: the Cook-Torrance specular lobe D G F / (4 N·V N·L).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "specular";
    d.step = 10;
    d.lab = "direct";
    d.title = "Cook-Torrance specular D G F / (4 N·V N·L)";
    d.function = "vec3 cookTorranceSpecular(vec3 N, vec3 V, vec3 L, vec3 F0, float roughness)";
    d.params = {directionParam("light_dir", {5, 5, 8},
                               "Direction from the scene centre to the light (moves light 0)",
                               ParamBinding::LightDirection)};
    d.components = 3;
    d.display = {DisplayMode::FalseColor, 1e-4, 10, true};
    d.needs = NeedsAlbedo | NeedsMetallic | NeedsRoughness;
    // GGX at roughness 0.05 turns one ulp of N·H into 4 ulp / alpha^2 = 4% of D: measured 6.2%
    // on the sphere grid (1e-4 on the sphere and the probe); the lesson's +0.001 adds <= 2% in
    // the faded band. 0.2 leaves 3x; mistakes are off by >= 0.75.
    d.tolerance = {1e-3, 0.2};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return grazingBand(s) *
               ref::cookTorranceSpecular(s.normal, s.view, s.light,
                                         ref::baseReflectivity(s.albedo, s.metallic), s.roughness);
    };
    // In the plane of incidence: V fixed 45° from N; x: L from -90° (grazing, on the mirror
    // side) through the mirror direction (x = 0.25), N (x = 0.5) and V itself (x = 0.75) to
    // +90°; y: roughness 0.05..1. F0 = (0.95, 0.5, 0.04): a metal's, an in-between one and a
    // dielectric's (metallic 1, albedo = F0).
    d.probe.xAxis = "angle(N, L) -90..90 deg (V at +45, mirror at -45)";
    d.probe.yAxis = "roughness 0.05..1";
    d.probe.width = 61;
    d.probe.height = 39;
    d.probe.at = [](double x, double y) {
        const double theta = (x - 0.5) * std::numbers::pi;
        const double v = std::numbers::pi / 3;
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {std::sin(v), 0, std::cos(v)};
        s.light = {std::sin(theta), 0, std::cos(theta)};
        s.metallic = 1;
        s.albedo = {0.95, 0.5, 0.04};
        s.roughness = 0.05 + 0.95 * y;
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
