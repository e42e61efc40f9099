// Step 6, g1: Schlick-GGX masking G1(N·X, roughness) for direct light, k = (r + 1)^2 / 8.
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "g1";
    d.step = 6;
    d.lab = "direct";
    d.title = "Schlick-GGX masking G1";
    d.function = "float geometrySchlickGGX(float NdotX, float roughness)";
    d.components = 1;
    d.display = {DisplayMode::Grey, 0, 1};
    d.needs = NeedsRoughness;
    // Rounding of N·V near the silhouette, amplified by 1/k <= 7.2: measured <= 2.2e-5, bound
    // 1.1e-4 (floor 0.01); 5e-4 leaves 4.5x over the bound, mistakes are off by >= 0.6.
    d.tolerance = {1e-2, 5e-4};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return glm::dvec3(
            ref::geometrySchlickGGX(std::max(glm::dot(s.normal, s.view), 0.0), s.roughness));
    };
    // x: N·X (here N·V) from 0 (grazing) to 1 (along the normal); y: roughness 0.05 to 1.
    d.probe = viewCosineRoughnessProbe();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
