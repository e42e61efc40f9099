// vndf: sampling the GGX normals visible from V (Heitz 2018), graded by the distribution of
// the student's own samples.
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "pbrlab/ibl_reference.h"

using namespace pbrlab;

namespace {

// Smith's masking of GGX in its exact form, G1(V) = 2 / (1 + sqrt(1 + alpha^2 tan^2)): what
// makes D_V integrate to 1 (the lab's Schlick-GGX approximates it).
double smithG1(double NdotV, double alpha) {
    const double c2 = std::max(NdotV * NdotV, 1e-12), tan2 = (1 - c2) / c2;
    return 2 / (1 + std::sqrt(1 + alpha * alpha * tan2));
}

// The density of the visible normals per steradian, D_V(H) = G1(V) max(V.H, 0) D(H) / (N.V),
// with alpha floored as the solution floors it.
double visibleNormalDensity(const glm::dvec3& N, const glm::dvec3& V, const glm::dvec3& H,
                            double roughness) {
    const double alpha = std::max(roughness * roughness, 3.1622777e-4), a2 = alpha * alpha;
    const double NdotH = glm::dot(N, H), VdotH = glm::dot(V, H), NdotV = glm::dot(N, V);
    if (NdotH <= 0 || VdotH <= 0 || NdotV <= 0) return 0;
    const double d = NdotH * NdotH * (a2 - 1) + 1;
    const double D = a2 / (ref::kPi * d * d);
    return smithG1(NdotV, alpha) * VdotH * D / NdotV;
}

constexpr double kRim = 0.03;  // the view's band: how far below the rim a sample may round

// The distribution the contract asks for, tested on the student's own samples: a chi-square
// test against D_V for views from normal incidence to grazing (N.V 1, 0.7, 0.3, 0.05), four
// roughnesses and three normals (the frame's switch-over cone around +-z among them), 16384
// uniform Xi each, significance 1e-4 for the whole family (Sidak); and every sample a unit
// vector above the surface that faces V.
struct SamplerCase {
    glm::dvec3 N, V;
    double roughness;
};

// V at N.V = mu, turned about N to an azimuth drawn from `random` (each case its own).
glm::dvec3 viewAtCosine(const glm::dvec3& N, double mu, DomainRandom& random) {
    const glm::dvec3 axis = std::abs(N.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 T = glm::normalize(axis - N * glm::dot(N, axis));
    const glm::dvec3 B = glm::cross(N, T);
    const double turn = 2 * ref::kPi * random.uniform();
    return glm::dvec3(glm::vec3(glm::normalize(
        N * mu + std::sqrt(1 - mu * mu) * (T * std::cos(turn) + B * std::sin(turn)))));
}

// The samples of one case that the chi-square test judges: unit vectors with N.H > 0 and
// V.H > 0. Samples on the visible hemisphere's rim may fall up to kRim below N.H = 0 or
// V.H = 0 where sin and cos are approximate (the view's band, docs/web.md): they are left
// out; anything further, or not a unit vector, is counted in `invalid`.
std::vector<glm::dvec3> judgedSamples(const glm::dvec3* H, int count, const SamplerCase& k,
                                      int& invalid) {
    std::vector<glm::dvec3> samples;
    for (int i = 0; i < count; ++i) {
        const glm::dvec3& h = H[i];
        const bool unit = std::isfinite(h.x + h.y + h.z) && std::abs(glm::length(h) - 1) <= 1e-3;
        const double NdotH = glm::dot(k.N, h), VdotH = glm::dot(k.V, h);
        if (!unit || NdotH < -kRim || VdotH < -kRim)
            ++invalid;
        else if (NdotH > 0 && VdotH > 0)
            samples.push_back(h);
    }
    return samples;
}

std::vector<InvariantResult> visibleNormalInvariants(const Evaluator& evaluate) {
    constexpr int kSamples = 16384;
    const glm::dvec3 normals[] = {{0, 0, 1}, {0.02, 0.03, -1}, {0.3, -0.5, 0.8}};
    const double cosines[] = {1, 0.7, 0.3, 0.05}, roughnesses[] = {0.1, 0.3, 0.6, 1.0};
    std::vector<SamplerCase> cases;
    std::vector<glm::dvec3> H;
    DomainRandom random(2026);
    for (const glm::dvec3& n : normals) {
        // One evaluation per normal: 16 cases of 16384 samples fit a render target.
        std::vector<Surface> surfaces;
        for (double mu : cosines)
            for (double r : roughnesses) {
                const glm::dvec3 N = glm::dvec3(glm::vec3(glm::normalize(n)));
                const glm::dvec3 V = viewAtCosine(N, mu, random);
                cases.push_back({N, V, r});
                for (int i = 0; i < kSamples; ++i) {
                    Surface s;
                    s.covered = true;
                    s.normal = N;
                    s.view = V;
                    s.roughness = r;
                    s.extra = {random.uniform(), random.uniform(), 0, 1};
                    surfaces.push_back(s);
                }
            }
        const std::vector<glm::dvec3> drawn = evaluate.run(surfaces, "sample", {});
        H.insert(H.end(), drawn.begin(), drawn.end());
    }
    const double perCase = 1 - std::pow(1 - 1e-4, 1.0 / double(cases.size()));
    double smallest = 1;
    int invalid = 0;
    std::string worstCase;
    for (size_t c = 0; c < cases.size(); ++c) {
        const SamplerCase& k = cases[c];
        const std::vector<glm::dvec3> samples =
            judgedSamples(H.data() + c * kSamples, kSamples, k, invalid);
        // phi measured from V's tangential direction (any direction at normal incidence).
        glm::dvec3 tangent = k.V - k.N * glm::dot(k.N, k.V);
        if (glm::length(tangent) < 1e-6) tangent = glm::cross(k.N, glm::dvec3(0.6, 0.8, 0));
        const ref::ChiSquareTest t = ref::directionChiSquare(
            samples, k.N, tangent, k.roughness,
            [&](const glm::dvec3& h) { return visibleNormalDensity(k.N, k.V, h, k.roughness); });
        invalid += t.invalid;
        if (t.pValue < smallest) {
            smallest = t.pValue;
            char name[128];
            std::snprintf(name, sizeof name, "N (%.2g, %.2g, %.2g), N.V %.2g, roughness %.1f",
                          k.N.x, k.N.y, k.N.z, glm::dot(k.N, k.V), k.roughness);
            worstCase = name;
        }
    }
    char expected[64];
    std::snprintf(expected, sizeof expected, ">= %.2g (significance 1e-4 for all %zu)", perCase,
                  cases.size());
    return {{"chi-square p-value of the samples against D_V(H) = G1(V) max(V.H, 0) D(H) / "
             "(N.V), smallest over " +
                 std::to_string(cases.size()) + " cases (" + worstCase + ")",
             smallest, expected, smallest >= perCase && invalid == 0,
             "the half vectors do not follow the distribution of visible normals"},
            {"samples that are not unit vectors above the surface facing V (0.03 allowed at the "
             "rim; of " +
                 std::to_string(cases.size() * kSamples) + ")",
             double(invalid), "0", invalid == 0,
             "H must be normalised, with N.H > 0 and V.H > 0: a visible microfacet faces the "
             "viewer"}};
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Visible-normal sampling (Heitz 2018)";
    d.components = 3;
    d.display = {DisplayMode::Grey, 0, 1};
    d.needs = NeedsRoughness;
    d.scene = "sphere-grid";
    // What every correct sampler shares, whatever its mapping of Xi: |H| = 1, N.H >= 0 and
    // V.H >= 0, so the reference is 0. The band is 0.03: at the disk's rim sqrt(1 - t1^2 - t2^2)
    // turns the 2^-11 error GLSL allows sin and cos into up to 0.02 (measured 1.2e-7 on the
    // desktop, 0.010 on 5 of 262144 pixels in the browser's SwiftShader, docs/web.md); the mistakes
    // reach 0.84 (README.md).
    d.tolerance = {3e-2, 0, 0};
    d.reference = [](const Surface&, const ReferenceContext&) { return glm::dvec3(0); };
    // x: Xi.x from 0 to 1, y: roughness 0.05 to 1, with Xi.y, N and V (N.V from 0.02 to 1) of
    // each pixel's own.
    d.probe.xAxis = "Xi.x 0..1 (Xi.y, N and V vary per pixel)";
    d.probe.yAxis = "roughness 0.05..1";
    d.probe.width = 65;
    d.probe.height = 33;
    d.probe.at = [](double x, double y) {
        const int index = int(std::lround(y * 32)) * 65 + int(std::lround(x * 64));
        DomainRandom r(std::uint64_t(index) + 1);
        Surface s;
        s.covered = true;
        s.normal = r.direction();
        s.view = r.around(s.normal, 0.02, 1);
        s.roughness = 0.05 + 0.95 * y;
        s.extra = {x, r.uniform(), 0, 1};
        return s;
    };
    // Xi anywhere in the unit square, N anywhere, V in its hemisphere, roughness 0.05 to 1.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.view = r.around(s.normal, 0, 1);
        s.roughness = r.range(0.05, 1);
        s.extra = {r.uniform(), r.uniform(), 0, 1};
        return s;
    };
    d.extraViews = {"sample"};
    d.invariants = visibleNormalInvariants;
    d.extraName = "Xi";
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
