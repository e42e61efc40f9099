// A real sun in the environment (step_grader.h, estimator.h): where it is, points that face it,
// the values check of steps that read the environment's maps, and the estimators' check on the
// points that face it.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

#include "assets/envgen.h"
#include "grading/estimator.h"
#include "ibl/precompute.h"

namespace pbrlab::step_grading {

namespace {

// `s` turned as a whole (every direction it holds) by the rotation that takes `from` to `to`.
Surface turned(Surface s, const glm::dvec3& from, const glm::dvec3& to) {
    const glm::dvec3 axis = glm::cross(from, to);
    const double sine = glm::length(axis), cosine = glm::dot(from, to);
    if (sine < 1e-12) return s;  // parallel: nothing to turn (opposite never happens here)
    const glm::dvec3 k = axis / sine;
    auto rotate = [&](const glm::dvec3& v) {  // Rodrigues
        return v * cosine + glm::cross(k, v) * sine + k * glm::dot(k, v) * (1 - cosine);
    };
    s.normal = rotate(s.normal);
    s.view = rotate(s.view);
    s.light = rotate(s.light);
    s.tangent = glm::dvec4(rotate(glm::dvec3(s.tangent)), s.tangent.w);
    return s;
}

}  // namespace

// The direction of the brightest texel of a cube's finest level (luminance): where an
// environment's sun is, whatever environment it is.
glm::dvec3 brightestDirection(const CubeSampler& cube) {
    double best = -1;
    glm::dvec3 direction(0, 1, 0);
    const auto& level = cube.mips().front();
    for (int face = 0; face < int(level.size()); ++face) {
        const Image& im = level[size_t(face)];
        for (int y = 0; y < im.height; ++y)
            for (int x = 0; x < im.width; ++x) {
                const double l =
                    0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
                if (l > best) best = l, direction = cubeTexelDirection(face, x, y, im.width);
            }
    }
    return direction;
}

// Random points of the domain turned so that their mirror direction, reflect(-V, N), falls
// near the sun: at an angle from it of up to 0.5 degrees plus 60 degrees times alpha
// (roughness squared, the contract's width of a GGX lobe), so that the sun lies in the lobe,
// near its peak or on its flank. Points of roughness up to `maxRoughness` only: beyond it a
// sun of a fraction of a degree is met too rarely for any sample count graded to resolve.
std::vector<Surface> sunFacingSurfaces(const ModuleDesc& d, std::uint64_t seed, int count,
                                       const glm::dvec3& sun, double maxRoughness) {
    std::vector<Surface> out;
    DomainRandom random(seed ^ 0x5017a1u);
    DomainRandom angles(seed * 31 + 7);
    for (int tries = 0; int(out.size()) < count && tries < 64 * count; ++tries) {
        Surface s = d.domain(random);
        s.covered = true;
        if (s.roughness > maxRoughness) continue;
        const glm::dvec3 R = glm::reflect(-s.view, s.normal);
        if (glm::length(R) < 0.5) continue;
        const double alpha = s.roughness * s.roughness;
        const double angle =
            std::sqrt(angles.uniform()) * (0.5 + 60.0 * alpha) * std::numbers::pi / 180.0;
        const glm::dvec3 target =
            glm::normalize(sun * std::cos(angle) +
                           glm::normalize(glm::cross(sun, angles.direction())) * std::sin(angle));
        out.push_back(turned(s, glm::normalize(R), target));
    }
    return out;
}

namespace {
// sunCause's one diagnosis of a rule rather than of a shape: a function that limits bright
// light is right wherever no light is bright, so no comparison on other inputs finds it.
constexpr std::string_view kBrightLightRule = "treats bright light differently";
}  // namespace

std::string sunCause(const Image& value, const std::vector<Surface>& points, const Band& band,
                     int components, bool rightWithoutSun) {
    int low = 0, high = 0, judged = 0;
    std::vector<double> ratios;
    for (size_t i = 0; i < points.size(); ++i) {
        if (!points[i].covered) continue;
        ++judged;
        // The component farthest outside says which way the point is off.
        double worst = 1;
        int side = 0;
        for (int c = 0; c < components; ++c) {
            const double v = value.pixels[i * 4 + size_t(c)];
            const double slack = std::max(band.slack[i][c], 1e-300);
            const double below = (band.lo[i][c] - v) / slack, above = (v - band.hi[i][c]) / slack;
            if (below > worst) worst = below, side = -1;
            if (above > worst) worst = above, side = 1;
            if (c == 0 && std::abs(band.expected[i][c]) > 0)
                ratios.push_back(v / band.expected[i][c]);
        }
        low += side < 0;
        high += side > 0;
    }
    if (low + high == 0) return "";
    std::nth_element(ratios.begin(), ratios.begin() + long(ratios.size() / 2), ratios.end());
    const double median = ratios.empty() ? 1 : ratios[ratios.size() / 2];
    const std::string where = " of " + std::to_string(judged) + " points facing the sun";
    // Its other checks failed too: the sun is not known to be the cause, so the facts only.
    if (!rightWithoutSun)
        return "facing the sun, " + std::to_string(low) + " too low and " + std::to_string(high) +
               " too high" + where + " (median " + number(median, 3) +
               " x the converged integral there)";
    const std::string without = "right on every sky without a sun, ";
    // A rule that drops or limits bright light only ever lowers a value; an estimate too
    // coarse for the sun misses it at most points and over-counts it at a few.
    const double few = 0.05 * (low + high);
    if (high <= few)
        return std::string(kBrightLightRule) + ": " + without + "too low at " +
               std::to_string(low) + where + " (median " + number(median, 3) +
               " x the converged integral there): is bright light clamped, dropped or limited "
               "relative to the rest (a firefly filter)?";
    if (low <= few)
        return "too bright where the sun is in view: " + without + "too high at " +
               std::to_string(high) + where + " (median " + number(median, 3) +
               " x the converged integral there)";
    return "too coarse for a sun: " + without + "off both ways at points facing it (" +
           std::to_string(high) + " too high, " + std::to_string(low) + " too low" + where +
           "): are its samples or nodes farther apart than the sun is "
           "wide? (the sun is a fraction of a degree; a sum over a mip's texels with their solid "
           "angles keeps its light)";
}

// A step that reads the environment's maps but is no estimator (the split sum): its values
// on points facing the sun, with the maps the host precomputes from an environment with a
// real sun (the estimators' EstimatorSpec::sunEnvironment), against the reference on the same
// maps. A limit on bright light that follows the environment's own brightness (a highlight
// clamped relative to the irradiance) is linear under the scaling checks and invisible on the
// smooth skies; here the sun's highlight is most of the value.
glm::dvec3 StepGrader::sunDirection(const Scene& judged) {
    return brightestDirection(renderer_.environmentInputs(judged, kGradingIbl, false).environment);
}

bool StepGrader::noFailureSoFar() const {
    return std::none_of(result_.checks.begin(), result_.checks.end(),
                        [](const CheckReport& c) { return c.deducted && !c.passed; });
}

void StepGrader::gradeSunValues(const Scene& scene) {
    if (!(d_.needs & NeedsEnvironment) || !d_.domain || d_.estimator) return;
    Scene judged = scene;
    judged.environment = settings_.sunEnvironment.empty() ? EstimatorSpec{}.sunEnvironment
                                                          : settings_.sunEnvironment;
    const Grid g =
        grid(sunFacingSurfaces(d_, settings_.seed, kSunFacingPoints, sunDirection(judged), 0.5));
    const bool cleanBefore = noFailureSoFar();
    ValuesRun run = runValues("random inputs facing the sun (" + judged.environment + ")",
                              CheckCategory::Random, judged, ParamValues(d_.params), &g.surfaces,
                              g.width, g.height, nullptr);
    // The shape of the error goes first in the check's detail. It is the mistake's name only
    // when it is the bright-light rule: a value too high or off both ways where the sun is in
    // view is a mistake of the maps' use that the sun shows best (the multiple-scattering term
    // lit by the prefiltered map: on a smooth sky the two maps nearly agree), and the typical
    // mistakes and mutants, drawn on these points under this sun, name it.
    if (!run.report.passed)
        if (const std::string cause =
                sunCause(run.value, run.surfaces, run.band, d_.components, cleanBefore);
            !cause.empty()) {
            run.report.detail = cause + "; " + run.report.detail;
            if (cleanBefore && cause.starts_with(kBrightLightRule)) run.cause = cause;
        }
    run.tier = ValuesRun::Tier::LabUse;
    keep(std::move(run));
}

namespace {

// The points of `surfaces` (with their converged integrals `truth` and the sun's part of them)
// at which the sun is resolved at n samples, the others uncovered: by the truth (its part's
// standard error under 5% of it, or the part under 0.1% of the value) and by n samples (their
// noise under 25% of the value).
std::vector<Surface> sunResolved(const ModuleDesc& d, const std::vector<Surface>& surfaces,
                                 const std::vector<Estimate>& truth,
                                 const std::vector<Estimate>& sunPart, int n) {
    const EstimatorSpec& e = *d.estimator;
    std::vector<Surface> judgedPoints = surfaces;
    for (size_t i = 0; i < judgedPoints.size(); ++i) {
        if (!judgedPoints[i].covered) continue;
        bool resolved = true;
        for (int c = 0; c < d.components; ++c) {
            const double value = std::abs(truth[i].mean[c]);
            const double part = std::abs(sunPart[i].mean[c]);
            const bool truthResolves = part <= 1e-3 * value || sunPart[i].error[c] <= 0.05 * part;
            const bool countResolves =
                n == 0 || truth[i].sigma[c] / std::sqrt(double(n)) <= 0.25 * value;
            resolved = resolved && value > e.systematic.absolute && truthResolves && countResolves;
        }
        judgedPoints[i].covered = resolved;
    }
    return judgedPoints;
}

}  // namespace

// An environment with a real sun (EstimatorSpec::sunEnvironment): a disc of a fraction of
// a degree, 1e5 times the sky. A rule that treats bright samples differently from the others
// (a firefly clamp, a rejection relative to the other samples) is linear under the scaling
// and sum checks and invisible on the smooth skies, and drops most of the light where the sun
// is in the lobe. Judged on points facing the sun, where the sun is met often enough by the
// samples of the counts graded to be resolved: the converged integral there comes with the
// sun's own part (`sunOnly`, the disc alone, same samples), and a point is judged at n only
// when the truth resolves the sun (its part's standard error under 5% of it, or the part
// under 0.1% of the value) and n samples do too (the noise of n samples under 25% of the
// value: a handful of sun samples at least, so that a correct estimator's error is near
// normal there).
void StepGrader::gradeSun(const Scene& scene) {
    const EstimatorSpec& e = *d_.estimator;
    if ((e.sunEnvironment.empty() && settings_.sunEnvironment.empty()) ||
        !(d_.needs & NeedsEnvironment) || !d_.domain)
        return;
    Scene judged = scene, sunOnly = scene;
    judged.environment =
        settings_.sunEnvironment.empty() ? e.sunEnvironment : settings_.sunEnvironment;
    sunOnly.environment = judged.environment + kBrightSuffix;
    const std::string on = " (" + judged.environment + ")";
    const ParamValues defaults(d_.params);
    const ReferenceContext context = referenceContext(renderer_, d_, judged, defaults, kGradingIbl);
    const ReferenceContext sunContext =
        referenceContext(renderer_, d_, sunOnly, defaults, kGradingIbl);
    Grid g = grid(sunFacingSurfaces(d_, settings_.seed, e.sunPoints, sunDirection(judged),
                                    e.sunMaxRoughness));
    PointSet set{"points facing the sun", g.surfaces, g.width, g.height, nullptr, {}, {}};
    const std::vector<const Surface*> points = addresses(set.surfaces);
    stage("converged integrals" + on);
    set.truth = convergedIntegrals(points, judged, context, e.sunTruthSamples);
    const std::vector<Estimate> sunPart =
        convergedIntegrals(points, sunOnly, sunContext, e.sunTruthSamples);
    // Every check before passed: a failure here is the sun's, and the message may say so.
    const bool cleanBefore = noFailureSoFar();
    const std::vector<int> counts = e.samplesParam.empty() ? std::vector<int>{0} : e.sunCounts;
    for (int n : counts) gradeSunAt(judged, set, sunPart, n, cleanBefore, on);
}

// One count of gradeSun: the points where the sun is resolved at n samples against the band,
// the overall scale and the bias test there, each failure told its cause from the error's shape
// (sunCause).
void StepGrader::gradeSunAt(const Scene& judged, const PointSet& set,
                            const std::vector<Estimate>& sunPart, int n, bool cleanBefore,
                            const std::string& on) {
    const EstimatorSpec& e = *d_.estimator;
    const ParamValues params = paramsAt(d_, n);
    const std::vector<Surface> judgedPoints = sunResolved(d_, set.surfaces, set.truth, sunPart, n);
    const int count = int(std::count_if(judgedPoints.begin(), judgedPoints.end(),
                                        [](const Surface& s) { return s.covered; }));
    const std::string name = std::to_string(count) + " " + set.name + atCount(e, n) + on;
    stage(name);
    RenderResult r = renderPoints(params, judged, set.surfaces, set.width, set.height);
    Band band = convergedBand(d_, judgedPoints, set.truth, n, e.systematic);
    // Which way the values are off, before an overall factor is divided out (a sun's light
    // dropped is a factor of its own where the sun is most of the value).
    const std::string cause = sunCause(r.value, judgedPoints, band, d_.components, cleanBefore);
    if (e.scaleTolerance > 0) {
        rescale(name, r.value, judgedPoints, set.truth, false);
        CheckReport& scale = result_.checks.back();
        if (!scale.passed && !cause.empty()) scale.detail = cause + "; " + scale.detail;
    }
    PointSet judgedSet = set;
    judgedSet.surfaces = judgedPoints;
    judgedSet.last = r.value;
    ValuesRun run = estimatorRun(name, d_, judgedPoints, std::move(r.value), std::move(band),
                                 judged, params, nullptr, set.width, set.height);
    run.tier = !e.sampleCounts.empty() && n > e.sampleCounts.back()
                   ? ValuesRun::Tier::AboveGradedCounts
                   : ValuesRun::Tier::LabUse;
    if (!run.report.passed && !cause.empty()) {
        run.report.detail = cause + "; " + run.report.detail;
        if (cleanBefore) run.cause = cause;
    }
    keep(std::move(run));
    if (n > 0) {
        biasTest({judgedSet}, n, on);
        CheckReport& bias = result_.checks.back();
        if (!bias.passed && !cause.empty()) bias.detail = cause + "; " + bias.detail;
    }
}

}  // namespace pbrlab::step_grading
