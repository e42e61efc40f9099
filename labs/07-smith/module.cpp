// Step 7, smith: Smith shadowing-masking G = G1(N·V) G1(N·L).
#include "pbrlab/module.h"

#include <cmath>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "smith";
    d.step = 7;
    d.lab = "direct";
    d.title = "Smith shadowing-masking G";
    d.function = "float geometrySmith(vec3 N, vec3 V, vec3 L, float roughness)";
    d.params = {directionParam("light_dir", {5, 5, 8},
                               "Direction from the scene centre to the light (moves light 0)",
                               ParamBinding::LightDirection)};
    d.components = 1;
    d.display = {DisplayMode::Grey, 0, 1};
    d.needs = NeedsRoughness;
    // Rounding of N·V and N·L near silhouette and terminator, amplified by 1/k <= 7.2:
    // measured <= 4.7e-5 (floor 0.01); 5e-4 leaves 10x, mistakes are off by >= 0.88.
    d.tolerance = {1e-2, 5e-4};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return glm::dvec3(ref::geometrySmith(s.normal, s.view, s.light, s.roughness));
    };
    // x: N·V, y: N·L, both 0..1, at roughness 0.5; V and L on opposite sides of N.
    d.probe.xAxis = "N·V 0..1";
    d.probe.yAxis = "N·L 0..1 (roughness 0.5)";
    d.probe.width = 65;
    d.probe.height = 65;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {std::sqrt(1 - x * x), 0, x};
        s.light = {-std::sqrt(1 - y * y), 0, y};
        s.roughness = 0.5;
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
