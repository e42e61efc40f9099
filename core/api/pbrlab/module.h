// What a lab module is: a descriptor the host reads (id, step, contract function, parameters,
// how its value is displayed and compared) plus a CPU reference in double precision. The
// module's GLSL lives beside it: solution.glsl (the student function) and view.glsl
// (`vec3 view(Surface s)`: what the step shows, evaluated per pixel).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "pbrlab/cube_sampler.h"
#include "pbrlab/params.h"
#include "pbrlab/reference.h"

namespace pbrlab {

// Bump when ModuleDesc or anything it contains changes layout.
constexpr int kModuleAbiVersion = 10;

// Everything a contract function may take, per pixel. The GPU fills the same fields in
// GLSL (shaders/surface.glsl) from the G-buffer (scene) or from uploaded textures (probe), so
// the CPU reference sees exactly the float inputs the shader saw.
struct Surface {
    bool covered = false;  // false: background, nothing to evaluate
    glm::dvec3 position{0}, normal{0, 0, 1};
    glm::dvec4 tangent{1, 0, 0, 1};
    glm::dvec2 uv{0};
    glm::dvec3 view{0, 0, 1};   // V: towards the camera
    glm::dvec3 light{0, 0, 1};  // L: towards the first light (zero when on it)
    glm::dvec3 lightPosition{0}, lightColor{0};
    glm::dvec3 albedoTexel{0};  // the base colour as stored (sRGB-encoded)
    glm::dvec3 albedo{0};       // linear
    double metallic = 0, roughness = 0.5, ao = 1;
    glm::dvec3 normalTexel{0.5, 0.5, 1};  // tangent-space normal map texel in [0, 1]
    glm::dvec3 emissive{0};               // emitted radiance, linear
    glm::dvec4 extra{0};                  // probe-only inputs; meaning given by the module
};

// shaders/common.glsl's pbrlab_grazingBand: smoothstep(0.05, 0.1, 4 N.V N.L).
inline double grazingBand(const Surface& s) {
    double d =
        4 * std::max(glm::dot(s.normal, s.view), 0.0) * std::max(glm::dot(s.normal, s.light), 0.0);
    double t = std::clamp((d - 0.05) / 0.05, 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// The light arriving at the point from the first light, times N.L: what a BRDF term is
// multiplied by to show its share of the picture (the term views of the BRDF's steps).
inline glm::dvec3 incidentIrradiance(const Surface& s) {
    return ref::pointLightRadiance(s.lightColor, s.lightPosition, s.position) *
           ref::lambertCosine(s.normal, s.light);
}

// One quantity of a step's lesson shown over the picture (the GUI's term views): computed per
// pixel with the CPU references from the surfaces the G-buffer held, so a student sees where a
// term is large or small on the object itself.
struct TermView {
    std::string name;  // as the view chooser and --view name it ("D", "kD")
    // How the value is shown: linear colours and radiance are display-encoded; the rest
    // (factors in [0, 1], directions mapped to [0, 1]) are shown as they are.
    enum class Encode { None, LinearColor, Radiance } encode = Encode::None;
    std::function<glm::dvec3(const Surface&)> value;
};

// What a CPU reference may read besides the surface.
struct ReferenceContext {
    const ParamValues& params;
    std::vector<ref::PointLight> lights;  // the scene's point lights
    glm::dvec3 cameraPosition{0};
    const IblInputs* ibl = nullptr;  // the precomputed maps, for modules with NeedsEnvironment
};

using ReferenceFn = std::function<glm::dvec3(const Surface&, const ReferenceContext&)>;

enum class DisplayMode {
    Grey,          // (v - lo) / (hi - lo), shown as it is (as the assignment's images are)
    LinearColor,   // a linear colour, sRGB-encoded for the screen
    HdrColor,      // linear radiance: Reinhard, then gamma 1/2.2
    SignedVector,  // a direction: 0.5 + 0.5 v
    FalseColor,    // (v.x - lo) / (hi - lo) through a colour map with a legend
    Encoded,       // already display-encoded (the tonemap step): shown as it is
};

struct Display {
    DisplayMode mode = DisplayMode::Grey;
    double lo = 0, hi = 1;
    bool logScale = false;  // FalseColor: map log10(v) between log10(lo) and log10(hi)
};

// The pass band around the CPU reference, per value component (docs/grading.md). At a point
// with reference r, accepted range alternatives a_k and float inputs x, a value v passes when
//     min(r, a_k) - t <= v <= max(r, a_k) + t,   t = max(absolute, relative |r|, spread),
// or when it is within t of one separate alternative (AcceptedAlternative),
// where spread is the largest change of the reference when every float input moves by up to
// `ulps` units in the last place: the measured conditioning of the function at that point,
// so the band is tight where the function is well conditioned and loose only where the
// rounding of its float inputs says so. The numbers and their measured reasons are written in
// the module's handout.
struct Tolerance {
    double absolute = 1e-6;  // in the value's own units: the band's width near zero
    double relative = 1e-3;  // of |r|: 50x under a 5% constant-factor mistake
    double ulps = 8;         // conditioning: input rounding budget (0: no spread term)
    // Share of compared points allowed outside the band (0: none). For views that filter HDR
    // textures: GL leaves the precision of bilinear weights to the implementation (llvmpipe
    // uses 8 bits), so next to a 20000-bright sun a handful of pixels differ by whole percents
    // while the function is right. NaN, Inf and negatives are never excused.
    double outlierFraction = 0;
};

// Deterministic random numbers for sampling a module's teaching domain (seeded by the grader,
// so instructors can choose other points than the ones students see).
class DomainRandom {
public:
    explicit DomainRandom(std::uint64_t seed) : state_(seed * 0x9E3779B97F4A7C15ull + 1) {}
    // Uniform in [0, 1) with 24 bits, so every value is exact in a float.
    double uniform() {
        state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
        std::uint64_t z = state_;
        z = (z ^ (z >> 33)) * 0xff51afd7ed558ccdull;
        z = (z ^ (z >> 33)) * 0xc4ceb9fe1a85ec53ull;
        return double((z ^ (z >> 33)) >> 40) * (1.0 / 16777216.0);
    }
    double range(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    // Log-uniform in [lo, hi] (lo > 0): every decade as likely.
    double logRange(double lo, double hi) { return lo * std::pow(hi / lo, uniform()); }
    glm::dvec3 color(double hi = 1) { return {range(0, hi), range(0, hi), range(0, hi)}; }
    // A uniformly distributed unit vector.
    glm::dvec3 direction() {
        const double z = range(-1, 1), phi = range(0, 2 * std::numbers::pi);
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
    // A unit vector at cosine c from n, c uniform in [minCos, maxCos], azimuth uniform.
    glm::dvec3 around(const glm::dvec3& n, double minCos, double maxCos) {
        const double c = range(minCos, maxCos), phi = range(0, 2 * std::numbers::pi);
        const glm::dvec3 a = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
        const glm::dvec3 t = glm::normalize(a - n * glm::dot(n, a)), b = glm::cross(n, t);
        const double s = std::sqrt(std::max(0.0, 1 - c * c));
        return glm::normalize(n * c + t * (s * std::cos(phi)) + b * (s * std::sin(phi)));
    }

private:
    std::uint64_t state_;
};

// A full-screen grid whose pixels map to the function's inputs, domain ends included:
// x and y run over [0, 1] with both ends hit exactly (pixel i -> i / (size - 1)).
struct Probe {
    std::string xAxis, yAxis;  // what x and y mean, for plots and reports
    int width = 65, height = 65;
    std::function<Surface(double x, double y)> at;
    // When x sweeps the light's angle from N in the plane of incidence (x = 0: -90 degrees,
    // x = 1: +90), plots may draw a row as a polar lobe. viewAngle: where V is, in degrees.
    bool xIsLightAngle = false;
    double viewAngle = 0;
};

// N·V along x, from 0 (grazing) to 1 (along the normal); roughness 0.05..1 along y. N = +z,
// V in the xz-plane. Shared by the steps that are functions of the view angle and roughness
// only (g1, brdf_lut).
inline Probe viewCosineRoughnessProbe() {
    Probe p;
    p.xAxis = "N·V 0..1";
    p.yAxis = "roughness 0.05..1";
    p.width = 65;
    p.height = 65;
    p.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {std::sqrt(1 - x * x), 0, x};
        s.roughness = 0.05 + 0.95 * y;
        return s;
    };
    return p;
}

// The chart of the ambient-light steps (split_sum, multiscatter_ibl): N·V along x from 0
// (grazing) to 1, roughness 0 to 1 along y, on an orange half-metal, so that both the diffuse
// and the specular term show. N = +z; V turns in the xz-plane.
inline Probe ambientLightProbe() {
    Probe p;
    p.xAxis = "N·V 0..1";
    p.yAxis = "roughness 0..1";
    p.width = 65;
    p.height = 33;
    p.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {std::sqrt(1 - x * x), 0, x};
        s.albedo = s.albedoTexel = {0.9, 0.55, 0.25};
        s.metallic = 0.5;
        s.roughness = y;
        s.ao = 1;
        return s;
    };
    return p;
}

// The domain of the ambient-light steps: N anywhere, V in its hemisphere, any material,
// roughness 0 to 1, any ao.
inline Surface ambientLightDomain(DomainRandom& r) {
    Surface s;
    s.normal = r.direction();
    s.view = r.around(s.normal, 0, 1);
    s.albedo = s.albedoTexel = r.color();
    s.metallic = r.uniform();
    s.roughness = r.uniform();
    s.ao = r.uniform();
    return s;
}

// The chart of the specular estimators (mc_specular, vndf_specular): N·V from 0.05 to 1 along
// x, roughness 0.05 to 1 along y (0 is an extreme input: there the floors on alpha and k
// legitimately differ between solutions), on an orange half-metal (F0 = 0.47, 0.30, 0.15:
// Fresnel and tint both show). N points straight down, so every sample reflects the ground (no
// sun, no sky): the plot shows the estimator, not the environment's detail. V turns in the
// yz-plane; at grazing V the mirror direction reaches the hazy horizon.
inline Probe groundReflectionProbe() {
    Probe p;
    p.xAxis = "N·V 0.05..1 (N down: the ground)";
    p.yAxis = "roughness 0.05..1";
    p.width = 65;
    p.height = 33;
    p.at = [](double x, double y) {
        const double NdotV = 0.05 + 0.95 * x;
        Surface s;
        s.covered = true;
        s.normal = {0, -1, 0};
        s.view = {0, -NdotV, std::sqrt(1 - NdotV * NdotV)};
        s.albedo = s.albedoTexel = {0.9, 0.55, 0.25};
        s.metallic = 0.5;
        s.roughness = 0.05 + 0.95 * y;
        s.ao = 1;
        return s;
    };
    return p;
}

// The domain of the specular estimators: N anywhere, V in its hemisphere (N·V 0.05 to 1), any
// material, roughness 0.05 to 1.
inline Surface specularEstimatorDomain(DomainRandom& r) {
    Surface s;
    s.normal = r.direction();
    s.view = r.around(s.normal, 0.05, 1);
    s.albedo = s.albedoTexel = r.color();
    s.metallic = r.uniform();
    s.roughness = r.range(0.05, 1);
    s.ao = 1;
    return s;
}

// The domain of the steps that are functions of the whole lobe (specular, brdf): N anywhere;
// V and L in its hemisphere, half the time L near V's mirror direction (the highlight); any
// albedo and metallic; roughness 0.05 to 1.
inline Surface highlightDomain(DomainRandom& r) {
    Surface s;
    s.normal = r.direction();
    s.view = r.around(s.normal, 0, 1);
    const glm::dvec3 mirror = glm::reflect(-s.view, s.normal);
    do s.light = r.uniform() < 0.5 ? r.around(mirror, 0.9, 1) : r.around(s.normal, 0, 1);
    while (glm::dot(s.light, s.normal) < 0);
    s.albedo = s.albedoTexel = r.color();
    s.metallic = r.uniform();
    s.roughness = r.range(0.05, 1);
    return s;
}

// L over a cap of the sphere around N = +z (V = N): x = the angle from N, 0..capOverPi * pi
// (1: the whole sphere, 0.5: the hemisphere; a multiple of pi keeps the column at 90 degrees
// exact), both ends hit; y = the azimuth, 0..360 degrees. Shared by the steps that are functions of
// L and N (ndotl, over the whole sphere) or of L and V = N (halfway, over the hemisphere).
inline Probe lightAroundNormalProbe(double capOverPi, int height, std::string xAxis) {
    Probe p;
    p.xAxis = std::move(xAxis);
    p.yAxis = "azimuth of L 0..360 deg";
    p.width = 65;
    p.height = height;
    p.at = [capOverPi](double x, double y) {
        const double theta = x * (capOverPi * std::numbers::pi), phi = y * 2 * std::numbers::pi;
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {0, 0, 1};
        s.light = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta)};
        return s;
    };
    return p;
}

// The plane-of-incidence probe the specular steps share: N = +z, V 60 degrees from N, L swept
// in the same plane from -90 degrees (x = 0, grazing on the mirror side) through the mirror
// direction (x = 1/6), N (x = 1/2) and V itself (x = 5/6) to +90 degrees; y = roughness
// 0.05..1. `material` sets albedo and metallic.
inline Probe planeOfIncidenceProbe(void (*material)(Surface&)) {
    Probe p;
    p.xAxis = "angle(N, L) -90..90 deg (V at +60, mirror at -60)";
    p.yAxis = "roughness 0.05..1";
    p.width = 61;
    p.height = 39;
    p.xIsLightAngle = true;
    p.viewAngle = 60;
    p.at = [material](double x, double y) {
        const double theta = (x - 0.5) * std::numbers::pi, v = std::numbers::pi / 3;
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {std::sin(v), 0, std::cos(v)};
        s.light = {std::sin(theta), 0, std::cos(theta)};
        s.roughness = 0.05 + 0.95 * y;
        material(s);
        return s;
    };
    return p;
}

// Which surface inputs the module's view reads, so that nothing else is loaded or compiled.
enum SurfaceNeeds : unsigned {
    NeedsGeometry = 0,  // position, normal, tangent, uv, V, L: always available
    NeedsAlbedo = 1u << 0,
    NeedsMetallic = 1u << 1,
    NeedsRoughness = 1u << 2,
    NeedsAo = 1u << 3,
    NeedsNormalMap = 1u << 4,
    NeedsEnvironment = 1u << 5,  // IBL: the environment cube uEnvironment (with mips)
    NeedsEmissive = 1u << 6,     // emitted radiance (modules whose view is the final picture)
    // The maps derived from the environment (irradiance, prefiltered, BRDF LUT), computed by
    // earlier steps' reference solutions: what the split sum reads. Without it a step sees
    // the environment cube only, and no precompute runs for it.
    NeedsPrecomputedMaps = 1u << 7,
    NeedsMaterial = NeedsAlbedo | NeedsMetallic | NeedsRoughness | NeedsAo,
};

// Runs the code being graded: the module's view (or one of its extra views, by name) on the
// given surfaces, one value each; parameters at their defaults unless `set` assigns them
// ("samples=16"). What invariants and distribution tests are measured with.
struct Evaluator {
    std::function<std::vector<glm::dvec3>(const std::vector<Surface>&, const std::string& view,
                                          const std::vector<std::string>& set)>
        run;
    std::vector<glm::dvec3> operator()(const std::vector<Surface>& surfaces) const {
        return run(surfaces, "", {});
    }
};
using EvaluateFn = Evaluator;

// A property every correct answer has (normalisation, bounds, reciprocity, end values, a
// distribution), measured on the student's function. It is part of the contract: a property
// that does not hold fails the step, and its name and value are the feedback.
struct InvariantResult {
    std::string name;      // "integral of D(h) (n.h) dw at roughness 0.5"
    double measured = 0;   // the quantity that should meet `expected`
    std::string expected;  // "1 +- 0.01"
    bool holds = false;
    std::string hint;  // when it fails: what that usually means ("is PI missing?"), optional
};
using InvariantsFn = std::function<std::vector<InvariantResult>(const Evaluator&)>;

// A legitimately different definition that the contract accepts. Two kinds:
//   range: one end of a continuous family of correct definitions, the reference the other
//          (an epsilon anywhere between the reference's floor and the lesson's + 0.001): a
//          value anywhere between the two passes;
//   separate: a definition on its own (pow(c, 2.2) for the sRGB curve): a value near it
//          passes, a blend of it and the reference does not.
struct AcceptedAlternative {
    std::string name;  // why it is correct too
    ReferenceFn value;
    bool range = false;
};

// d turned in the plane of n and d to the cosine c with n (unit n and d; when d is along n,
// towards any direction perpendicular to n): what an InputAxis sets a cosine such as N.H with.
inline glm::dvec3 atCosine(const glm::dvec3& n, const glm::dvec3& d, double c) {
    glm::dvec3 t = d - n * glm::dot(n, d);
    if (glm::dot(t, t) < 1e-24) t = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    t = glm::normalize(t - n * glm::dot(n, t));
    c = std::clamp(c, -1.0, 1.0);
    return n * c + t * std::sqrt(std::max(0.0, 1 - c * c));
}

// A part of the step's formula, named, for feedback (docs/grading.md, "Feedback: the missing or
// extra term"): the step's value recomputed in double with that part raised to an exponent of
// its own. The grader tries each term missing, applied twice, at a fitted power, or switched to
// a common wrong form, on the points of a failed check, and names the one that explains the
// student's values when no other does as well. pbrlab/named_terms.h builds them from a model
// written once with all its exponents in a struct (the built-in steps and `pbrlab new-step`'s
// template do so).
// Every member has a default, so that a step may write a term with designated initializers
// naming only what it sets ({.kind = ..., .symbol = ..., .value = ...}).
struct NamedTerm {
    // Factor: a quantity the value is multiplied by, tried missing, twice, or extra.
    // Exponent: the power of an input, fitted over [lo, hi] (or tried at `tries`).
    // Switch: another way of writing the step, tried as a whole (`name` says what it is).
    enum class Kind { Factor, Exponent, Switch };
    Kind kind = Kind::Factor;
    std::string symbol{};  // as the formula writes it: "N.L"
    std::string name{};    // what it is: "the N.L weight of each sample"
    // The step's value with this term at exponent e, every other part as the reference has it.
    std::function<glm::dvec3(const Surface&, const ReferenceContext&, double e)> value{};
    // The exponent the reference has: 0 where it has no such factor; a Switch's reference is 0
    // (off) for a form tried on, 1 for a part tried removed.
    double reference = 1;
    // The exponents tried. Empty: a Factor tries 0 and twice its reference (1 and -1 when the
    // reference has none); an Exponent with lo < hi is fitted instead.
    std::vector<double> tries{};
    double lo = 0, hi = 0;
    std::function<std::string(double e)> format{};  // Exponent: e in the input's terms
    bool whole = false;  // Factor: multiplies the whole value (said as a ratio to the reference)
    // The exponents this term sets, as ids the step chooses: two terms that share one (G and
    // G1(N.V)) are not independent factors. Empty: its own.
    std::vector<int> knobs{};
};

// A scalar the step's function receives, in the lesson's terms, as its view derives it from
// the surface: "N.H" for a step given N and H = halfwayVector(L, V). Feedback names where an
// error lies by these ("wrong only where N.H < 0") and describes a point by them; a step that
// declares none is described by the cosines of its directions (N.V, N.L, V.L) and the fields
// its domain varies. `set` (optional) moves the surface to the value v of this input, leaving
// the others as they were: feedback evaluates the reference on inputs transformed by it.
struct InputAxis {
    std::string name;
    std::function<double(const Surface&)> value;
    std::function<void(Surface&, double)> set;
};

// The module's teaching domain as a distribution: one random point, every input the function
// reads varied independently over the range it is taught on (the ends of the domain belong
// to the probe; the extremes beyond it to the robustness sweep). Graded as "random inputs",
// and read by the feedback to tell which input an error depends on.
using DomainFn = std::function<Surface(DomainRandom&)>;

// One more set of inputs the grader checks, beyond the ones it makes for every module (the
// probe, the module's scene, random points of the domain, every parameter at other values,
// coloured lights for steps that sum the scene's lights).
struct GradeCase {
    enum class Inputs { Scene, Probe, Domain };
    std::string name;  // "the lesson's four-light grid"
    Inputs inputs = Inputs::Scene;
    std::string scene;             // a scene name for Inputs::Scene ("" the module's own)
    std::vector<std::string> set;  // parameter assignments, "samples=7"
};

// The lesson's sphere grid with four lights (seed 001): direct-lab steps shown on one light
// are also checked there, so a sum over one light only cannot pass.
inline GradeCase lessonGridCase() {
    return {"the lesson's sphere grid (four lights)", GradeCase::Inputs::Scene, "sphere-grid", {}};
}

// Estimators (Monte Carlo, quadratures) are judged by convergence, not sample by sample: the
// value is compared with the converged integral, within what any correct estimator of the same
// budget reaches (docs/design.md, "Grading policy").
struct Estimate {
    glm::dvec3 mean{0};   // the converged value (the CPU double reference of the integral)
    glm::dvec3 sigma{0};  // standard deviation of a one-sample estimate (0: deterministic)
    // The standard error of `mean` itself (0: exact), independent from point to point: the
    // statistics add it to the estimator's noise, sigma^2 / n + error^2.
    glm::dvec3 error{0};
};
struct EstimatorSpec {
    std::string samplesParam;  // the parameter that sets the sample count ("" none)
    // Graded counts, smallest first; the smallest measures the error's fall only (no band).
    std::vector<int> sampleCounts;
    // The environment correctness is judged on: one where legitimate estimators converge (no
    // sub-degree sun). The module's own scene stays for the quality report.
    std::string environment = "sky-soft";
    // Judged the same way on this one too ("" none): radiance of real dynamic range, a smooth
    // lobe of 1e4 to 1e5 on the soft sky (envgen.h), where every correct estimator still
    // converges and a clamp or tone map on radiance is off by orders of magnitude.
    std::string hdrEnvironment = "sky-hdr";
    // An environment with a real sun ("" none): judged on points facing the sun of roughness
    // up to sunMaxRoughness, at sunCounts, against the converged integral of sunTruthSamples
    // samples (docs/grading.md, "A real sun").
    std::string sunEnvironment = "sky-sun";
    std::vector<int> sunCounts = {1024, 16384};
    std::uint32_t sunTruthSamples = 262144;
    int sunPoints = 128;
    // Pixels of the module's scene judged in the picture check (docs/grading.md, "Graded in
    // the picture").
    int picturePixels = 512;
    double sunMaxRoughness = 0.5;
    // The converged value and one sample's spread at a point, measured with `truthSamples`
    // samples of the reference's estimator where it is not known in closed form.
    std::function<Estimate(const Surface&, const ReferenceContext&, std::uint32_t truthSamples)>
        converged;
    std::uint32_t truthSamples = 16384;
    // At n samples: |v - mean| <= t + sigmas * sqrt(sigma^2 / n + error^2), t from
    // `systematic` (what correct estimators differ by beyond noise: filtering, quadrature;
    // measured), on all but systematic.outlierFraction of the points.
    double sigmas = 5;
    Tolerance systematic;
    // The mean error at the smallest count must be at least this many times the mean error at
    // the largest: an estimator that ignores its sample count does not converge.
    double minimumFall = 3;
    // A noise budget, for a step whose lesson is its sampling (visible normals): on
    // `noisePoints` points drawn from `noiseDomain` (where the sampling matters: grazing view),
    // at `noiseCount` samples, the mean over the points of error^2 / (sigma^2 / n + error^2),
    // sigma this estimator's own one-sample spread, is at most `maxNoise`. A correct estimator
    // of this kind (plain Monte Carlo or better) stays near 1 or below; one that draws from
    // another density, however unbiased, carries its variance. Unset domain: no check.
    DomainFn noiseDomain;
    int noiseCount = 16;
    int noisePoints = 256;
    double maxNoise = 3;
    // > 0: the value may be off by a constant factor within this (a quadrature normalised by
    // its node count, as LearnOpenGL's is); the band then applies to the value divided by its
    // best-fit factor (the median ratio to the converged value), so an error that varies
    // with the inputs is held to `systematic` alone.
    double scaleTolerance = 0;
    // Counts above the largest of sampleCounts, at `highCountPoints` random points of the
    // domain and on the probe's edges: a function that stops using its count somewhere above
    // the graded ones returns the same values at n and 3n/4 (docs/grading.md, "Counts above
    // the graded ones"). The largest also grades an environment of another size.
    std::vector<int> highCounts = {4096, 65536};
    int highCountPoints = 16;
    // What correct estimators differ by beyond noise at the largest of highCounts, where
    // `systematic` allows for a blur that has vanished there (filtered importance sampling
    // reads LOD 0 at 65536 samples); unset: `systematic`.
    std::optional<Tolerance> systematicAtLargestCount;
    // The environment's other size (grading's is 256), for a step that reads it: 16 texels per
    // face, smaller than any map the host builds (128 to 512). Measured both ways: irradiance
    // with textureSize written as 256 reads a mip of 2 x 2 texels there, 5.4x the band (within
    // it at 48 and 64, 2.1x at 32); the rotated cosine estimator's worst over 200 seeds 0.43x
    // at 16, 1.002x (one failure) at 32 (docs/grading.md, "The environment at another size").
    int otherEnvironmentSize = 16;
    int domainPoints = 384;  // random points of the domain per count
    int probeStride = 2;     // every probeStride-th row and column of the probe (ends kept)
};

struct ModuleDesc {
    int abiVersion = kModuleAbiVersion;
    std::string id;        // contract id, e.g. "ndotl"
    int step = 0;          // contract step number (1..21): the lab order
    std::string lab;       // "direct" or "ibl"
    std::string title;     // one line for lists
    std::string function;  // the GLSL signature students implement
    std::vector<ParamDecl> params;
    int components = 1;       // meaningful channels of the value: 1 (float), 2, or 3
    bool nonNegative = true;  // a negative value is an error
    Display display;
    std::string scene = "sphere";    // default scene (assets/scenes/<name>.json)
    unsigned needs = NeedsGeometry;  // SurfaceNeeds flags
    std::vector<std::string> uses;   // other contract ids the view calls
    bool skyBackground = false;      // draw the environment behind the scene (radiance views)
    // With NeedsEnvironment: the values are radiance read from the environment, graded linear
    // in it. false for a step that reads only a map independent of the environment's radiance
    // (the BRDF LUT: the furnace's E = A + B).
    bool linearInEnvironment = true;
    Tolerance tolerance;
    std::vector<Tolerance> componentTolerances;  // per component when not empty
    ReferenceFn reference;
    std::vector<AcceptedAlternative> alternatives;
    Probe probe;
    DomainFn domain;  // optional
    std::vector<GradeCase> cases;
    std::optional<EstimatorSpec> estimator;
    // Extra views in the module's folder (<name>.glsl, each `vec3 view(Surface s)`), for
    // invariants that need other outputs than the picture's (the raw sample of a sampler).
    std::vector<std::string> extraViews;
    InvariantsFn invariants;  // optional
    // The quantities of this step's lesson the GUI can show over any picture, after the scene
    // inputs and the earlier steps' (in step order).
    std::vector<TermView> termViews;
    // What the step's function receives, when the view derives it (InputAxis); empty: the
    // generic ones.
    std::vector<InputAxis> inputAxes;
    // What the surface's extra inputs are to the step's function ("hdr", "Xi"), for feedback.
    std::string extraName = "extra";
    // The named parts of the step's formula (NamedTerm), for feedback; optional.
    std::vector<NamedTerm> namedTerms;
    // How many of a failed check's points the term fits evaluate, each fit evaluating the
    // step's value about 150 times there. 0: 192, or 32 for an estimator (its value costs its
    // sample count).
    int namedTermPoints = 0;

