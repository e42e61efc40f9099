// split_sum: ambient light from the environment with three precomputed lookups.
#include "pbrlab/module.h"

#include <numbers>

#include "pbrlab/ibl_reference.h"
#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// What the reference solution computes, from the same maps the shader reads (CubeSampler
// reads them as the GPU's sampler does).
constexpr double kMaxNdotVFloor = 1e-3;  // the largest floor on N.V a correct solution may use

glm::dvec3 splitSum(const Surface& s, const IblInputs& ibl, double minNdotV = 0) {
    const glm::dvec3 N = s.normal, V = s.view;
    const double NdotV = std::max(glm::dot(N, V), minNdotV);
    const glm::dvec3 R = glm::reflect(-V, N);
    glm::dvec3 irradiance = ibl.irradiance.sample(N, 0);
    glm::dvec3 prefiltered = ibl.prefilter.sample(R, s.roughness * ibl.prefilterMaxLod);
    glm::dvec2 lut(sampleTexture(ibl.lut, {NdotV, s.roughness}));
    return ref::ambientIBL(N, V, s.albedo, s.metallic, s.roughness, s.ao, irradiance, prefiltered,
                           lut, minNdotV);
}

// Named terms for feedback (pbrlab/shading_terms.h): the diffuse weight's and the split sum's
// parts, each missing, doubled or written another way.
struct Knobs : ShadingKnobs {
    double ao = 1, bias = 1, fForF0 = 0, irradiancePi = 0;
    double maxLod = 1;      // the LOD roughness x uPrefilterMaxLod
    double lutSwapped = 0;  // the LUT read at (roughness, N.V)
};
glm::dvec3 splitSumWithKnobs(const Surface& s, const ReferenceContext& c, const Knobs& k) {
    if (!c.ibl) return s.emissive;
    const IblInputs& ibl = *c.ibl;
    const glm::dvec3 &N = s.normal, &V = s.view;
    const double NdotV = std::max(glm::dot(N, V), 0.0);
    const glm::dvec3 F0 = ref::baseReflectivity(s.albedo, s.metallic);
    const glm::dvec3 F = ref::fresnelSchlickRoughness(NdotV, F0, s.roughness);
    const glm::dvec3 kD = (1.0 - F) * power(1.0 - s.metallic, k.metal);
    const glm::dvec3 diffuse = power(kD, k.kD) * power(s.albedo, k.albedo) *
                               ibl.irradiance.sample(N, 0) * power(ref::kPi, k.irradiancePi);
    const glm::dvec3 prefiltered = ibl.prefilter.sample(
        glm::reflect(-V, N), s.roughness * power(ibl.prefilterMaxLod, k.maxLod));
    const glm::dvec2 lut(sampleTexture(ibl.lut, k.lutSwapped != 0
                                                    ? glm::dvec2(s.roughness, NdotV)
                                                    : glm::dvec2(NdotV, s.roughness)));
    const glm::dvec3 specular = prefiltered * ((k.fForF0 != 0 ? F : F0) * lut.x + k.bias * lut.y);
    return (k.diffuse * diffuse + k.specular * specular) * power(s.ao, k.ao) + s.emissive;
}
std::vector<NamedTerm> splitSumTerms() {
    using K = Knobs;
    return namedTerms<K>(
        splitSumWithKnobs,
        {wholeFactor<K>("ao", "ao", {&K::ao}), factor<K>("kD", "the diffuse weight kD", {&K::kD}),
         factor<K>("(1 - metallic)", "(1 - metallic) in kD", {&K::metal}),
         factor<K>("albedo", "the albedo in the diffuse term", {&K::albedo}),
         factor<K>("PI", "PI in the diffuse term (uIrradianceMap stores E / PI already)",
                   {&K::irradiancePi}, 0),
         removed<K>("the LUT's bias B (in F0 A + B)", &K::bias),
         factorTried<K>("uPrefilterMaxLod",
                        "uPrefilterMaxLod in the LOD roughness x uPrefilterMaxLod", {&K::maxLod}, 1,
                        {0}),
         onOff<K>("the LUT read at (roughness, N.V), where its coordinates are (N.V, roughness)",
                  &K::lutSwapped),
         onOff<K>("F where the bracket has F0 (prefiltered (F0 A + B): Fresnel is inside A "
                  "and B)",
                  &K::fForF0),
         removed<K>("the diffuse term kD albedo irradiance", &K::diffuse),
         removed<K>("the specular term prefiltered (F0 A + B)", &K::specular)});
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Split-sum ambient light";
    d.components = 3;
    d.display = {DisplayMode::HdrColor};
    d.needs = NeedsMaterial | NeedsEmissive | NeedsEnvironment | NeedsPrecomputedMaps;
    d.skyBackground = true;
    d.scene = "sphere-grid";
    // Band: +- 2e-3 of the value or the spread of 8 ulps of the inputs; GPU and CPU read the
    // same maps, and 0.1% of the points may differ more where llvmpipe's 8-bit filter weights
    // meet a bright texel (README.md).
    d.tolerance = {1e-5, 2e-3, 8, 1e-3};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        return (c.ibl ? splitSum(s, *c.ibl) : glm::dvec3(0)) + s.emissive;
    };
    d.alternatives = {{"N.V floored at up to 1e-3 (an epsilon of its own at grazing angles)",
                       [](const Surface& s, const ReferenceContext& c) {
                           return (c.ibl ? splitSum(s, *c.ibl, kMaxNdotVFloor) : glm::dvec3(0)) +
                                  s.emissive;
                       },
                       true}};
    d.probe = ambientLightProbe();  // N·V along x, roughness along y, an orange half-metal
    d.domain = ambientLightDomain;
    d.namedTerms = splitSumTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
