// g1: Schlick-GGX masking G1(N·X, roughness) for direct light, k = (r + 1)^2 / 8.
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>

#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// Named terms for feedback (pbrlab/named_terms.h): G1 without N.X in its numerator, with k and
// 1 - k swapped, or with another remapping of k.
std::vector<NamedTerm> g1Terms() {
    using K = ShadingKnobs;
    KnobbedTerms<K> terms = {wholeFactor<K>("N.X", "N.X in the numerator", {&K::NX}),
                             kSwappedTerm()};
    for (size_t i = 1; i < kRemappings().size(); ++i)
        terms.push_back(
            onOff(kRemappings()[i].name + std::string(", where the direct-light remapping is k = "
                                                      "(roughness + 1)^2 / 8"),
                  &K::kChoice, double(i)));
    return namedTerms<K>(
        [](const Surface& s, const ReferenceContext&, const K& k) {
            return glm::dvec3(shadingG1(glm::dot(s.normal, s.view), s.roughness, k, 0));
        },
        terms);
}

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
    d.namedTerms = g1Terms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
