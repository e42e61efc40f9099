// g1: Schlick-GGX masking G1(N·X, roughness) for direct light, k = (r + 1)^2 / 8.
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Schlick-GGX masking G1";
    d.components = 1;
    d.display = {DisplayMode::Grey, 0, 1};
    d.needs = NeedsRoughness;
    // Band: +- 1e-3 of G1, at least 1e-6, or the spread of 8 ulps of N and V (README.md).
    d.tolerance = {1e-6, 1e-3, 8};
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.view = r.around(s.normal, 0, 1);
        s.roughness = r.range(0.05, 1);
        return s;
    };
    d.cases = {lessonGridCase()};
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
