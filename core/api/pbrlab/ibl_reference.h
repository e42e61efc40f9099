// The CPU truth of the lab "ibl" (contract steps 15-21) in double precision. The sampling
// functions mirror the GLSL reference solutions (labs/hammersley ... labs/split_sum)
// formula for formula and guard for guard, so GPU and CPU differ only by float rounding and by
// how the environment is stored (cube map on the GPU, equirectangular image here). Next to
// the Monte Carlo estimators are high-accuracy quadratures (brdfLutExact, irradianceAt,
// projectSH9) that serve as ground truth in the error-against-run-time plots.
//
// Conventions: y is up; directions are unit vectors; `roughness` is perceptual and
// alpha = roughness^2 (docs/design.md). The equirectangular mapping is the one of
// shaders/ibl/cube_face.glsl: u = atan2(d.x, -d.z) / 2pi + 0.5 (u = 0.5 looks down -z),
// v = acos(d.y) / pi (v = 0 at the zenith, image row 0).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <vector>

#include "pbrlab/cube_sampler.h"
#include "pbrlab/image.h"
#include "pbrlab/reference.h"

namespace pbrlab::ref {

// GGX alpha^2 = roughness^4 with the floor of distributionGGX (reference.h): roughness 0 keeps a
// finite lobe.
double ggxAlpha2(double roughness);

// Guards shared with the GLSL solutions (each is explained where it is used, in
// ibl_reference.cpp and the solution files).
constexpr double kIblMinNdotV = 1e-4;  // N.V floor in the IBL weights and the LUT (N.V = 0)
constexpr double kIblMinNdotH = 1e-4;  // N.H floor in the weight G V.H / (N.H N.V)
constexpr double kIblMinAlpha = 3.1622776601683794e-4;  // sqrt(kMinAlpha2): alpha floor in k

// Gauss-Legendre nodes x and weights w on [-1, 1] (n points: exact for polynomials of degree
// 2n - 1); the quadrature behind the ground truths here and in the tests.
struct GaussRule {
    std::vector<double> x, w;
};
GaussRule gaussLegendre(int n);

// ---- 15 hammersley --------------------------------------------------------------------------

// Van der Corput radical inverse in base 2: the bits of i mirrored around the binary point
// (bit reversal of the 32-bit word, divided by 2^32). In [0, 1).
double radicalInverse2(std::uint32_t i);
// Point i of the n-point Hammersley set: (i / n, radicalInverse2(i)). n = 0 is treated as 1.
dvec2 hammersley(std::uint32_t i, std::uint32_t n);

// ---- 16 importance --------------------------------------------------------------------------

// Maps a uniform Xi in [0,1)^2 to a GGX-distributed half vector around N: phi = 2 pi Xi.x and
// cos^2(theta) = (1 - Xi.y) / (1 + (alpha^2 - 1) Xi.y), so that H has the density
// pdfGGXHalfVector (D(h) (N.H) per steradian). The tangent frame is the one of the seed: the
// up vector z (x when N is within ~2.6 degrees of +-z), T = normalize(up x N), B = N x T.
dvec3 importanceSampleGGX(const dvec2& Xi, const dvec3& N, double roughness);
// The density of importanceSampleGGX's H per steradian of half-vector directions: D (N.H).
double pdfGGXHalfVector(double NdotH, double roughness);
// The density of L = reflect(-V, H) per steradian of light directions: D (N.H) / (4 V.H), the
// Jacobian dH/dL = 1 / (4 V.H) of the reflection. 0 when V.H <= 0.
double pdfGGXReflected(double NdotH, double VdotH, double roughness);

// P(X >= chi2) for a chi-square distribution with `dof` degrees of freedom (the regularised
// upper incomplete gamma Q(dof / 2, chi2 / 2)): the p-value of a chi-square test.
double chiSquareTail(double chi2, int dof);

// A chi-square test of half vectors against the GGX density D(h) (N.h) per steradian, in a
// frame of the test's own around N (a correct sampler in any orthonormal frame is a rotation
// or reflection of it, which leaves a uniform phi uniform). 16 theta bins by s = ln tan(theta),
// edges at the closed-form quantiles, probabilities integrated numerically from the density
// (so a wrong quantile formula cannot hide); 8 phi bins. Samples that are not finite unit
// vectors above the surface (|1 - |H|| > 1e-3, N.H <= 0) are invalid and left out of the bins.
struct ChiSquareTest {
    double pValue = 0, chi2 = 0;
    int dof = 0, valid = 0, invalid = 0;
};
ChiSquareTest ggxHalfVectorChiSquare(const std::vector<dvec3>& H, const dvec3& N, double roughness);

// The same test against any density p(H) per steradian of directions around N, for samplers
// whose distribution also depends on the azimuth (the visible normals seen from V): theta binned
// as above by the GGX quantiles of `roughness`, phi measured from T (a unit vector
// perpendicular to N, e.g. V's tangential direction) in 16 bins. Each bin's probability is
// integrated from p on a 24 x 24 grid of midpoints (p may have a kink inside a bin), bins
// expecting fewer than 5 samples are pooled, and samples where p is 0 (outside its support)
// are invalid like the others.
ChiSquareTest directionChiSquare(const std::vector<dvec3>& H, const dvec3& N, const dvec3& T,
                                 double roughness, const std::function<double(const dvec3&)>& p);

// Smith-Schlick-GGX for image-based lighting: k = alpha / 2 = roughness^2 / 2 (not the
// direct-light (roughness + 1)^2 / 8 of step 6), alpha floored at kIblMinAlpha like D.
double geometrySchlickGGXIBL(double NdotX, double roughness);
double geometrySmithIBL(double NdotV, double NdotL, double roughness);

// The contract's helper for step 21: F0 + (max(1 - roughness, F0) - F0) (1 - cosTheta)^5.
dvec3 fresnelSchlickRoughness(double cosTheta, const dvec3& F0, double roughness);

// ---- environments ---------------------------------------------------------------------------

// Incoming radiance from every direction, at infinite distance.
struct Environment {
    virtual ~Environment() = default;
    virtual dvec3 radiance(const dvec3& dir) const = 0;
};

// The same radiance everywhere (the white furnace when colour = 1).
struct ConstantEnvironment final : Environment {
    explicit ConstantEnvironment(const dvec3& c) : colour(c) {}
    dvec3 radiance(const dvec3&) const override { return colour; }
    dvec3 colour;
};

// A cube map as the shaders read the environment (textureLod(uEnvironment, L, 0)): the CPU
// copy of the same cube, mip 0, filtered as GL filters it. Refers to `cube`, not a copy.
struct CubeEnvironment final : Environment {
    explicit CubeEnvironment(const CubeSampler& c) : cube(c) {}
    dvec3 radiance(const dvec3& dir) const override { return cube.sample(dir, 0); }
    const CubeSampler& cube;
};

// An equirectangular image (RGB from the first three channels; one channel is grey), looked
// up bilinearly between texel centres, wrapping around in u and clamped in v, as a GL sampler
// with GL_REPEAT on s and GL_CLAMP_TO_EDGE on t would. Throws pbrlab::Error on an empty image.
class EquirectEnvironment final : public Environment {
public:
    explicit EquirectEnvironment(Image image);
    dvec3 radiance(const dvec3& dir) const override;
    const Image& image() const { return image_; }
    dvec3 texel(int x, int y) const;  // x wraps, y clamps

private:
    Image image_;
};

dvec2 equirectUv(const dvec3& dir);        // the mapping above, u in [0, 1], v in [0, 1]
dvec3 equirectDirection(const dvec2& uv);  // its inverse
// EquirectEnvironment's lookups on an image it does not own (no copy; not validated).
dvec3 equirectTexel(const Image& image, int x, int y);         // x wraps, y clamps
dvec3 equirectRadiance(const Image& image, const dvec3& dir);  // bilinear

// ---- 17 mc_specular -------------------------------------------------------------------------

// Brute-force split-free specular IBL: (1/n) sum over Hammersley-driven GGX half vectors H of
// L(l) F(V.H) G(N.V, N.L) (V.H) / ((N.H)(N.V)), l = reflect(-V, H), samples with N.L <= 0
// contributing 0. This is f_spec(l) (N.L) / pdf(l) with D cancelled (pdf = D (N.H) / 4 (V.H)).
dvec3 specularIBLReference(const Environment& env, const dvec3& N, const dvec3& V, const dvec3& F0,
                           double roughness, std::uint32_t sampleCount);

// What grading an estimator needs at one point (steps 17, 19, 20): its converged value, the
// standard deviation of a one-sample estimate, and the converged value's own standard error,
// measured with `m` samples of the reference's own estimator in double. The samples are 16
// Hammersley sets of m / 16 points, each shifted modulo 1 by an offset of its own (randomised
// quasi-Monte Carlo: a Cranley-Patterson rotation), the offsets drawn from a hash of the
// point's inputs: each set is an unbiased estimate, independent of the other sets and of other
// points', so the spread of the 16 measures the mean's error. An estimator of n samples is then
// within a few sqrt(sigma^2 / n + error^2) of the mean (docs/grading.md, "Estimators").
struct Moments {
    dvec3 mean{0}, sigma{0}, error{0};
};
// The same measure for a one-sample estimator of a step's own, `sample(Xi)` with Xi in
// [0, 1)^2, seeded by the point's `inputs` (a step's estimator of another integral, or of the
// same one with another sampler).
Moments estimatorMoments(std::initializer_list<double> inputs, std::uint32_t m,
                         const std::function<dvec3(const dvec2& xi)>& sample);
Moments specularIBLMoments(const Environment& env, const dvec3& N, const dvec3& V, const dvec3& F0,
                           double roughness, std::uint32_t m);
// The ratio estimator sum L (N.l) / sum (N.l): sigma from the delta method,
// Var = E[w^2 (L - mean)^2] / E[w]^2 for one sample of weight w = (N.l)+.
Moments prefilterMoments(const Environment& env, const dvec3& R, double roughness, std::uint32_t m);
// (A, B) in x and y; the mean from brdfLutExact (error 0).
Moments brdfLutMoments(double NdotV, double roughness, std::uint32_t m);

// ---- 18 irradiance --------------------------------------------------------------------------

// E(N) / pi with E(N) = integral over the hemisphere around N of L(l) (N.l) dl, so that
// diffuse = albedo * irradianceAt(N). High-accuracy quadrature: Gauss-Legendre in theta
// (thetaSteps nodes) times the periodic midpoint rule in phi (4 * thetaSteps nodes) around N.
// 256 resolves features of about 0.2 degrees; see tests/test_ibl_reference.cpp for measured
// convergence.
dvec3 irradianceAt(const Environment& env, const dvec3& N, int thetaSteps = 256);
// The same for an equirectangular image taken as piecewise constant per texel: the sum over
// texels of L (N.l)+ times the texel's exact solid angle (2 pi / W)(cos theta_top -
// cos theta_bottom), with l at the texel centre. The ground truth for small bright sources
// (a sun a few texels wide), which point quadratures resolve only slowly: on the shipped sky,
// irradianceAt(EquirectEnvironment) is off by 2.4% at 128 theta nodes, 2.4e-4 at 512.
dvec3 irradianceAt(const Image& equirect, const dvec3& N);

// Real spherical harmonics up to band 2 (9 coefficients, RGB each): index l (l + 1) + m.
struct SH9 {
    std::array<dvec3, 9> c{};
};
// The 9 real SH basis functions at a unit direction (orthonormal over the sphere).
std::array<double, 9> shBasis9(const dvec3& dir);
// Projection by quadrature over the whole sphere: Gauss-Legendre in cos(theta) (thetaSteps
// nodes) times the midpoint rule in phi (2 * thetaSteps nodes).
SH9 projectSH9(const Environment& env, int thetaSteps = 512);
// Projection of an equirectangular image taken as piecewise constant per texel, each texel
// weighted by its exact solid angle (2 pi / W) (cos(theta_top) - cos(theta_bottom)).
SH9 projectSH9(const Image& equirect);
// E(N) / pi from the 9 coefficients: the clamped-cosine kernel acts on band l by
// A_l = 2 pi integral_0^1 t P_l(t) dt, i.e. A_0 = pi, A_1 = 2 pi / 3, A_2 = pi / 4 (Funk-Hecke).
dvec3 shIrradiance(const SH9& sh, const dvec3& N);

// ---- 19 prefilter ---------------------------------------------------------------------------

// The first sum of the split sum: the environment averaged over the GGX lobe of L around R,
// assuming N = V = R, weighted by N.L (Karis 2013): sum L(l) (N.l) / sum (N.l) over samples
// with N.l > 0.
dvec3 prefilterEnvironment(const Environment& env, const dvec3& R, double roughness,
                           std::uint32_t sampleCount);

// The converged value of prefilterEnvironment for an equirectangular image taken as piecewise
// constant per texel (like irradianceAt(Image, N)): the sum over texels of L (N.l)+ D(h) times
// the texel's exact solid angle, divided by the same sum without L (N = V = R, h halfway
// between R and l, so (N.h)^2 = (1 + N.l) / 2). Evaluated by TexelSums below.
//
// TexelSums: the texel sums of irradianceAt(Image, N) and of the prefilter above, evaluated
// hierarchically so that a whole map's sample costs milliseconds, not seconds. The image's
// texels are grouped into blocks of 4x4, 8x8 ... texels (a quadtree). A block whose
// directions all lie on one side of the horizon and whose angular radius s is small next to
// its distance from the lobe's peak (s <= opening * max(distance, lobe width)) contributes
// through the moments of its directions, per colour channel weighted by power: the kernel at
// the mean direction plus half its second derivative times the variance of N.l (exact for a
// kernel linear or quadratic in N.l, such as the cosine of irradiance; the error falls as the
// fourth power of s otherwise). Every other block is opened, down to single texels, which are
// the sum's definition (the horizon is resolved texel by texel, as in irradianceAt). With
// opening = 0 every block is opened: the plain texel sum. Accuracy against it is measured in
// tests/test_ibl_reference.cpp (TexelSums*).
class TexelSums {
public:
    // Keeps a reference to the image: it must outlive this object.
    explicit TexelSums(const Image& equirect, double opening = 0.1);
    // E(N) / pi: irradianceAt(equirect, N), hierarchically.
    dvec3 irradiance(const dvec3& N) const;
    // sum L (N.l)+ D(h) dl / sum (N.l)+ D(h) dl with N = V = R. Lobes narrower than a texel
    // (roughness 0) see the piecewise-constant image: use EquirectEnvironment::radiance there.
    dvec3 prefilter(const dvec3& R, double roughness) const;
    // The mean radiance over the sphere (solid-angle weighted).
    dvec3 meanRadiance() const;

private:
    // Directions weighted by w: the sum of w, the mean direction (not unit) and the mean of
    // d d^T (xx, yy, zz, xy, yz, xz).
    struct Moments {
        double weight = 0;
        dvec3 mean{0.0};
        double second[6] = {};
        void add(const dvec3& d, double w);
        void add(const Moments& m);
        void normalise();
    };
    struct Block {
        Moments power[3];  // weighted by L times solid angle, per colour channel
        Moments solidAngle;
    };
    // Where a block is, apart from its moments: what the traversal reads for every block.
    struct Bound {
        dvec3 axis{0.0};      // unit: the solid angle's mean direction
        double radius = 0.0;  // every direction of the block is within this angle of axis
        double sinRadius = 0.0, cosFar = 1.0;  // sin(radius), cos(radius / opening)
    };
    template <class Kernel>
    void accumulate(const dvec3& N, double lobeWidth, const Kernel& kernel, dvec3& weighted,
                    double& weight) const;
    // The constructor's pieces: the finest level from the texels, each coarser level from the
    // one below, and a block's bound once its sums are complete.
    std::vector<Block> finestLevel(int bw, int bh);
    std::vector<Block> coarserLevel(const std::vector<Block>& fine, int fw, int fh, int bw, int bh,
                                    int size);
    Bound finish(Block& b, int x0, int y0, int x1, int y1) const;
    dvec3 texel(int x, int y) const {
        const float* p =
            &image_
                 .pixels[(size_t(y) * size_t(image_.width) + size_t(x)) * size_t(image_.channels)];
        return image_.channels < 3 ? dvec3(p[0]) : dvec3(p[0], p[1], p[2]);
    }
    const Image& image_;
    int blockSize_;  // texels a side of the finest blocks
    double opening_;
    std::vector<double> rowSolidAngle_, rowSin_, rowCos_, colSin_, colCos_;
    // levels_[k]: blocks of blockSize_ * 2^k texels a side, row-major, widths_[k] x heights_[k].
    std::vector<std::vector<Block>> levels_;
    std::vector<std::vector<Bound>> bounds_;  // per level, as levels_
    std::vector<int> widths_, heights_;
};

// ---- 20 brdf_lut ----------------------------------------------------------------------------

// The second sum: scale A and bias B with integral of f_spec (N.L) = F0 A + B for Schlick's
// Fresnel, by Monte Carlo with Hammersley points; N = +z, V = (sqrt(1 - NdotV^2), 0, NdotV).
dvec2 integrateBRDF(double NdotV, double roughness, std::uint32_t sampleCount);
// The same two integrals by deterministic quadrature (graded Gauss-Legendre panels in the
// half-vector angle, the exact azimuth range where N.L > 0): within 4e-7 of a rule with 4x
// the nodes (measured over roughness and N.V in [0, 1]), about 0.6 ms per value.
dvec2 brdfLutExact(double NdotV, double roughness);

// ---- 21 split_sum ---------------------------------------------------------------------------

// The ambient term from the three precomputed values at this point: irradiance (E/pi at N),
// prefiltered (the prefiltered environment at R = reflect(-V, N), roughness) and lut (A, B at
// N.V, roughness). kD = (1 - F)(1 - metallic), F = fresnelSchlickRoughness(N.V, F0, roughness);
// result = (kD albedo irradiance + prefiltered (F0 A + B)) ao.
dvec3 ambientIBL(const dvec3& N, const dvec3& V, const dvec3& albedo, double metallic,
                 double roughness, double ao, const dvec3& irradiance, const dvec3& prefiltered,
                 const dvec2& lut, double minNdotV = 0);

}  // namespace pbrlab::ref
