// reflectance: the reflectance equation for point lights, a sum over the scene's
// lights of f_r L_i N·L, plus the ambient term 0.03 albedo ao.
#include "pbrlab/module.h"

#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// Named terms for feedback (pbrlab/shading_terms.h): the BRDF's, and the reflectance
// equation's own: the light's radiance and N.L per light, the ambient term.
struct Knobs : ShadingKnobs {
    double lightColor = 1, distance = -2, NLcos = 1, ambient = 1, ao = 1;
};
glm::dvec3 reflected(const Surface& s, const ReferenceContext& c, const Knobs& k) {
    glm::dvec3 sum(0.0);
    for (const ref::PointLight& light : c.lights) {
        const glm::dvec3 L = ref::safeNormalize(light.position - s.position, glm::dvec3(0.0));
        const glm::dvec3 d = light.position - s.position;
        const glm::dvec3 radiance =
            power(light.color, k.lightColor) *
            power(std::max(glm::dot(d, d), ref::kMinDistance2), k.distance / 2);
        sum +=
            shadingBrdf(s, L, k) * radiance * power(std::max(glm::dot(s.normal, L), 0.0), k.NLcos);
    }
    return sum + k.ambient * ref::kAmbient * s.albedo * power(s.ao, k.ao) + s.emissive;
}
std::vector<NamedTerm> reflectanceTerms() {
    return namedTerms<Knobs>(
        reflected,
        joined<Knobs>(
            derivedTerms<Knobs>(joined(specularLobeTerms(false), diffuseTerms())),
            {factor<Knobs>("N.L", "the cosine N.L", {&Knobs::NLcos}),
             exponent<Knobs>("d", "the inverse square", &Knobs::distance, -2, -6, 2, falloffText),
             factor<Knobs>("ao", "ao in the ambient term", {&Knobs::ao}),
             removed<Knobs>("the ambient term 0.03 albedo ao", &Knobs::ambient)}));
}

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
    d.namedTerms = reflectanceTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
