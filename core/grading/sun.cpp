// A real sun in the environment (step_grader.h): where it is, points that face it, and the
// values check of steps that read the environment's maps (the estimators' sun check is with
// their convergence, grading/estimator_band.cpp).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "grading/step_grader.h"
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
        return "treats bright light differently: " + without + "too low at " + std::to_string(low) +
               where + " (median " + number(median, 3) +
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
    if (!run.report.passed)
        if (const std::string cause =
                sunCause(run.value, run.surfaces, run.band, d_.components, cleanBefore);
            !cause.empty()) {
            run.report.detail = cause + "; " + run.report.detail;
            if (cleanBefore) run.cause = cause;
        }
    run.tier = ValuesRun::Tier::LabUse;
    keep(std::move(run));
}

}  // namespace pbrlab::step_grading
