// CPU references of the lab "ibl" in double precision. The estimators (hammersley ...
// integrateBRDF, ambientIBL) mirror the GLSL reference solutions labs/hammersley ...
// labs/split_sum formula for formula and guard for guard; the quadratures (brdfLutExact,
// irradianceAt, projectSH9) are the ground truth those estimators converge to.
#include "pbrlab/ibl_reference.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <utility>
#include <vector>

#include "util/error.h"

namespace pbrlab::ref {

namespace {

constexpr double kTwoPi = 2.0 * kPi;

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre recurrence).
const GaussRule& gauss8() {
    static const GaussRule rule = gaussLegendre(8);
    return rule;
}
const GaussRule& gauss16() {
    static const GaussRule rule = gaussLegendre(16);
    return rule;
}

// Calls f(x, weight) for the nodes of `rule` mapped onto [a, b].
template <class F>
void forGaussNodes(const GaussRule& rule, double a, double b, const F& f) {
    const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
    for (size_t i = 0; i < rule.x.size(); ++i) f(mid + half * rule.x[i], half * rule.w[i]);
}

// Composite 8-point Gauss-Legendre on [a, b] with ceil(nodes / 8) equal panels.
template <class F>
void forCompositeGauss(double a, double b, int nodes, const F& f) {
    const int panels = std::max(1, (nodes + 7) / 8);
    for (int p = 0; p < panels; ++p)
        forGaussNodes(gauss8(), a + (b - a) * p / panels, a + (b - a) * (p + 1) / panels, f);
}

// The tangent frame of importanceSampleGGX (the seed's): up = z unless N is within
// acos(0.999) ~ 2.6 degrees of +-z, where cross(z, N) would be too short; then up = x.
void tangentFrame(const dvec3& N, dvec3& T, dvec3& B) {
    const dvec3 up = std::abs(N.z) < 0.999 ? dvec3(0.0, 0.0, 1.0) : dvec3(1.0, 0.0, 0.0);
    T = glm::normalize(glm::cross(up, N));
    B = glm::cross(N, T);
}

}  // namespace

double ggxAlpha2(double roughness) {
    const double a = roughness * roughness;
    return std::max(a * a, kMinAlpha2);
}

namespace {

// D as a function of N.H, the same formula and grouping as distributionGGX.
double ggxD(double NdotH, double roughness) {
    const double a2 = ggxAlpha2(roughness);
    const double c = std::max(NdotH, 0.0);
    const double c2 = c * c;
    const double d = (1.0 - c2) + c2 * a2;
    return a2 / (kPi * d * d);
}

}  // namespace

// ---- 15 hammersley --------------------------------------------------------------------------

double radicalInverse2(std::uint32_t i) {
    // Reverse the 32 bits by swapping halves, then bytes, nibbles, pairs and single bits.
    std::uint32_t b = (i << 16) | (i >> 16);
    b = ((b & 0x00FF00FFu) << 8) | ((b & 0xFF00FF00u) >> 8);
    b = ((b & 0x0F0F0F0Fu) << 4) | ((b & 0xF0F0F0F0u) >> 4);
    b = ((b & 0x33333333u) << 2) | ((b & 0xCCCCCCCCu) >> 2);
    b = ((b & 0x55555555u) << 1) | ((b & 0xAAAAAAAAu) >> 1);
    return double(b) * (1.0 / 4294967296.0);
}

dvec2 hammersley(std::uint32_t i, std::uint32_t n) {
    // Guard: n = 0 would divide by zero; treated as 1 (max(n, 1u) in GLSL).
    return {double(i) / double(std::max(n, 1u)), radicalInverse2(i)};
}

// ---- 16 importance --------------------------------------------------------------------------

