// importance: GGX importance sampling of the half vector H around N.
#include "pbrlab/module.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>
#include <vector>

#include "pbrlab/ibl_reference.h"

using namespace pbrlab;

namespace {

constexpr float kXiMax = 0.999755859375f;  // 1 - 2^-12: the scene's largest Xi.y (view.glsl)
constexpr float kTurn = 0.236068f;         // sqrt(5) - 2: the view's second sample, Xi.x + this

// What the view computes (view.glsl), from quantities that do not depend on the tangent frame:
//   x: N.H of the sample for Xi (cos theta_h, set by Xi.y alone);
//   y: |H| (1: a unit vector);
//   z: the dot product of the sideways parts (perpendicular to N) of the samples for Xi and
//      for (Xi.x + kTurn, Xi.y): sin^2(theta) cos(2 pi kTurn) in any frame when phi = 2 pi
//      Xi.x (or -2 pi Xi.x, a mirrored frame).
glm::dvec3 frameFreeView(const Surface& s) {
    // Probe, domain and stability inputs carry Xi in extra, clamped to the unit square; the
    // scene's uv, with Xi.y stopped at kXiMax.
    const bool given = s.extra != glm::dvec4(0);
    const double x = given ? std::clamp(s.extra.x, 0.0, 1.0) : s.uv.x;
    const double y = given ? std::clamp(s.extra.y, 0.0, 1.0) : std::min(float(s.uv.y), kXiMax);
    const glm::dvec3 N = s.normal;
    const glm::dvec3 H = ref::importanceSampleGGX({x, y}, N, s.roughness);
    // fract(Xi.x + kTurn) as the shader computes it in float.
    const float turned = float(x) + kTurn;
    const glm::dvec3 H2 =
        ref::importanceSampleGGX({double(turned - std::floor(turned)), y}, N, s.roughness);
    const glm::dvec3 t1 = H - N * glm::dot(N, H), t2 = H2 - N * glm::dot(N, H2);
    return {glm::dot(N, H), glm::length(H), glm::dot(t1, t2)};
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

// The distribution the contract asks for, tested on the student's own samples: a chi-square
// test against D(h) (N.h) for every normal the probe uses and four roughnesses (4096 uniform
// Xi each), significance 1e-4 for the whole family (Sidak: 1 - (1 - 1e-4)^(1/32) per case),
// so a correct sampler fails it with probability 1e-4; and every sample a unit vector above
// the surface.
std::vector<InvariantResult> ggxSamplingInvariants(const Evaluator& evaluate) {
    constexpr int kSamples = 4096;
    const glm::dvec3 normals[] = {{0, 0, 1}, {0, 0, -1}, {0.02, 0.03, 1},  {0.0447, 0, 1},
                                  {1, 0, 0}, {0, 1, 0},  {0.3, -0.5, 0.8}, {-0.6, 0.2, -0.75}};
    const double roughnesses[] = {0.1, 0.3, 0.6, 1.0};
    std::vector<Surface> surfaces;
    surfaces.reserve(std::size(normals) * std::size(roughnesses) * kSamples);
    DomainRandom random(2024);
    for (const glm::dvec3& n : normals)
        for (double r : roughnesses)
            for (int i = 0; i < kSamples; ++i) {
                Surface s;
                s.covered = true;
                s.normal = glm::dvec3(glm::vec3(glm::normalize(n)));  // what the GPU receives
                s.roughness = r;
                s.extra = {random.uniform(), random.uniform(), 0, 1};
                surfaces.push_back(s);
            }
    const std::vector<glm::dvec3> H = evaluate.run(surfaces, "sample", {});
    const int cases = int(std::size(normals) * std::size(roughnesses));
    const double perCase = 1 - std::pow(1 - 1e-4, 1.0 / cases);
    double smallest = 1;
    int invalid = 0;
    std::string worstCase;
    for (int c = 0; c < cases; ++c) {
        const std::vector<glm::dvec3> samples(H.begin() + long(c) * kSamples,
                                              H.begin() + long(c + 1) * kSamples);
        const Surface& s = surfaces[size_t(c) * kSamples];
        const ref::ChiSquareTest t = ref::ggxHalfVectorChiSquare(samples, s.normal, s.roughness);
        invalid += t.invalid;
        if (t.pValue < smallest) {
            smallest = t.pValue;
            char name[96];
            std::snprintf(name, sizeof name, "N (%.2g, %.2g, %.2g), roughness %.1f", s.normal.x,
                          s.normal.y, s.normal.z, s.roughness);
            worstCase = name;
        }
    }
    char expected[64];
    std::snprintf(expected, sizeof expected, ">= %.2g (significance 1e-4 for all %d)", perCase,
                  cases);
    return {{"chi-square p-value of the samples against D(h) (n.h), smallest over 32 cases (" +
                 worstCase + ")",
             smallest, expected, smallest >= perCase && invalid == 0,
             "the half vectors do not follow the GGX distribution"},
            {"samples that are not unit vectors above the surface (of " +
                 std::to_string(cases * kSamples) + ")",
             double(invalid), "0", invalid == 0, "H must be normalised and have N.H > 0"}};
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "GGX importance sampling";
    d.components = 3;
    d.nonNegative = false;  // N.H < 0 is a wrong sample, not a negative error
    d.display = {DisplayMode::Grey, 0, 1};
    d.needs = NeedsRoughness;
    d.scene = "sphere-grid";
    // Band: +- 1e-3 of each quantity, at least 1e-6, or the spread of 8 ulps of Xi and N
    // (README.md). Roughness 0 is an extreme input (the robustness sweep): there the floors on
    // alpha^2 legitimately differ between solutions.
    d.tolerance = {1e-6, 1e-3, 8};
    d.reference = [](const Surface& s, const ReferenceContext&) { return frameFreeView(s); };
    // x: Xi.y from 0 to 1 - 2^-12 (theta from 0 to its largest in the teaching domain); y:
    // roughness 0 to 1. Behind the plot, each pixel also takes its own Xi.x and its own N
    // (probeNormal): a correct sampler gives the same N.H whatever they are, a frame bug
    // does not.
    d.probe.xAxis = "Xi.y 0..1-2^-12 (Xi.x and N vary per pixel)";
    d.probe.yAxis = "roughness 0.05..1";
    d.probe.width = 65;
    d.probe.height = 33;
    d.probe.at = [](double x, double y) {
        const int col = int(std::lround(x * 64)), row = int(std::lround(y * 32));
        const int index = row * 65 + col;
        Surface s;
        s.covered = true;
        s.normal = probeNormal(index);
        s.roughness = 0.05 + 0.95 * y;
        const double xiX = index * 0.7548776662466927 - std::floor(index * 0.7548776662466927);
        // Xi.y = x (1 - 2^-12): exact in float for x = k / 64. extra.w = 1 marks probe inputs
        // (a pixel with extra = 0 would read the uv instead).
        s.extra = {xiX, x * double(kXiMax), 0, 1};
        return s;
    };
    // Xi anywhere in the unit square (24-bit uniform), N anywhere, roughness 0.05 to 1.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.roughness = r.range(0.05, 1);
        s.extra = {r.uniform(), r.uniform(), 0, 1};
        return s;
    };
    // The distribution itself: a chi-square test of the student's samples against the GGX
    // density D(h) (N.h), in any frame (sample.glsl returns H).
    d.extraViews = {"sample"};
    d.invariants = [](const Evaluator& evaluate) { return ggxSamplingInvariants(evaluate); };
    d.extraName = "Xi";  // the point of the unit square the function maps (extra.xy), for feedback
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
