// brdf_lut: the split sum's second factor, scale A and bias B of F0 as functions of
// N·V and roughness (what uBrdfLut stores; IBL k = roughness^2 / 2).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "pbrlab/ibl_reference.h"
#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// N·V as the view passes it: floored at 1e-3, so that correct guards between 1e-4 and 1e-3
// inside integrateBRDF see the same input (README.md, edge cases).
constexpr double kViewMinNdotV = 1e-3;

// Named terms for feedback (pbrlab/shading_terms.h): A and B on the same samples with a factor
// of G_vis = G V.H / (N.H N.V) or of the Schlick factor changed.
glm::dvec3 scaleAndBias(const Surface& s, const ReferenceContext& c, const ShadingKnobs& k) {
    const double NdotV = std::clamp(std::max(glm::dot(s.normal, s.view), 1e-3), 1e-4, 1.0);
    const glm::dvec3 N(0, 0, 1), V(std::sqrt(1 - NdotV * NdotV), 0, NdotV);
    const auto n = std::max(std::uint32_t(std::max(c.params.number("samples"), 1.0)), 1u);
    double A = 0, B = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::dvec3 H = ref::importanceSampleGGX(ref::hammersley(i, n), N, s.roughness);
        double VdotH = glm::dot(V, H);
        const glm::dvec3 L = 2.0 * VdotH * H - V;
        if (L.z <= 0) continue;
        const double NdotH = std::max(H.z, ref::kIblMinNdotH);
        VdotH = std::clamp(VdotH, 0.0, 1.0);
        const double G1v = shadingG1(NdotV, s.roughness, k, 1);
        const double G1l = k.g1vTwice != 0 ? G1v : shadingG1(L.z, s.roughness, k, 1);
        const double G = power(G1v, k.G1V) * power(G1l, k.G1L);
        const double Gvis = G * power(VdotH, k.VH) * power(NdotH, k.NH) * power(NdotV, k.NV);
        const double Fc = power(1.0 - (k.fresnelAtNdotV != 0 ? NdotV : VdotH), k.schlick);
        A += (1 - Fc) * Gvis;
        B += Fc * Gvis;
    }
    return glm::dvec3(A / n, B / n, 0);
}
std::vector<NamedTerm> scaleAndBiasTerms() {
    using K = ShadingKnobs;
    KnobbedTerms<K> terms = estimatorWeightTerms("G_vis = G V.H / (N.H N.V)");
    terms.push_back(exponentTried<K>(
        "(1 - V.H)", "the Schlick factor", &K::schlick, 5, {1, 2, 3, 4, 6},
        [](double e) { return "the Schlick factor Fc = (1 - V.H)^" + exponentText(e); }));
    terms.push_back(
        onOff("Fc = (1 - N.V)^5, where each sample has (1 - V.H)^5", &K::fresnelAtNdotV));
    terms.push_back(directRemappingTerm());
    return namedTerms<K>(scaleAndBias, terms);
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Split-sum BRDF LUT (scale A, bias B)";
    d.params = {intParam("samples", 256, 1, 65536,
                         "GGX samples per value (the host's LUT precompute uses 512)")};
    d.components = 2;
    // A in red, B in green, as stored (linear, like the published LUT images).
    d.display = {DisplayMode::Grey, 0, 1};
    // The LUT reads no environment: no precompute runs for this step.
    d.needs = NeedsRoughness;
    d.scene = "sphere-grid";
    // The quality report (same Hammersley points as the reference): float rounding, 1.8e-6
    // (README.md).
    d.tolerance = {1e-4, 1e-3, 0};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        const double NdotV = std::max(glm::dot(s.normal, s.view), kViewMinNdotV);
        const auto n = std::uint32_t(std::max(c.params.number("samples"), 1.0));
        const glm::dvec2 ab = ref::integrateBRDF(NdotV, s.roughness, n);
        return glm::dvec3(ab, 0.0);
    };
    // The probe is the LUT itself: x = N·V from 0 (grazing; evaluated at 1e-3) to 1, y =
    // roughness from 0.05 to 1 (roughness 0 is scored by the robustness sweep). Bottom row =
    // smoothest, as uBrdfLut's t = roughness; the published LUT images put roughness 1 on top
    // too. N = +z, V in the xz-plane.
    d.probe = viewCosineRoughnessProbe();
    // Bounds: A, B >= 0 and A + B <= 1 over the LUT (with F0 = 1 the specular lobe reflects
    // at most all the light: a white furnace). 1e-3 of slack for Monte Carlo noise at the
    // default sample count (the reference reaches 1.000000 at its maximum).
    d.invariants = [](const EvaluateFn& evaluate) {
        std::vector<Surface> grid;
        for (int i = 0; i < 16; ++i)
            for (int j = 0; j < 16; ++j) {
                double NdotV = (i + 0.5) / 16, r = 0.05 + 0.95 * j / 15;
                Surface s;
                s.covered = true;
                s.normal = {0, 0, 1};
                s.view = {std::sqrt(1 - NdotV * NdotV), 0, NdotV};
                s.roughness = r;
                grid.push_back(s);
            }
        std::vector<glm::dvec3> ab = evaluate(grid);
        double lo = 1e300, sum = 0;
        for (const auto& v : ab) lo = std::min({lo, v.x, v.y}), sum = std::max(sum, v.x + v.y);
        return std::vector<InvariantResult>{
            {"smallest of A, B", lo, ">= 0", lo >= 0, "A and B are averages of positive weights"},
            {"largest A + B", sum, "<= 1 (+1e-3)", sum <= 1.001,
             "with F0 = 1 the lobe reflects more than arrives: a weight is too large"}};
    };
    // Graded by convergence (README.md, "Grading"): at 4, 64 and 1024 samples, within
    // 5 sigma / sqrt(n) of the exact LUT (brdfLutExact), sigma the one-sample spread of the
    // reference's estimator; the mean error must fall at least 3x from 4 to 1024.
    EstimatorSpec e;
    e.samplesParam = "samples";
    e.sampleCounts = {4, 64, 1024};
    e.environment = "";  // the LUT reads no environment
    e.converged = [](const Surface& s, const ReferenceContext&, std::uint32_t samples) {
        const double NdotV = std::max(glm::dot(s.normal, s.view), kViewMinNdotV);
        const ref::Moments m = ref::brdfLutMoments(NdotV, s.roughness, std::min(samples, 2048u));
        return Estimate{m.mean, m.sigma, m.error};
    };
    // 4% of the points may be outside the band: Chebyshev's bound for any correct estimator
    // (with the true sigma, P(|error| > 5 sigma / sqrt(n)) <= 1/25), on the random inputs,
    // whose errors are independent (grading/estimator_convergence.cpp): there correct estimators
    // reached 2.1% (mc_specular, one set of random numbers for the whole picture, docs/grading.md).
    e.systematic = {2e-4, 2e-3, 0, 0.04};
    d.estimator = e;
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = {0, 0, 1};
        const double NdotV = r.uniform();
        s.view = {std::sqrt(1 - NdotV * NdotV), 0, NdotV};
        s.roughness = r.range(0.05, 1);
        return s;
    };
    d.namedTerms = scaleAndBiasTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
