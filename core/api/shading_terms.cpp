#include "pbrlab/shading_terms.h"

#include <algorithm>
#include <cmath>

#include "pbrlab/ibl_reference.h"

namespace pbrlab {

using glm::dvec3;

const std::vector<KRemapping>& kRemappings() {
    static const std::vector<KRemapping> r = {
        {"k = (roughness + 1)^2 / 8", [](double x) { return (x + 1) * (x + 1) / 8; }},
        {"k = roughness^2 / 2", [](double x) { return std::max(x * x, ref::kIblMinAlpha) / 2; }},
        {"k = (roughness + 1) / 8", [](double x) { return (x + 1) / 8; }},
        {"k = roughness / 2", [](double x) { return x / 2; }},
        {"k = roughness^2", [](double x) { return x * x; }},
        {"k = (roughness + 1)^2 / 2", [](double x) { return (x + 1) * (x + 1) / 2; }},
    };
    return r;
}

double shadingG1(double NdotX, double roughness, const ShadingKnobs& k, int own) {
    const double x = std::max(NdotX, 0.0);
    const int choice = k.kChoice > 0 ? int(k.kChoice) : k.kChoice < 0 ? 0 : own;
    const double remapped = kRemappings()[size_t(choice)].k(roughness);
    const double kk = k.kComplement != 0 ? 1 - remapped : remapped;
    return power(x, k.NX) / (x * (1 - kk) + kk);
}

double shadingGgx(double NdotH, double roughness, const ShadingKnobs& k) {
    const double a = std::pow(roughness, k.alphaPower);
    const double a2 = std::max(a * a, ref::kMinAlpha2);
    const double h = power(std::max(NdotH, 0.0), k.NHpower);
    const double d = (1.0 - h) + h * a2;
    // Squared as the formula writes it: d < 0 where N.H > 1 (an unnormalised H), and its square
    // is what the student's float code computes there.
    return power(a2, k.alpha2) /
           (ref::kPi * (k.denominator == 2 ? d * d : power(d, k.denominator)));
}

dvec3 shadingFresnel(double cosine, const dvec3& F0, const ShadingKnobs& k) {
    const double s = power(std::clamp(1.0 - cosine, 0.0, 1.0), k.schlick);
    if (k.f0TimesSchlick != 0) return F0 + F0 * s;
    return F0 + power(1.0 - F0, k.oneMinusF0) * s;
}

Lobe cookTorranceLobe(const Surface& s, const dvec3& L, const ShadingKnobs& k) {
    const dvec3 &N = s.normal, &V = s.view;
    const dvec3 H = k.unnormalisedH != 0 ? L + V : ref::halfwayVector(L, V);
    const dvec3 F0 = ref::baseReflectivity(s.albedo, s.metallic);
    const double NdotV = std::max(glm::dot(N, V), 0.0), NdotL = std::max(glm::dot(N, L), 0.0);
    const double cosine = k.fresnelAtNdotV != 0 ? NdotV : std::max(glm::dot(H, V), 0.0);
    const dvec3 F = k.f0ForF != 0 ? F0 : shadingFresnel(cosine, F0, k);
    const double G1v = shadingG1(NdotV, s.roughness, k, 0);
    const double G1l = k.g1vTwice != 0 ? G1v : shadingG1(NdotL, s.roughness, k, 0);
    const double denominator = std::max(4 * NdotV * NdotL, ref::kSpecularDenomFloor);
    // The reference's guarded denominator, then each of its factors at another power.
    const dvec3 specular = power(shadingGgx(glm::dot(N, H), s.roughness, k), k.D) *
                           power(G1v, k.G1V) * power(G1l, k.G1L) * power(F, k.F) * power(F0, k.F0) /
                           denominator * power(4.0, k.four + 1) * power(NdotL, k.NL + 1) *
                           power(NdotV, k.NV + 1);
    // kD = (1 - F)(1 - metallic), from the reference's F, or from F at N.V when the lobe's is
    // (a BRDF computes F once and uses it in both).
    const dvec3 Fd = shadingFresnel(cosine, F0, ShadingKnobs{});
    const dvec3 kD = (1.0 - Fd) * power(1.0 - s.metallic, k.metal);
    const dvec3 diffuse = power(kD, k.kD) * power(s.albedo, k.albedo) * power(ref::kPi, k.pi);
    return {specular, diffuse};
}

dvec3 shadingBrdf(const Surface& s, const dvec3& L, const ShadingKnobs& k) {
    const Lobe lobe = cookTorranceLobe(s, L, k);
    return (k.diffuse * lobe.diffuse + k.specular * lobe.specular) *
           power(std::max(glm::dot(s.normal, L), 0.0), k.cosine);
}

KnobbedTerm<ShadingKnobs> kSwappedTerm() {
    return onOff("k and (1 - k) swapped in G1's denominator N.X (1 - k) + k",
                 &ShadingKnobs::kComplement);
}

KnobbedTerm<ShadingKnobs> pdfWeightTerm() {
    return factorTried<ShadingKnobs>(
        "V.H / (N.H N.V)", "the V.H / (N.H N.V) left after dividing by the pdf",
        {&ShadingKnobs::VH, &ShadingKnobs::NH, &ShadingKnobs::NV}, 1, {0});
}

KnobbedTerm<ShadingKnobs> directRemappingTerm() {
    return onOff("k = (roughness + 1)^2 / 8 (direct light), where IBL has k = roughness^2 / 2",
                 &ShadingKnobs::kChoice, -1);
}

KnobbedTerms<ShadingKnobs> specularLobeTerms(bool whole) {
    using K = ShadingKnobs;
    auto f = [whole](std::string symbol, std::string name, std::vector<double K::*> knobs,
                     double reference = 1) {
        return whole ? wholeFactor(std::move(symbol), std::move(name), std::move(knobs), reference)
                     : factor(std::move(symbol), std::move(name), std::move(knobs), reference);
    };
    return {
        f("D", "the distribution term D", {&K::D}),
        f("G", "the geometry term G", {&K::G1V, &K::G1L}),
        f("G1(N.V)", "the masking term G1(N.V)", {&K::G1V}),
        f("G1(N.L)", "the shadowing term G1(N.L)", {&K::G1L}),
        f("F", "the Fresnel term F", {&K::F}),
        f("F0", "F0", {&K::F0}, 0),
        f("N.L", "N.L in the denominator 4 N.L N.V", {&K::NL}, -1),
        f("N.V", "N.V in the denominator 4 N.L N.V", {&K::NV}, -1),
        f("4 N.L N.V", "the denominator 4 N.L N.V", {&K::four, &K::NL, &K::NV}, -1),
        onOff("F0 where F belongs (F = F0 + (1 - F0)(1 - H.V)^5)", &K::f0ForF),
        onOff("F evaluated at N.V, where the specular lobe has H.V", &K::fresnelAtNdotV),
        onOff("F0 multiplying the Schlick factor (F0 + F0 (1 - cos)^5)", &K::f0TimesSchlick),
        onOff("G1(N.V) for the light too, where the reference has G1(N.L)", &K::g1vTwice),
        onOff("the half vector L + V used without normalising it", &K::unnormalisedH),
        exponentTried("alpha", "alpha", &K::alphaPower, 2, {1, 4},
                      [](double e) { return "alpha = roughness^" + exponentText(e); }),
        onOff("k = roughness^2 / 2 (the IBL remapping) in G1", &K::kChoice),
    };
}

KnobbedTerms<ShadingKnobs> diffuseTerms() {
    using K = ShadingKnobs;
    return {
        factor<K>("kD", "the diffuse weight kD", {&K::kD}),
        factor<K>("(1 - metallic)", "(1 - metallic) in kD", {&K::metal}),
        factor<K>("albedo", "the albedo in the diffuse term", {&K::albedo}),
        factor<K>("PI", "the division by PI in the diffuse term", {&K::pi}, -1),
        removed("the diffuse term kD albedo / PI", &K::diffuse),
        removed("the specular term", &K::specular),
    };
}

KnobbedTerms<ShadingKnobs> estimatorWeightTerms(const std::string& weight) {
    using K = ShadingKnobs;
    return {
        factor<K>("G", "the geometry term G", {&K::G1V, &K::G1L}),
        factor<K>("G1(N.V)", "the masking term G1(N.V)", {&K::G1V}),
        factor<K>("G1(N.L)", "the shadowing term G1(N.L)", {&K::G1L}),
        factor<K>("V.H", "V.H in " + weight, {&K::VH}),
        factor<K>("N.H", "N.H in " + weight, {&K::NH}, -1),
        factor<K>("N.V", "N.V in " + weight, {&K::NV}, -1),
        pdfWeightTerm(),
    };
}

}  // namespace pbrlab