    const Tolerance& toleranceFor(int component) const {
        return componentTolerances.empty() ? tolerance
                                           : componentTolerances[size_t(std::min<int>(
                                                 component, int(componentTolerances.size()) - 1))];
    }
};

}  // namespace pbrlab

namespace pbrlab {

// A step linked into the program instead of loaded from a library (the browser has no dlopen):
// its id and descriptor, registered before main() by PBRLAB_MODULE when the build defines
// PBRLAB_STATIC_STEP as the step's id. ModuleRegistry takes them as it takes libraries.
struct StaticModule {
    const char* id;
    const ModuleDesc* (*get)();
};
bool registerStaticModule(StaticModule module);
const std::vector<StaticModule>& staticModules();

}  // namespace pbrlab

// Exports the module from its shared library. `makeDesc` is a function returning ModuleDesc.
#ifndef PBRLAB_STATIC_STEP
#define PBRLAB_MODULE(makeDesc)                            \
    extern "C" int pbrlab_module_abi() {                   \
        return pbrlab::kModuleAbiVersion;                  \
    }                                                      \
    extern "C" const pbrlab::ModuleDesc* pbrlab_module() { \
        static const pbrlab::ModuleDesc desc = makeDesc(); \
        return &desc;                                      \
    }
#else
#define PBRLAB_MODULE(makeDesc)                                                \
    namespace {                                                                \
    const pbrlab::ModuleDesc* staticModuleDesc() {                             \
        static const pbrlab::ModuleDesc desc = makeDesc();                     \
        return &desc;                                                          \
    }                                                                          \
    const bool staticModuleRegistered =                                        \
        pbrlab::registerStaticModule({PBRLAB_STATIC_STEP, &staticModuleDesc}); \
    }
#endif
