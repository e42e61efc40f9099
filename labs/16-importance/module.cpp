// Step 16, importance: GGX importance sampling of the half vector H around N.
#include "pbrlab/module.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "pbrlab/ibl_reference.h"

using namespace pbrlab;

namespace {

constexpr float kXiMax = 0.999755859375f;  // 1 - 2^-12: the scene's largest Xi.y (view.glsl)
constexpr int kRing = 8;                   // samples around N in the lopsidedness measure

// What the view computes (view.glsl), from quantities that do not depend on the tangent frame:
//   x: N.H of the sample for Xi (cos theta_h);
//   y: the length of the sideways part (perpendicular to N) of the mean of the kRing samples
//      with Xi.y and Xi.x + k / kRing: 0 when phi turns once around N.
glm::dvec3 frameFreeView(const Surface& s) {
    // Probe and stability inputs clamped to the unit square; the scene's uv with Xi.y stopped
    // at kXiMax.
    const bool given = s.extra != glm::dvec4(0);
    const double x = given ? std::clamp(s.extra.x, 0.0, 1.0) : s.uv.x;
    const double y = given ? std::clamp(s.extra.y, 0.0, 1.0) : std::min(float(s.uv.y), kXiMax);
    const glm::dvec3 N = s.normal;
    const glm::dvec3 H = ref::importanceSampleGGX({x, y}, N, s.roughness);
    glm::dvec3 ring(0);
    for (int k = 0; k < kRing; ++k)
        // (k + x) / 8 as the shader computes it in float.
        ring += ref::importanceSampleGGX({double((float(k) + float(x)) / float(kRing)), y}, N,
                                         s.roughness);
    ring /= double(kRing);
    const glm::dvec3 sideways = ring - N * glm::dot(N, ring);
    return {glm::dot(N, H), glm::length(sideways), 0};
}

// Probe normals: the axes, the frame's switch-over cone around +-z (|N.z| >= 0.999) and its
// edge, and directions spread over the sphere (golden-angle spiral), one per pixel in turn.
glm::dvec3 probeNormal(int index) {
    static const std::array<glm::dvec3, 10> fixed = {
        glm::dvec3(0, 0, 1),       glm::dvec3(0, 0, -1),        glm::dvec3(1, 0, 0),
        glm::dvec3(0, 1, 0),       glm::dvec3(-1, 0, 0),        glm::dvec3(0, -1, 0),
        glm::dvec3(0.02, 0.03, 1), glm::dvec3(0.03, -0.01, -1), glm::dvec3(0.0447, 0, 1),
        glm::dvec3(0.3, 0.2, 0.93)};
    const int k = index % 32;
    if (k < int(fixed.size())) return glm::normalize(fixed[size_t(k)]);
    const double z = 1 - 2 * (index * 0.6180339887498949 - std::floor(index * 0.6180339887498949));
    const double phi = index * 2.399963229728653, r = std::sqrt(std::max(0.0, 1 - z * z));
    return glm::normalize(glm::dvec3(r * std::cos(phi), r * std::sin(phi), z));
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "importance";
    d.step = 16;
    d.lab = "ibl";
    d.title = "GGX importance sampling";
    d.function = "vec3 importanceSampleGGX(vec2 Xi, vec3 N, float roughness)";
    d.components = 2;
    d.nonNegative = false;  // N.H < 0 is a wrong sample, not a negative error
    d.display = {DisplayMode::Grey, 0, 1};
    d.needs = NeedsRoughness;
    d.scene = "sphere-grid";
    // Float rounding gives 1.6e-5 (2e-7 absolute); the seed's unguarded formula differs by
    // 2.05e-4 on the probe's roughness-0 row (the reference floors alpha^2 at 1e-7). 1e-3 is 5x
    // that; every mistake is off by >= 0.6 (README.md).
    d.tolerance = {1e-2, 1e-3};
    d.reference = [](const Surface& s, const ReferenceContext&) { return frameFreeView(s); };
    // x: Xi.y from 0 to 1 - 2^-12 (theta from 0 to its largest in the teaching domain); y:
    // roughness 0 to 1. Behind the plot, each pixel also takes its own Xi.x and its own N
    // (probeNormal): a correct sampler gives the same N.H whatever they are, a frame bug
    // does not.
    d.probe.xAxis = "Xi.y 0..1-2^-12 (Xi.x and N vary per pixel)";
    d.probe.yAxis = "roughness 0..1";
    d.probe.width = 65;
    d.probe.height = 33;
    d.probe.at = [](double x, double y) {
        const int col = int(std::lround(x * 64)), row = int(std::lround(y * 32));
        const int index = row * 65 + col;
        Surface s;
        s.covered = true;
        s.normal = probeNormal(index);
        s.roughness = y;
        const double xiX = index * 0.7548776662466927 - std::floor(index * 0.7548776662466927);
        // Xi.y = x (1 - 2^-12): exact in float for x = k / 64. extra.w = 1 marks probe inputs
        // (a pixel with extra = 0 would read the uv instead).
        s.extra = {xiX, x * double(kXiMax), 0, 1};
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
