// prefilter: the environment averaged over the GGX lobe around the reflection
// direction, the first factor of the split sum (what one mip of uPrefilterMap stores).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "pbrlab/ibl_reference.h"

using namespace pbrlab;

namespace {

// The samples uniform as the shader receives it (an int, clamped to the declared range).
std::uint32_t samples(const ReferenceContext& c) {
    return std::uint32_t(std::max(c.params.number("samples"), 1.0));
}

// The reference's lobe average with its weights N.L raised to `weight` (1: the reference) and
// divided by the mean weight sum(N.L^weight) / n raised to `normalised` (1: the reference, a
// weighted average; 0: the weighted sum divided by the sample count): the parts of the formula
// feedback names (ModuleDesc::namedTerms).
glm::dvec3 lobeAverage(const Surface& s, const ReferenceContext& c, double weight,
                       double normalised) {
    if (!c.ibl) return glm::dvec3(0);
    const ref::CubeEnvironment env(c.ibl->environment);
    const glm::dvec3 R = glm::reflect(-s.view, s.normal);
    const std::uint32_t n = samples(c);
    glm::dvec3 sum(0.0);
    double total = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::dvec3 H = ref::importanceSampleGGX(ref::hammersley(i, n), R, s.roughness);
        const glm::dvec3 L = 2.0 * glm::dot(R, H) * H - R;
        const double NdotL = glm::dot(R, L);
        if (NdotL <= 0.0) continue;
        const double w = std::pow(NdotL, weight);
        sum += env.radiance(L) * w;
        total += w;
    }
    if (total <= 0.0) return env.radiance(R);
    return sum / double(n) / std::pow(total / double(n), normalised);
}

// Graded by convergence (README.md, "Grading"): on the soft sky, at 4, 64 and 1024
// samples, within 5 sigma / sqrt(n) of the converged lobe average (sigma of the ratio
// estimator by the delta method), + 1% for what filtered importance sampling's blur and
// texel filtering leave; the mean error must fall at least 3x from 4 to 1024.
EstimatorSpec convergence() {
    EstimatorSpec e;
    e.samplesParam = "samples";
    e.sampleCounts = {4, 64, 1024};
    e.converged = [](const Surface& s, const ReferenceContext& c, std::uint32_t samples) {
        if (!c.ibl) return Estimate{};
        const ref::CubeEnvironment env(c.ibl->environment);
        const glm::dvec3 R = glm::reflect(-s.view, s.normal);
        const ref::Moments m = ref::prefilterMoments(env, R, s.roughness, samples);
        return Estimate{m.mean, m.sigma, m.error};
    };
    // 4% of the points may be outside the band: Chebyshev's bound for any correct estimator
    // (with the true sigma, P(|error| > 5 sigma / sqrt(n)) <= 1/25), on the random inputs,
    // whose errors are independent (grading/estimator_convergence.cpp): there correct estimators
    // reached 2.1% (mc_specular, one set of random numbers for the whole picture, docs/grading.md).
    e.systematic = {1e-3, 1e-2, 0, 0.04};
    // At 65536 samples filtered importance sampling reads LOD 0: its blur, what the 1% is
    // for, is gone, and a lobe of the wrong width hid inside it (L = 2.2 (V.H) H - V, about
    // 8% narrower: 1.12x the 1% band at 65536). With 0.3% there (mc_specular's): that lobe
    // 1.65x, 4 of the 28 points outside; every correct variant at most 0.33x (docs/grading.md).
    e.systematicAtLargestCount = Tolerance{1e-3, 3e-3, 0, 0.04};
    return e;
}

// Named terms for feedback (ModuleDesc::namedTerms): the lobe average with each sample's N.L
// weight, or the division by the mean weight, at another power.
std::vector<NamedTerm> lobeTerms() {
    NamedTerm weight, mean;
    weight.symbol = "N.L";
    weight.name = "the N.L weight of each sample";
    weight.value = [](const Surface& s, const ReferenceContext& c, double e) {
        return lobeAverage(s, c, e, 1);
    };
    mean.symbol = "sum(N.L) / n";
    mean.name =
        "the division by the mean weight sum(N.L) / n (the weighted sum divided by the sample "
        "count instead of the sum of weights)";
    mean.value = [](const Surface& s, const ReferenceContext& c, double e) {
        return lobeAverage(s, c, 1, e);
    };
    return {weight, mean};
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Prefiltered environment (GGX lobe average)";
    d.params = {intParam("samples", 64, 1, 65536,
                         "GGX samples per pixel (the host's precompute uses 256)")};
    d.components = 3;
    d.display = {DisplayMode::HdrColor};
    d.needs = NeedsRoughness | NeedsEnvironment;
    d.skyBackground = true;
    d.scene = "sphere-grid";
    // The quality report (the shipped sky, same samples as the reference): float rounding of
    // the directions, <= 1.1e-4 on all but 0.1% of the pixels (README.md).
    d.tolerance = {1e-3, 2e-3, 0, 2e-3};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        if (!c.ibl) return glm::dvec3(0);
        const glm::dvec3 R = glm::reflect(-s.view, s.normal);
        // The reference solution in double (ref::prefilterEnvironment), reading the same
        // environment texels (mip 0) the shader reads.
        return ref::prefilterEnvironment(ref::CubeEnvironment(c.ibl->environment), R, s.roughness,
                                         samples(c));
    };
    // x: R's elevation from the nadir (0) through the horizon (0.5) to the zenith (1), in the
    // vertical plane of the shipped sky's sun (azimuth 130 degrees, elevation 35: column 100 of
    // 145 looks straight at it); y: roughness 0 to 1. N = V = R there, as in the precompute.
    d.probe.xAxis = "elevation of R -90..90 degrees, towards the sun's azimuth";
    d.probe.yAxis = "roughness 0..1";
    d.probe.width = 145;
    d.probe.height = 33;
    d.probe.at = [](double x, double y) {
        const double azimuth = 130.0 * std::numbers::pi / 180.0;
        const double elevation = std::numbers::pi * (x - 0.5);
        Surface s;
        s.covered = true;
        s.normal = {std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                    -std::cos(elevation) * std::cos(azimuth)};
        s.view = s.normal;  // R = reflect(-V, N) = N
        s.roughness = y;
        return s;
    };
    d.estimator = convergence();
    d.namedTerms = lobeTerms();
    // N anywhere, V in its hemisphere, roughness 0 to 1.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.view = r.around(s.normal, 0, 1);
        s.roughness = r.uniform();
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