dvec3 importanceSampleGGX(const dvec2& Xi, const dvec3& N, double roughness) {
    // Guard: alpha^2 floored (ggxAlpha2) so that at roughness 0 the denominator below stays
    // positive at Xi.y = 1 (else 0/0); Xi clamped to [0, 1] so no square root goes negative.
    const double a2 = ggxAlpha2(roughness);
    const double x = std::clamp(Xi.x, 0.0, 1.0), y = std::clamp(Xi.y, 0.0, 1.0);
    const double phi = kTwoPi * x;
    // cos^2 = (1 - y) / (1 + (a2 - 1) y) and sin^2 = a2 y / (same), with the denominator
    // regrouped as (1 - y) + a2 y: sin(theta) then never comes from 1 - cos^2, which loses all
    // its digits in float for a small lobe (roughness 0.05: sin^2 ~ 6e-6).
    const double oneMinusY = 1.0 - y;
    const double denom = oneMinusY + a2 * y;
    const double cosTheta = std::sqrt(oneMinusY / denom);
    const double sinTheta = std::sqrt(a2 * y / denom);
    dvec3 T, B;
    tangentFrame(N, T, B);
    const dvec3 H = T * (sinTheta * std::cos(phi)) + B * (sinTheta * std::sin(phi)) + N * cosTheta;
    return glm::normalize(H);
}

double pdfGGXHalfVector(double NdotH, double roughness) {
    return ggxD(NdotH, roughness) * std::max(NdotH, 0.0);
}

double pdfGGXReflected(double NdotH, double VdotH, double roughness) {
    // V.H <= 0: no reflected direction above the microfacet, density 0 (not a division by 0).
    if (VdotH <= 0.0) return 0.0;
    return pdfGGXHalfVector(NdotH, roughness) / (4.0 * VdotH);
}

double geometrySchlickGGXIBL(double NdotX, double roughness) {
    const double x = std::max(NdotX, 0.0);
    // k = alpha / 2 with the alpha floor of D and of the sampling (sqrt(kMinAlpha2)): the
    // masking then belongs to the lobe that is really sampled. Guard: with k = 0 at roughness
    // 0, 0/0 at N.X = 0, and the LUT at N.V -> 0 exceeds 1 (A + B = 2.1 at N.V = 1e-4,
    // measured) because the floored lobe is wider than the view's angle above the horizon.
    const double k = std::max(roughness * roughness, kIblMinAlpha) / 2.0;
    return x / (x * (1.0 - k) + k);
}

double geometrySmithIBL(double NdotV, double NdotL, double roughness) {
    return geometrySchlickGGXIBL(NdotV, roughness) * geometrySchlickGGXIBL(NdotL, roughness);
}

dvec3 fresnelSchlickRoughness(double cosTheta, const dvec3& F0, double roughness) {
    return F0 + (glm::max(dvec3(1.0 - roughness), F0) - F0) *
                    std::pow(std::clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}

// ---- environments ---------------------------------------------------------------------------

namespace {

// Throws pbrlab::Error on an empty or inconsistent image (what every equirectangular lookup
// here needs).
void validateEquirect(const Image& image) {
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0 ||
        image.pixels.size() != size_t(image.width) * size_t(image.height) * size_t(image.channels))
        throw Error("equirectangular environment: empty or inconsistent image (" +
                    std::to_string(image.width) + " x " + std::to_string(image.height) + ", " +
                    std::to_string(image.channels) + " channels)");
}

}  // namespace

EquirectEnvironment::EquirectEnvironment(Image image) : image_(std::move(image)) {
    validateEquirect(image_);
}

dvec3 EquirectEnvironment::texel(int x, int y) const {
    return equirectTexel(image_, x, y);
}

dvec3 EquirectEnvironment::radiance(const dvec3& dir) const {
    return equirectRadiance(image_, dir);
}

