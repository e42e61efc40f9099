// multiscatter_ibl: the split sum with the energy of multiple scattering given back
// (Fdez-Aguera 2019), from the same three maps.
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>

#include "pbrlab/ibl_reference.h"
#include "pbrlab/named_terms.h"

using namespace pbrlab;

namespace {

// The parts of the formula, for feedback that names the one a student got wrong; at the
// defaults the reference itself.
struct Knobs {
    double ao = 1;
    double series = 1;           // the 1 / (1 - Ems F_avg) of the bounces' geometric series
    double favgTerm = 1;         // (1 - F0) / 21 in F_avg = F0 + (1 - F0) / 21
    double multiple = 1;         // the multiple-scattering term Fms Ems
    double diffuseLoss = 1;      // (FssEss + Fms Ems) taken from the diffuse weight
    double splitSumKd = 0;       // 1: kD = (1 - F)(1 - metallic) albedo, split_sum's weight
    double msOnPrefiltered = 0;  // 1: Fms Ems lit by the prefiltered map, not the irradiance
    double roughFresnel = 1;     // kS = fresnelSchlickRoughness (0: F0, three.js's choice)
    double lutSwapped = 0;       // 1: the LUT read at (roughness, N.V)
};

glm::dvec3 multiscatterWithKnobs(const Surface& s, const ReferenceContext& c, const Knobs& k) {
    if (!c.ibl) return s.emissive;
    const IblInputs& ibl = *c.ibl;
    const glm::dvec3 &N = s.normal, &V = s.view;
    const double NdotV = std::max(glm::dot(N, V), 0.0);
    const glm::dvec3 F0 = ref::baseReflectivity(s.albedo, s.metallic);
    const glm::dvec2 AB(sampleTexture(ibl.lut, k.lutSwapped != 0 ? glm::dvec2(s.roughness, NdotV)
                                                                 : glm::dvec2(NdotV, s.roughness)));
    const glm::dvec3 kS =
        k.roughFresnel != 0 ? ref::fresnelSchlickRoughness(NdotV, F0, s.roughness) : F0;
    const glm::dvec3 FssEss = kS * AB.x + AB.y;
    const double Ems = 1 - (AB.x + AB.y);
    const glm::dvec3 Favg = F0 + k.favgTerm * (1.0 - F0) / 21.0;
    const glm::dvec3 Fms = FssEss * Favg / power(1.0 - Ems * Favg, k.series);
    const glm::dvec3 multiple = k.multiple * Fms * Ems;
    const glm::dvec3 kD =
        k.splitSumKd != 0
            ? (1.0 - ref::fresnelSchlickRoughness(NdotV, F0, s.roughness)) * (1 - s.metallic)
            : (1 - s.metallic) * (1.0 - k.diffuseLoss * (FssEss + multiple));
    const glm::dvec3 irradiance = ibl.irradiance.sample(N, 0);
    const glm::dvec3 prefiltered =
        ibl.prefilter.sample(glm::reflect(-V, N), s.roughness * ibl.prefilterMaxLod);
    return (FssEss * prefiltered + multiple * (k.msOnPrefiltered != 0 ? prefiltered : irradiance) +
            kD * s.albedo * irradiance) *
               power(s.ao, k.ao) +
           s.emissive;
}
std::vector<NamedTerm> multiscatterTerms() {
    using K = Knobs;
    return namedTerms<K>(
        multiscatterWithKnobs,
        {wholeFactor<K>("ao", "ao", {&K::ao}),
         factorTried<K>("1 / (1 - Ems F_avg)",
                        "the series' sum 1 / (1 - Ems F_avg) in Fms = FssEss F_avg / (1 - Ems "
                        "F_avg)",
                        {&K::series}, 1, {0, 2}),
         removed<K>("(1 - F0) / 21 in F_avg = F0 + (1 - F0) / 21", &K::favgTerm),
         removed<K>("the multiple-scattering term Fms Ems", &K::multiple),
         removed<K>("the energy reflected, FssEss + Fms Ems, taken from the diffuse weight kD "
                    "= albedo (1 - metallic) (1 - (FssEss + Fms Ems))",
                    &K::diffuseLoss),
         onOff<K>("split_sum's kD = (1 - F)(1 - metallic) where the energy left, 1 - (FssEss + "
                  "Fms Ems), belongs",
                  &K::splitSumKd),
         onOff<K>("Fms Ems lit by the prefiltered map where the irradiance belongs (light that "
                  "bounced many times has forgotten its direction)",
                  &K::msOnPrefiltered),
         onOff<K>("the LUT read at (roughness, N.V), where its coordinates are (N.V, roughness)",
                  &K::lutSwapped)});
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Multiple-scattering ambient light (Fdez-Aguera)";
    d.components = 3;
    d.display = {DisplayMode::HdrColor};
    d.needs = NeedsMaterial | NeedsEmissive | NeedsEnvironment | NeedsPrecomputedMaps;
    d.skyBackground = true;
    d.scene = "furnace";
    // As split_sum: the same maps on both sides; +- 2e-3 of the value or the spread of 8 ulps of
    // the inputs, 0.1% of the points free where llvmpipe's 8-bit filter weights meet a bright
    // texel (README.md).
    d.tolerance = {1e-5, 2e-3, 8, 1e-3};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        return multiscatterWithKnobs(s, c, Knobs{});
    };
    d.alternatives = {
        {"FssEss = F0 A + B (three.js and Filament: Schlick's F0 where the "
         "paper has the roughness-aware kS; they differ at grazing view only)",
         [](const Surface& s, const ReferenceContext& c) {
             Knobs k;
             k.roughFresnel = 0;
             return multiscatterWithKnobs(s, c, k);
         },
         false}};
    d.probe = ambientLightProbe();  // N·V along x, roughness along y, an orange half-metal
    d.domain = ambientLightDomain;
    d.namedTerms = multiscatterTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
