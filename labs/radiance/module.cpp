// radiance: the radiance a point light delivers at a point, falling off as 1/d^2.
#include "pbrlab/module.h"

#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// Named terms for feedback (pbrlab/named_terms.h): the radiance with the inverse square at
// another power of d, or without the light's colour.
struct Knobs {
    double lightColor = 1, distance = -2;
};
std::vector<NamedTerm> radianceTerms() {
    return namedTerms<Knobs>(
        [](const Surface& s, const ReferenceContext&, const Knobs& k) {
            const glm::dvec3 d = s.lightPosition - s.position;
            return power(s.lightColor, k.lightColor) *
                   power(std::max(glm::dot(d, d), ref::kMinDistance2), k.distance / 2);
        },
        {exponent<Knobs>("d", "the inverse square", &Knobs::distance, -2, -6, 2, falloffText),
         wholeFactor<Knobs>("the light's colour", "the light's colour", {&Knobs::lightColor})});
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Point-light radiance (inverse square)";
    d.params = {lightDirectionParam()};
    d.components = 3;
    d.display = {DisplayMode::HdrColor, 0, 1};
    // Band: the floored and the epsilon forms, +- 1e-3 of the value or the spread of 8 ulps
    // of the positions (README.md, "Tolerance and why").
    d.tolerance = {1e-6, 1e-3, 8};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return ref::pointLightRadiance(s.lightColor, s.lightPosition, s.position);
    };
    d.alternatives = {{"an epsilon added to d^2 instead of a floor, as large as the floor (1e-4)",
                       [](const Surface& s, const ReferenceContext&) {
                           const glm::dvec3 v = s.lightPosition - s.position;
                           return s.lightColor / (glm::dot(v, v) + ref::kMinDistance2);
                       },
                       true}};
    // A point anywhere near the sphere, a light in any direction at 0.05 to 20 units (every
    // decade as likely), of any colour and intensity up to 100 per channel.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.position = {r.range(-1.5, 1.5), r.range(-1.5, 1.5), r.range(-1.5, 1.5)};
        s.light = r.direction();
        s.lightPosition = s.position + s.light * r.logRange(0.05, 20);
        s.lightColor = r.color(100);
        return s;
    };
    d.cases = {lessonGridCase()};
    // x: distance from the point to the light, 0.05 to 5 (2.525 at the centre column);
    // y: intensity of a white light, 0 to 10.
    d.probe.xAxis = "distance d 0.05..5";
    d.probe.yAxis = "intensity 0..10 (white)";
    d.probe.width = 65;
    d.probe.height = 65;
    d.probe.at = [](double x, double y) {
        const glm::dvec3 direction = glm::dvec3(1, 2, 2) / 3.0;
        const double distance = 0.05 + 4.95 * x;
        Surface s;
        s.covered = true;
        s.position = {0.5, -0.25, 1};
        s.normal = {0, 0, 1};
        s.light = direction;
        s.lightPosition = s.position + direction * distance;
        s.lightColor = glm::dvec3(10 * y);
        return s;
    };
    d.namedTerms = radianceTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
