// Step 19, prefilter: the environment averaged over the GGX lobe around the reflection
// direction, the first factor of the split sum (what one mip of uPrefilterMap stores).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include "pbrlab/ibl_reference.h"

using namespace pbrlab;

namespace {

// The reference solution in double, reading the same environment texels (mip 0) the shader
// reads: N = V = R, Hammersley-driven GGX half vectors, L = reflect(-V, H), weights N.L.
glm::dvec3 prefilter(const CubeSampler& env, const glm::dvec3& R, double roughness,
                     std::uint32_t sampleCount) {
    const glm::dvec3 N = R, V = R;
    const std::uint32_t n = std::max(sampleCount, 1u);
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const glm::dvec3 H = ref::importanceSampleGGX(ref::hammersley(i, n), N, roughness);
        const glm::dvec3 L = 2.0 * glm::dot(V, H) * H - V;
        const double NdotL = glm::dot(N, L);
        if (NdotL > 0.0) {
            sum += env.sample(L, 0.0) * NdotL;
            weight += NdotL;
        }
    }
    return weight > 0.0 ? sum / weight : env.sample(R, 0.0);
}

// The samples uniform as the shader receives it (an int, clamped to the declared range).
std::uint32_t samples(const ReferenceContext& c) {
    return std::uint32_t(std::max(c.params.number("samples"), 1.0));
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "prefilter";
    d.step = 19;
    d.lab = "ibl";
    d.title = "Prefiltered environment (GGX lobe average)";
    d.function = "vec3 prefilterEnvironment(vec3 R, float roughness, uint sampleCount)";
    d.params = {
        intParam("samples", 64, 1, 4096, "GGX samples per pixel (the host's precompute uses 256)")};
    d.components = 3;
    d.display = {DisplayMode::HdrColor};
    d.needs = NeedsRoughness | NeedsEnvironment;
    d.skyBackground = true;
    d.scene = "sphere-grid";
    // Set from measurement (README.md): same samples on both sides, so GPU and CPU differ by
    // float rounding of the directions: <= 1.1e-4 on all but 0.1% of the pixels; a pixel or two
    // reach 0.7 where a sample rounds across a sharp edge (the sun's rim, a tile border, a face
    // edge). Correct variants measure the same; every mistake is off by >= 0.63 there.
    d.tolerance = {0.05, 1e-2, 1e-3};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        if (!c.ibl) return glm::dvec3(0);
        const glm::dvec3 R = glm::reflect(-s.view, s.normal);
        return prefilter(c.ibl->environment, R, s.roughness, samples(c));
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
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
