// multiscatter_direct: the Cook-Torrance BRDF with Turquin's multiple-scattering
// compensation of the specular lobe, 1 + F0 (1 / E - 1), E = A + B from the split-sum LUT.
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>

#include "pbrlab/cube_sampler.h"
#include "pbrlab/params.h"
#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// The parts of the formula: the lobe's and the diffuse term's (pbrlab/shading_terms.h) and the
// compensation's own.
struct Knobs : ShadingKnobs {
    double compensation = 1;  // the factor 1 + F0 (1 / E - 1) on the lobe
    double f0Scale = 1;       // the F0 in it (0: 1 / E for every material)
    double inverseE = -1;     // E's power: 1 / E
    double lutSwapped = 0;    // 1: the LUT read at (roughness, N.V)
    double onDiffuse = 0;     // 1: the whole BRDF scaled, the diffuse part too
};

// E = A + B at (N.V, roughness), as the sampler reads uBrdfLut.
double albedoAt(const Surface& s, const ReferenceContext& c, bool swapped) {
    if (!c.ibl || c.ibl->lut.pixels.empty()) return 1;
    const double NdotV = std::max(glm::dot(s.normal, s.view), 0.0);
    const glm::dvec4 ab = sampleTexture(
        c.ibl->lut, swapped ? glm::dvec2(s.roughness, NdotV) : glm::dvec2(NdotV, s.roughness));
    return ab.x + ab.y;
}

glm::dvec3 compensated(const Surface& s, const ReferenceContext& c, const Knobs& k) {
    const Lobe lobe = cookTorranceLobe(s, s.light, k);
    const glm::dvec3 F0 = ref::baseReflectivity(s.albedo, s.metallic);
    const double E = albedoAt(s, c, k.lutSwapped != 0);
    const glm::dvec3 scale =
        1.0 + k.compensation * power(F0, k.f0Scale) * (power(E, k.inverseE) - 1.0);
    const glm::dvec3 diffuse =
        k.diffuse * lobe.diffuse * (k.onDiffuse != 0 ? scale : glm::dvec3(1));
    return grazingBand(s) * (diffuse + k.specular * lobe.specular * scale);
}
std::vector<NamedTerm> compensationTerms() {
    using K = Knobs;
    return namedTerms<K>(
        compensated,
        joined(derivedTerms<K>(joined(specularLobeTerms(false), diffuseTerms())),
               {removed<K>("the compensation 1 + F0 (1 / E - 1) on the specular lobe",
                           &K::compensation),
                factor<K>("F0", "F0 in the compensation 1 + F0 (1 / E - 1)", {&K::f0Scale}),
                exponentTried<K>(
                    "1 / E", "E's power in 1 + F0 (1 / E - 1)", &K::inverseE, -1, {1, -2, -0.5},
                    [](double e) {
                        return "the compensation 1 + F0 (E^" + exponentText(e) + " - 1)";
                    }),
                onOff<K>("the LUT read at (roughness, N.V), where its coordinates are (N.V, "
                         "roughness)",
                         &K::lutSwapped),
                onOff<K>("the compensation applied to the diffuse part too: it belongs to the "
                         "specular lobe",
                         &K::onDiffuse)}));
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Cook-Torrance BRDF with multiple scattering (Turquin)";
    d.params = {lightDirectionParam()};
    d.components = 3;
    d.display = {DisplayMode::HdrColor, 0, 1};
    // E comes from the split-sum LUT, a precomputed map; the value is a BRDF, not radiance
    // read from the environment.
    d.needs =
        NeedsAlbedo | NeedsMetallic | NeedsRoughness | NeedsEnvironment | NeedsPrecomputedMaps;
    d.linearInEnvironment = false;
    // As step `brdf`: between the floored and the lesson's + 0.001 specular denominator, +- 1e-3
    // of the value or the spread of 8 ulps of N, V, L (README.md).
    d.tolerance = {1e-7, 1e-3, 8};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        return compensated(s, c, Knobs{});
    };
    d.alternatives = {
        {"the lesson's 4 N.V N.L + 0.001 in the specular denominator (seed 001)",
         [](const Surface& s, const ReferenceContext& c) {
             const glm::dvec3 F0 = ref::baseReflectivity(s.albedo, s.metallic);
             const glm::dvec3 F = ref::fresnelSchlick(
                 std::max(glm::dot(ref::halfwayVector(s.light, s.view), s.view), 0.0), F0);
             const glm::dvec3 diffuse = (1.0 - F) * (1.0 - s.metallic) * s.albedo / ref::kPi;
             const glm::dvec3 specular = ref::cookTorranceSpecular(
                 s.normal, s.view, s.light, F0, s.roughness, ref::DenominatorGuard::LessonEpsilon);
             const double E = albedoAt(s, c, false);
             return grazingBand(s) * (diffuse + specular * (1.0 + F0 * (1.0 / E - 1.0)));
         },
         true}};
    d.domain = highlightDomain;  // the whole lobe, half the points near the highlight
    d.cases = {lessonGridCase()};
    // As brdf's probe: the plane of incidence, on a half-metallic orange.
    d.probe = planeOfIncidenceProbe([](Surface& s) {
        s.metallic = 0.5;
        s.albedo = s.albedoTexel = glm::dvec3(0.9, 0.5, 0.1);
    });
    d.namedTerms = compensationTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