dvec3 equirectTexel(const Image& image, int x, int y) {
    x %= image.width;
    if (x < 0) x += image.width;
    y = std::clamp(y, 0, image.height - 1);
    if (image.channels < 3) return dvec3(image.at(x, y, 0));
    return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

dvec3 equirectRadiance(const Image& image, const dvec3& dir) {
    const dvec2 uv = equirectUv(dir);
    // Texel centres sit at (i + 0.5) / size, as in GL.
    const double x = uv.x * image.width - 0.5, y = uv.y * image.height - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    const double fx = x - x0, fy = y - y0;
    const int ix = int(x0), iy = int(y0);
    const dvec3 top = glm::mix(equirectTexel(image, ix, iy), equirectTexel(image, ix + 1, iy), fx);
    const dvec3 bottom =
        glm::mix(equirectTexel(image, ix, iy + 1), equirectTexel(image, ix + 1, iy + 1), fx);
    return glm::mix(top, bottom, fy);
}

dvec2 equirectUv(const dvec3& dir) {
    return {std::atan2(dir.x, -dir.z) / kTwoPi + 0.5,
            std::acos(std::clamp(dir.y, -1.0, 1.0)) / kPi};
}

dvec3 equirectDirection(const dvec2& uv) {
    const double phi = (uv.x - 0.5) * kTwoPi, theta = uv.y * kPi;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// ---- 17 mc_specular -------------------------------------------------------------------------

dvec3 specularIBLReference(const Environment& env, const dvec3& N, const dvec3& V, const dvec3& F0,
                           double roughness, std::uint32_t sampleCount) {
    // Guard: N.V floored at 1e-4, it divides the weight (N.V = 0 would give x/0).
    const double NdotV = std::max(glm::dot(N, V), kIblMinNdotV);
    const std::uint32_t n = std::max(sampleCount, 1u);  // guard: 0 samples would give 0/0
    dvec3 sum(0.0);
    for (std::uint32_t i = 0; i < n; ++i) {
        const dvec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        const double VdotH = glm::dot(V, H);
        const dvec3 L = 2.0 * VdotH * H - V;  // reflect(-V, H)
        const double NdotL = glm::dot(N, L);
        if (NdotL <= 0.0) continue;  // below the horizon: no light arrives from there
        // Guards: N.H floored (it divides; importance samples have N.H > 0 except at
        // Xi.y = 1); V.H clamped at 0 (V below the horizon can give V.H < 0 with N.L > 0).
        const double NdotH = std::max(glm::dot(N, H), kIblMinNdotH);
        const double VdotHc = std::max(VdotH, 0.0);
        const double G = geometrySmithIBL(NdotV, NdotL, roughness);
        const dvec3 F = fresnelSchlick(VdotHc, F0);
        sum += env.radiance(L) * F * (G * VdotHc / (NdotH * NdotV));
    }
    return sum / double(n);
}

namespace {

// The randomised quasi-Monte Carlo of the Moments functions (ibl_reference.h).
constexpr std::uint32_t kReplicates = 16;

std::uint64_t splitMix(std::uint64_t x) {
    x += 0x9E3779B97F4A7C15ull;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

class Replicates {
public:
    // Seeded by the point's inputs (their bits), so a point's truth is a function of it alone.
    Replicates(std::initializer_list<double> inputs, std::uint32_t m)
        : perSet_(std::max(m / kReplicates, 1u)) {
        std::uint64_t h = 0x5EED;
        for (double v : inputs) {
            std::uint64_t bits = 0;
            std::memcpy(&bits, &v, sizeof bits);
            h = splitMix(h ^ bits);
        }
        for (dvec2& s : shift_) {
            h = splitMix(h);
            s.x = double(h >> 11) * 0x1p-53;
            h = splitMix(h);
            s.y = double(h >> 11) * 0x1p-53;
        }
    }
    std::uint32_t perSet() const { return perSet_; }
    // Point j of set r, in [0, 1)^2.
    dvec2 xi(std::uint32_t r, std::uint32_t j) const {
        const dvec2 p = hammersley(j, perSet_) + shift_[r];
        return p - glm::floor(p);
    }

private:
    std::uint32_t perSet_;
    dvec2 shift_[kReplicates];
};

// The standard error of the mean of kReplicates independent estimates.
dvec3 standardError(const std::array<dvec3, kReplicates>& estimates, const dvec3& mean) {
    dvec3 sum(0.0);
    for (const dvec3& e : estimates) sum += (e - mean) * (e - mean);
    return glm::sqrt(sum / double(kReplicates * (kReplicates - 1)));
}

}  // namespace

Moments estimatorMoments(std::initializer_list<double> inputs, std::uint32_t m,
                         const std::function<dvec3(const dvec2& xi)>& sample) {
    const Replicates sets(inputs, m);
    const std::uint32_t n = sets.perSet() * kReplicates;
    dvec3 sum(0.0), sum2(0.0);
    std::array<dvec3, kReplicates> estimates{};
    for (std::uint32_t r = 0; r < kReplicates; ++r) {
        dvec3 setSum(0.0);
        for (std::uint32_t j = 0; j < sets.perSet(); ++j) {
            const dvec3 x = sample(sets.xi(r, j));
            setSum += x;
            sum2 += x * x;
        }
        sum += setSum;
        estimates[r] = setSum / double(sets.perSet());
    }
    const dvec3 mean = sum / double(n);
    return {mean, glm::sqrt(glm::max(sum2 / double(n) - mean * mean, dvec3(0.0))),
            standardError(estimates, mean)};
}

Moments specularIBLMoments(const Environment& env, const dvec3& N, const dvec3& V, const dvec3& F0,
                           double roughness, std::uint32_t m) {
    // The same one-sample estimate as specularIBLReference, its first two moments.
    const double NdotV = std::max(glm::dot(N, V), kIblMinNdotV);
    return estimatorMoments(
        {N.x, N.y, N.z, V.x, V.y, V.z, F0.x, F0.y, F0.z, roughness}, m, [&](const dvec2& xi) {
            const dvec3 H = importanceSampleGGX(xi, N, roughness);
            const double VdotH = glm::dot(V, H);
            const dvec3 L = 2.0 * VdotH * H - V;
            const double NdotL = glm::dot(N, L);
            if (NdotL <= 0.0) return dvec3(0.0);
            const double NdotH = std::max(glm::dot(N, H), kIblMinNdotH);
            const double VdotHc = std::max(VdotH, 0.0);
            return env.radiance(L) * fresnelSchlick(VdotHc, F0) *
                   (geometrySmithIBL(NdotV, NdotL, roughness) * VdotHc / (NdotH * NdotV));
        });
}

Moments prefilterMoments(const Environment& env, const dvec3& R, double roughness,
                         std::uint32_t m) {
    const Replicates sets({R.x, R.y, R.z, roughness}, m);
    std::vector<dvec3> radiance;
    std::vector<double> weight;
    dvec3 sum(0.0);
    double total = 0.0;
    std::array<dvec3, kReplicates> setSum{};
    std::array<double, kReplicates> setTotal{};
    for (std::uint32_t r = 0; r < kReplicates; ++r)
        for (std::uint32_t j = 0; j < sets.perSet(); ++j) {
            const dvec3 H = importanceSampleGGX(sets.xi(r, j), R, roughness);
            const dvec3 L = 2.0 * glm::dot(R, H) * H - R;
            const double w = std::max(glm::dot(R, L), 0.0);
            const dvec3 x = w > 0 ? env.radiance(L) : dvec3(0.0);
            radiance.push_back(x);
            weight.push_back(w);
            sum += x * w;
            total += w;
            setSum[r] += x * w;
            setTotal[r] += w;
        }
    if (total <= 0.0) return {env.radiance(R), dvec3(0.0), dvec3(0.0)};
    const dvec3 mean = sum / total;
    dvec3 var(0.0);
    for (size_t i = 0; i < radiance.size(); ++i) {
        const dvec3 d = weight[i] * (radiance[i] - mean);
        var += d * d;
    }
    const double meanWeight = total / double(radiance.size());
    // Each set's ratio is an estimate of the mean (biased by O(1 / set size), far under its
    // spread); a set without weight (none of its points above the horizon: for sets of a
    // few points only) counts as the mean.
    std::array<dvec3, kReplicates> estimates{};
    for (std::uint32_t r = 0; r < kReplicates; ++r)
        estimates[r] = setTotal[r] > 0 ? setSum[r] / setTotal[r] : mean;
    return {mean, glm::sqrt(var / double(radiance.size())) / meanWeight,
            standardError(estimates, mean)};
}

Moments brdfLutMoments(double NdotV, double roughness, std::uint32_t m) {
    NdotV = std::clamp(NdotV, kIblMinNdotV, 1.0);
    const dvec3 N(0.0, 0.0, 1.0);
    const dvec3 V(std::sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    const std::uint32_t n = std::max(m, 1u);
    dvec2 sum(0.0), sum2(0.0);
    for (std::uint32_t i = 0; i < n; ++i) {
        const dvec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        const double VdotH = glm::dot(V, H);
        const dvec3 L = 2.0 * VdotH * H - V;
        if (L.z <= 0.0) continue;
        const double NdotH = std::max(H.z, kIblMinNdotH);
        const double VdotHc = std::clamp(VdotH, 0.0, 1.0);
        const double Gvis = geometrySmithIBL(NdotV, L.z, roughness) * VdotHc / (NdotH * NdotV);
        const double Fc = std::pow(1.0 - VdotHc, 5.0);
        const dvec2 x((1.0 - Fc) * Gvis, Fc * Gvis);
        sum += x;
        sum2 += x * x;
    }
    const dvec2 mean = sum / double(n);
    const dvec2 sigma = glm::sqrt(glm::max(sum2 / double(n) - mean * mean, dvec2(0.0)));
    return {dvec3(brdfLutExact(NdotV, roughness), 0.0), dvec3(sigma, 0.0)};
}

// ---- 18 irradiance --------------------------------------------------------------------------

dvec3 irradianceAt(const Environment& env, const dvec3& N, int thetaSteps) {
    thetaSteps = std::max(thetaSteps, 8);
    const int phiSteps = 4 * thetaSteps;
    dvec3 T, B;
    tangentFrame(N, T, B);
    std::vector<double> cosPhi(phiSteps), sinPhi(phiSteps);
    for (int j = 0; j < phiSteps; ++j) {
        const double phi = kTwoPi * (j + 0.5) / phiSteps;
        cosPhi[j] = std::cos(phi);
        sinPhi[j] = std::sin(phi);
    }
    dvec3 E(0.0);
    forCompositeGauss(0.0, kPi / 2.0, thetaSteps, [&](double theta, double w) {
        const double c = std::cos(theta), s = std::sin(theta);
        dvec3 ring(0.0);
        for (int j = 0; j < phiSteps; ++j)
            ring += env.radiance(T * (s * cosPhi[j]) + B * (s * sinPhi[j]) + N * c);
        // dl = sin(theta) dtheta dphi, times the cosine N.l = cos(theta).
        E += ring * (w * c * s * kTwoPi / phiSteps);
    });
    return E / kPi;
}

dvec3 irradianceAt(const Image& equirect, const dvec3& N) {
    validateEquirect(equirect);
    const int W = equirect.width, H = equirect.height;
    dvec3 E(0.0);
    for (int y = 0; y < H; ++y) {
        const double solidAngle =
            (kTwoPi / W) * (std::cos(kPi * y / H) - std::cos(kPi * (y + 1) / H));
        for (int x = 0; x < W; ++x) {
            const double c = glm::dot(N, equirectDirection({(x + 0.5) / W, (y + 0.5) / H}));
            if (c > 0.0) E += equirectTexel(equirect, x, y) * (c * solidAngle);
        }
    }
    return E / kPi;
}

std::array<double, 9> shBasis9(const dvec3& d) {
    // Real, orthonormal SH: K_l^m P_l^|m|(cos theta) times sqrt(2) cos(m phi) or sin(|m| phi),
    // written as polynomials in x, y, z (polar axis z).
    const double k0 = 0.5 / std::sqrt(kPi);           // sqrt(1 / 4pi)
    const double k1 = std::sqrt(3.0 / (4.0 * kPi));   // band 1
    const double k2 = 0.5 * std::sqrt(15.0 / kPi);    // xy, yz, xz
    const double k20 = 0.25 * std::sqrt(5.0 / kPi);   // 3z^2 - 1
    const double k22 = 0.25 * std::sqrt(15.0 / kPi);  // x^2 - y^2
    return {k0,
            k1 * d.y,
            k1 * d.z,
            k1 * d.x,
            k2 * d.x * d.y,
            k2 * d.y * d.z,
            k20 * (3.0 * d.z * d.z - 1.0),
            k2 * d.x * d.z,
            k22 * (d.x * d.x - d.y * d.y)};
}

SH9 projectSH9(const Environment& env, int thetaSteps) {
    thetaSteps = std::max(thetaSteps, 8);
    const int phiSteps = 2 * thetaSteps;
    SH9 sh;
    forCompositeGauss(-1.0, 1.0, thetaSteps, [&](double z, double w) {
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        for (int j = 0; j < phiSteps; ++j) {
            const double phi = kTwoPi * (j + 0.5) / phiSteps;
            const dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
            const dvec3 L = env.radiance(d);
            const auto Y = shBasis9(d);
            // dl = d(cos theta) dphi
            for (int k = 0; k < 9; ++k) sh.c[k] += L * (Y[k] * w * kTwoPi / phiSteps);
        }
    });
    return sh;
}

SH9 projectSH9(const Image& equirect) {
    validateEquirect(equirect);
    SH9 sh;
    const int W = equirect.width, H = equirect.height;
    // equirectDirection at texel centres, from per-column sines and cosines of phi.
    std::vector<double> sinPhi(static_cast<size_t>(W)), cosPhi(static_cast<size_t>(W));
    for (int x = 0; x < W; ++x) {
        const double phi = ((x + 0.5) / W - 0.5) * kTwoPi;
        sinPhi[size_t(x)] = std::sin(phi);
        cosPhi[size_t(x)] = std::cos(phi);
    }
    for (int y = 0; y < H; ++y) {
        const double solidAngle =
            (kTwoPi / W) * (std::cos(kPi * y / H) - std::cos(kPi * (y + 1) / H));
        const double theta = kPi * (y + 0.5) / H, st = std::sin(theta), ct = std::cos(theta);
        for (int x = 0; x < W; ++x) {
            const dvec3 d(st * sinPhi[size_t(x)], ct, -st * cosPhi[size_t(x)]);
            const auto Y = shBasis9(d);
            const dvec3 L = equirectTexel(equirect, x, y) * solidAngle;
            for (int k = 0; k < 9; ++k) sh.c[k] += L * Y[k];
        }
    }
    return sh;
}

dvec3 shIrradiance(const SH9& sh, const dvec3& N) {
    // E = sum A_l L_lm Y_lm(N) with A_l = 2 pi integral_0^1 t P_l(t) dt (Funk-Hecke for the
    // clamped cosine max(t, 0)): pi, 2 pi / 3, pi / 4. Returned divided by pi.
    constexpr double band[9] = {1.0, 2.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0, 0.25, 0.25, 0.25, 0.25, 0.25};
    const auto Y = shBasis9(N);
    dvec3 e(0.0);
    for (int k = 0; k < 9; ++k) e += sh.c[k] * (band[k] * Y[k]);
    return e;
}

// ---- 19 prefilter ---------------------------------------------------------------------------

dvec3 prefilterEnvironment(const Environment& env, const dvec3& R, double roughness,
                           std::uint32_t sampleCount) {
    const std::uint32_t n = std::max(sampleCount, 1u);  // guard: no samples, no average
    dvec3 sum(0.0);
    double weight = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const dvec3 H = importanceSampleGGX(hammersley(i, n), R, roughness);
        const dvec3 L = 2.0 * glm::dot(R, H) * H - R;  // N = V = R
        const double NdotL = glm::dot(R, L);
        if (NdotL > 0.0) {
            sum += env.radiance(L) * NdotL;
            weight += NdotL;
        }
    }
    // Guard: weight > 0 whenever sample 0 (Xi = (0, 0), H = N, N.L = 1) is used, so the
    // fallback (the unfiltered environment at R) is reached only by callers of other
    // sequences; it keeps 0/0 out.
    return weight > 0.0 ? sum / weight : env.radiance(R);
}

// ---- 20 brdf_lut ----------------------------------------------------------------------------

dvec2 integrateBRDF(double NdotV, double roughness, std::uint32_t sampleCount) {
    // Guard: N.V clamped to [1e-4, 1]: it divides the weight, and V needs sqrt(1 - N.V^2).
    NdotV = std::clamp(NdotV, kIblMinNdotV, 1.0);
    const dvec3 N(0.0, 0.0, 1.0);
    const dvec3 V(std::sqrt(1.0 - NdotV * NdotV), 0.0, NdotV);
    const std::uint32_t n = std::max(sampleCount, 1u);
    double A = 0.0, B = 0.0;
    for (std::uint32_t i = 0; i < n; ++i) {
        const dvec3 H = importanceSampleGGX(hammersley(i, n), N, roughness);
        const double VdotH = glm::dot(V, H);
        const dvec3 L = 2.0 * VdotH * H - V;
        const double NdotL = L.z;
        if (NdotL <= 0.0) continue;
        const double NdotH = std::max(H.z, kIblMinNdotH);   // as in specularIBLReference
        const double VdotHc = std::clamp(VdotH, 0.0, 1.0);  // 1 - V.H >= 0 for pow in GLSL
        const double Gvis = geometrySmithIBL(NdotV, NdotL, roughness) * VdotHc / (NdotH * NdotV);
        const double Fc = std::pow(1.0 - VdotHc, 5.0);
        A += (1.0 - Fc) * Gvis;
        B += Fc * Gvis;
    }
    return dvec2(A, B) / double(n);
}

dvec2 brdfLutExact(double NdotV, double roughness) {
    // The limit of integrateBRDF for n -> infinity, same guards:
    //   (A, B) = integral over H of ((1 - Fc), Fc) G V.H / (N.H N.V) pdf(H) dH,
    // pdf(H) = D(h) cos(theta), dH = sin(theta) dtheta dphi, restricted to N.L > 0.
    // With V = (sin tv, 0, cos tv) and H at (theta, phi), N.L = 2 (V.H) cos(theta) - cos tv > 0
    // exactly when cos(phi) > c(theta) = -cot(tv) cot(2 theta). So every phi counts for
    // theta < pi/4 - tv/2, none for theta > pi/4 + tv/2, and |phi| < acos(c) in between;
    // the integrand is even in phi. Integrating over that exact range leaves integrands without
    // a kink inside a panel, which Gauss-Legendre handles to near machine precision.
    NdotV = std::clamp(NdotV, kIblMinNdotV, 1.0);
    const double cv = NdotV, sv = std::sqrt(1.0 - cv * cv);
    const double tv = std::acos(cv);
    const double thetaA = kPi / 4.0 - tv / 2.0, thetaB = kPi / 4.0 + tv / 2.0;
    const double alpha = std::sqrt(std::sqrt(ggxAlpha2(roughness)));

    auto sample = [&](double theta, double phi, double& A, double& B, double w) {
        const double ch = std::cos(theta), sh = std::sin(theta);
        const double VdotH = sv * sh * std::cos(phi) + cv * ch;
        const double NdotL = 2.0 * VdotH * ch - cv;
        if (NdotL <= 0.0 || VdotH <= 0.0) return;  // only at the range ends, in rounding
        const double Gvis = geometrySmithIBL(cv, NdotL, roughness) * VdotH / (ch * cv);
        const double Fc = std::pow(std::max(1.0 - VdotH, 0.0), 5.0);
        A += w * (1.0 - Fc) * Gvis;
        B += w * Fc * Gvis;
    };
    // Inner integral over phi in [0, phiMax] (x2 for the mirror half), times pdf and sin.
    auto ring = [&](double theta, double phiMax, double w, double& A, double& B) {
        const double pdfSin = ggxD(std::cos(theta), roughness) * std::cos(theta) * std::sin(theta);
        forGaussNodes(gauss16(), 0.0, phiMax, [&](double phi, double wp) {
            sample(theta, phi, A, B, 2.0 * w * wp * pdfSin);
        });
    };

    // Panels in theta: they grow geometrically (x1.25) from 1e-3 alpha, which resolves the GGX
    // peak (width ~alpha) and its 1/theta^3 tail, until they are 0.02 rad wide. thetaA and
    // thetaB are panel edges; the inner integral behaves like a power 3/2 of the distance to
    // both, so the panels are also halved 30 times towards each of them.
    std::vector<double> edges = {0.0, thetaA, thetaB};
    for (double t = 1e-3 * alpha; t < thetaB;) {
        edges.push_back(t);
        t = t * 0.25 < 0.02 ? t * 1.25 : t + 0.02;
    }
    for (int k = 1; k <= 30; ++k) {
        const double d = (thetaB - thetaA) * std::ldexp(1.0, -k);
        edges.push_back(thetaA + d);
        edges.push_back(thetaB - d);
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

    double A = 0.0, B = 0.0;
    for (size_t k = 0; k + 1 < edges.size() && edges[k] < thetaB; ++k) {
        forGaussNodes(
            gauss8(), edges[k], std::min(edges[k + 1], thetaB), [&](double theta, double w) {
                double phiMax = kPi;  // theta < thetaA: every phi counts
                if (theta > thetaA && sv > 0.0) {
                    const double c = -(cv / sv) * std::cos(2.0 * theta) / std::sin(2.0 * theta);
                    phiMax = std::acos(std::clamp(c, -1.0, 1.0));
                }
                ring(theta, phiMax, w, A, B);
            });
    }
    return {A, B};
}

// ---- 21 split_sum ---------------------------------------------------------------------------

dvec3 ambientIBL(const dvec3& N, const dvec3& V, const dvec3& albedo, double metallic,
                 double roughness, double ao, const dvec3& irradiance, const dvec3& prefiltered,
                 const dvec2& lut, double minNdotV) {
    // max(N.V, 0): V below the horizon (silhouettes of interpolated normals) reads the LUT
    // and Fresnel at grazing incidence instead of outside their domain.
    const double NdotV = std::max(glm::dot(N, V), minNdotV);
    const dvec3 F0 = baseReflectivity(albedo, metallic);
    const dvec3 F = fresnelSchlickRoughness(NdotV, F0, roughness);
    const dvec3 kD = (1.0 - F) * (1.0 - metallic);
    const dvec3 diffuse = albedo * irradiance;
    const dvec3 specular = prefiltered * (F0 * lut.x + lut.y);  // Karis: F0, not F
    return (kD * diffuse + specular) * ao;
}

// Nodes by Newton's method on the Legendre recurrence, from Tricomi's initial guesses.
GaussRule gaussLegendre(int n) {
    GaussRule g;
    for (int i = 0; i < n; ++i) {
        double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
        double dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = x;
            for (int k = 2; k <= n; ++k) {
                const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1.0);
            const double dx = p1 / dp;
            x -= dx;
            if (std::abs(dx) < 1e-16) break;
        }
        g.x.push_back(x);
        g.w.push_back(2.0 / ((1.0 - x * x) * dp * dp));
    }
    return g;
}

}  // namespace pbrlab::ref
