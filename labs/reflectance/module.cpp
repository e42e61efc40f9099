// reflectance: the reflectance equation for point lights, a sum over the scene's
// lights of f_r L_i N·L, plus the ambient term 0.03 albedo ao.
#include "pbrlab/module.h"

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Reflectance equation: sum of f_r L_i N·L + ambient";
    d.components = 3;
    d.display = {DisplayMode::HdrColor, 0, 1};
    d.needs = NeedsMaterial | NeedsEmissive;
    // Band: between the floored and the lesson's + 0.001 specular denominator, +- 1e-3 of the
    // value or the spread of 8 ulps of the inputs and the lights (README.md).
    d.tolerance = {1e-7, 1e-3, 8};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        return ref::reflectedRadiance(s.position, s.normal, s.view, s.albedo, s.metallic,
                                      s.roughness, s.ao, c.lights.data(), int(c.lights.size())) +
               s.emissive;
    };
    d.alternatives = {{"the lesson's 4 N.V N.L + 0.001 in the specular denominator (seed 001)",
                       [](const Surface& s, const ReferenceContext& c) {
                           return ref::reflectedRadiance(s.position, s.normal, s.view, s.albedo,
                                                         s.metallic, s.roughness, s.ao,
                                                         c.lights.data(), int(c.lights.size()),
                                                         ref::DenominatorGuard::LessonEpsilon) +
                                  s.emissive;
                       },
                       true}};
    // A point near the sphere, any N and V in its hemisphere, any material and ao: the scene's
    // lights (the grader also uses the lesson's four and three coloured ones).
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.position = {r.range(-1, 1), r.range(-1, 1), r.range(-1, 1)};
        s.normal = r.direction();
        s.view = r.around(s.normal, 0, 1);
        s.albedo = s.albedoTexel = r.color();
        s.metallic = r.uniform();
        s.roughness = r.range(0.05, 1);
        s.ao = r.uniform();
        return s;
    };
    d.cases = {lessonGridCase()};
    // The lesson's sphere grid as a continuous chart: x roughness 0.05..1, y metallic 0..1,
    // albedo (0.5, 0, 0), ao 1, at the origin with N = +z and V the mirror image of the
    // direction to (5, 5, 8), the light of the default scene: there the highlight is at its
    // peak. The lights are the scene's (uLightPositions), as on the sphere.
    d.probe.xAxis = "roughness 0.05..1";
    d.probe.yAxis = "metallic 0..1";
    d.probe.width = 39;
    d.probe.height = 33;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.position = {0, 0, 0};
        s.normal = {0, 0, 1};
        s.view = glm::normalize(glm::dvec3(-5, -5, 8));
        s.albedo = {0.5, 0, 0};
        s.metallic = y;
        s.roughness = 0.05 + 0.95 * x;
        s.ao = 1;
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
