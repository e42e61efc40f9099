// Estimators at counts above the graded ones, and on the environment at another size
// (estimator.h).

#include <algorithm>
#include <cmath>
#include <set>

#include "grading/estimator.h"
#include "util/parallel.h"

namespace pbrlab::step_grading {

namespace {

// The probe's edges at three inner points each (indices into a w x h probe): twelve inputs with
// one argument at an end of its range and the other over its inner range. Not the corners: at
// N.V = 0 and roughness 0.05 the weights of the LUT's estimator have no useful variance
// (G / N.V), and the reference's own error at 65536 samples was 0.94x the band.
std::set<size_t> probeEdges(int w, int h) {
    std::set<size_t> edges;
    for (int k = 1; k <= 3; ++k) {
        const int x = k * (w - 1) / 4, y = k * (h - 1) / 4;
        for (const auto& [px, py] : {std::pair{x, 0}, {x, h - 1}, {0, y}, {w - 1, y}})
            edges.insert(size_t(py) * size_t(w) + size_t(px));
    }
    return edges;
}

// The check that an estimator uses its count: how many of `points` values at n samples are the
// values at `fewer` (within 4 units in the last place: the same sum in another order).
CheckReport countChanges(const ModuleDesc& d, const std::vector<glm::dvec3>& values,
                         const std::vector<glm::dvec3>& before, size_t points, int fewer, int n) {
    int same = 0;
    for (size_t i = 0; i < points; ++i) {
        bool equal = true;
        for (int c = 0; c < d.components; ++c)
            equal = equal && std::abs(values[i][c] - before[i][c]) <=
                                 4.8e-7 * std::max(std::abs(values[i][c]), std::abs(before[i][c]));
        same += equal;
    }
    const std::string& samplesParam = d.estimator->samplesParam;
    CheckReport changes;
    changes.name = "uses its sample count: " + std::to_string(fewer) + " and " + std::to_string(n) +
                   " samples give other values";
    changes.kind = CheckKind::Convergence;
    changes.category = CheckCategory::Estimator;
    changes.measured = same;
    changes.expected = "< half of " + std::to_string(points) + " points the same";
    // Correct estimators: 0 points the same at every seed measured (docs/grading.md).
    changes.passed = 2 * same < int(points);
    changes.detail = std::to_string(same) + " of " + std::to_string(points) +
                     " points have the same value with " + samplesParam + " = " +
                     std::to_string(fewer) + " and " + std::to_string(n) +
                     (changes.passed ? ""
                                     : ": ignores its sample count above " + std::to_string(fewer) +
                                           " (or less): an estimator of n samples changes with n; "
                                           "is the count capped?");
    return changes;
}

}  // namespace

// Counts above the graded ones (EstimatorSpec::highCounts): within the band of the converged
// integral, at the first few random points and on the probe's edges (one of its two inputs at
// an end of its range, the other over its range: an estimator that clamps an input short of
// its end, N.V at 0.9 say, is off there by more than the band at 65536 samples, and within
// the band of smaller counts everywhere). And different from the values at three quarters of the
// count: an estimator of n samples changes with n (other samples, or more of them), one that stops
// using its count above some N returns the same floats at every count above N, so a cap anywhere
// below 3n/4 is caught at n (one rendered at 3/4 of the previous count would leave the caps between
// the two counts unseen).
void StepGrader::gradeHighCounts(const Scene& judged, const PointSet& probe,
                                 const PointSet& random) {
    const PointSet points = highCountPoints(probe, random);
    for (int n : d_.estimator->highCounts)
        // The lowest count it ignores is said; the counts above say nothing more.
        if (!gradeHighCount(judged, points, n)) break;
}

// The points gradeHighCounts judges, with their converged integrals: the first random inputs
// and the probe's edges (probeEdges), named by how many of each.
StepGrader::PointSet StepGrader::highCountPoints(const PointSet& probe,
                                                 const PointSet& random) const {
    const EstimatorSpec& e = *d_.estimator;
    std::vector<Surface> surfaces;
    std::vector<Estimate> truth;
    const size_t randomPoints = std::min(size_t(e.highCountPoints), random.surfaces.size());
    for (size_t i = 0; i < randomPoints; ++i)
        surfaces.push_back(random.surfaces[i]), truth.push_back(random.truth[i]);
    for (size_t i : probeEdges(probe.width, probe.height)) {
        if (i >= probe.surfaces.size() || !probe.surfaces[i].covered) continue;
        surfaces.push_back(probe.surfaces[i]), truth.push_back(probe.truth[i]);
    }
    const std::string what = std::to_string(randomPoints) + " random inputs and " +
                             std::to_string(surfaces.size() - randomPoints) + " probe edges";
    Grid g = grid(std::move(surfaces));
    return {what, std::move(g.surfaces), g.width, g.height, nullptr, std::move(truth), {}};
}

// One count n above the graded ones: the values at n against those at 3n/4 (a check that the
// count is used) and against the band of the converged integral. False where the count is not
// used.
bool StepGrader::gradeHighCount(const Scene& judged, const PointSet& points, int n) {
    const EstimatorSpec& e = *d_.estimator;
    const size_t count = points.truth.size();
    const int fewer = n - n / 4;
    const std::string with = e.samplesParam + " = " + std::to_string(n);
    stage(points.name + " with " + e.samplesParam + " = " + std::to_string(fewer) + " and " +
          std::to_string(n));
    const std::vector<glm::dvec3> before = pointValues(
        renderPoints(withSamples(d_, fewer), judged, points.surfaces, points.width, points.height)
            .value,
        count);
    const ParamValues params = withSamples(d_, n);
    RenderResult r = renderPoints(params, judged, points.surfaces, points.width, points.height);
    const Tolerance& systematic = n == e.highCounts.back() && e.systematicAtLargestCount
                                      ? *e.systematicAtLargestCount
                                      : e.systematic;
    Band band = convergedBand(d_, points.surfaces, points.truth, n, systematic);
    const CheckReport changes =
        countChanges(d_, pointValues(r.value, count), before, count, fewer, n);
    record(changes);
    ValuesRun run =
        estimatorRun(points.name + " with " + with +
                         ((d_.needs & NeedsEnvironment) ? " (" + judged.environment + ")" : ""),
                     d_, points.surfaces, std::move(r.value), std::move(band), judged, params,
                     nullptr, points.width, points.height, &systematic);
    run.tier = ValuesRun::Tier::AboveGradedCounts;
    keep(std::move(run));
    return changes.passed;
}

// The environment at other sizes than grading's default (256): textureSize(uEnvironment) is a
// host value the step may read (a texel-sum quadrature picks its mip by it, filtered
// importance sampling its LOD). At EstimatorSpec::otherEnvironmentSize (16: it says why) and, for
// code that queries a texture's size, at the largest the host builds (`precompute
// --learnopengl`'s 512), at the largest count, where filtered importance sampling's LOD is 0,
// on the first random points. Cost: one cube of each size and 16 points each.
//
// A failure there is named from the evaluation. A size written in (256) is right at the
// default size at every count; at another size its error follows the count as a correct
// estimator's blur would at the size it assumes, and falls as n grows. A blur or mip choice
// that does not follow the sample count (a texel solid angle written 4 pi / (6 w n), so that n
// cancels in filtered importance sampling's LOD) reads textureSize and is wrong by a bias that
// does not shrink as n grows. So, on failure only, an estimator with a sample count is also
// rendered at the other size at the largest graded count (1024, 64x fewer samples: noise alone
// falls 8x), and the failure is told a bias that does not shrink where the error at the largest
// count stays above kBiasFallLimit of that. Measured on prefilter at 16 x 16 (mean relative
// error at 1024 and 65536 samples): the size written as 256 in filtered importance sampling
// 0.084 and 0.0091 (0.11 of it); the solid angle without n 0.0245 and 0.0242 (0.99), with
// Krivanek's +1 mip 0.0546 and 0.0547 (1.0; 0.056 at 64 samples: one blur at every count).
void StepGrader::gradeEnvironmentSize(const Scene& judged, const PointSet& random) {
    const EstimatorSpec& e = *d_.estimator;
    const size_t points = std::min(size_t(e.highCountPoints), random.surfaces.size());
    const Grid g =
        grid(std::vector<Surface>(random.surfaces.begin(), random.surfaces.begin() + long(points)));
    const int n = e.sampleCounts.empty() ? 0
                  : e.highCounts.empty() ? e.sampleCounts.back()
                                         : e.highCounts.back();
    const ParamValues params = paramsAt(d_, n);
    // The largest only for code that can tell it from the default: a read at a direction and a
    // LOD is the same function of a finer cube (a fixed mip is finer, nearer the truth), while
    // building the 512^2 cube costs 0.3-0.7 s.
    std::vector<int> sizes = {e.otherEnvironmentSize};
    if (codeQueriesTextureSize())
        sizes.push_back(
            std::max(IblSettings::learnOpenGl().environmentSize, kGradingIbl.environmentSize));
    for (const int size : sizes) {
        const std::string side = std::to_string(size) + "x" + std::to_string(size);
        IblSettings ibl = kGradingIbl;
        ibl.environmentSize = size;
        const ReferenceContext context = referenceContext(renderer_, d_, judged, params, ibl);
        std::vector<Estimate> truth(points);
        parallelFor(points, [&](size_t i) {
            if (g.surfaces[i].covered)
                truth[i] = e.converged(g.surfaces[i], context, e.truthSamples);
        });
        const std::string name = std::to_string(points) + " random inputs" + atCount(e, n) + " (" +
                                 judged.environment + ", uEnvironment " + side + ")";
        stage(name);
        noteHostValues(judged, params, ibl);
        RenderResult r =
            renderRescaled(name, params, judged, g.surfaces, g.width, g.height, truth, ibl);
        const double errorAtN = RelativeError::of(d_, r.value, g.surfaces, truth);
        Band band = convergedBand(d_, g.surfaces, truth, n, e.systematic);
        // Recorded, not handed to the feedback (whose references read the default maps).
        CheckReport report = estimatorRun(name, d_, g.surfaces, std::move(r.value), std::move(band),
                                          judged, params, nullptr, g.width, g.height)
                                 .report;
        if (!report.passed)
            report.detail =
                environmentSizeCause(judged, g, n, ibl, truth, errorAtN) + "; " + report.detail;
        record(report);
    }
}

// Why the check of gradeEnvironmentSize at `ibl`'s environment size failed, named from the
// evaluation (above): a size written in, or a bias that does not shrink as the count grows.
std::string StepGrader::environmentSizeCause(const Scene& judged, const Grid& g, int n,
                                             const IblSettings& ibl,
                                             const std::vector<Estimate>& truth, double errorAtN) {
    // Between the two (0.11 and 1.0), well above noise's 1/8.
    constexpr double kBiasFallLimit = 0.5;
    const EstimatorSpec& e = *d_.estimator;
    const std::string side =
        std::to_string(ibl.environmentSize) + "x" + std::to_string(ibl.environmentSize);
    const std::string hardCoded =
        "hard-coded host value (the size of uEnvironment, textureSize): right with " +
        std::to_string(kGradingIbl.environmentSize) + "x" +
        std::to_string(kGradingIbl.environmentSize) + ", wrong with " + side;
    const int fewer = e.sampleCounts.empty() ? 0 : e.sampleCounts.back();
    if (fewer <= 0 || fewer >= n || settings_.stopAtFirstFailure)
        // No count to vary: a size written in, or a blur or mip that does not follow it.
        return hardCoded + " (or a blur or mip choice that does not follow it)";
    const std::string fewerName = std::to_string(truth.size()) + " random inputs with " +
                                  e.samplesParam + " = " + std::to_string(fewer) + " (" +
                                  judged.environment + ", uEnvironment " + side + ")";
    stage(fewerName);
    const double errorAtFewer =
        RelativeError::of(d_,
                          renderRescaled(fewerName, paramsAt(d_, fewer), judged, g.surfaces,
                                         g.width, g.height, truth, ibl)
                              .value,
                          g.surfaces, truth);
    // The error at 65536 over the error at 1024 samples.
    const double fall = errorAtN / std::max(errorAtFewer, 1e-12);
    const std::string errors = "mean relative error " + number(errorAtFewer, 3) + " at " +
                               std::to_string(fewer) + " samples, " + number(errorAtN, 3) + " at " +
                               std::to_string(n);
    return fall <= kBiasFallLimit
               ? hardCoded + " (" + errors + ": it falls as n grows)"
               : "a bias that does not shrink as the sample count grows (" + errors +
                     " on uEnvironment " + side +
                     "): does a blur or mip choice not follow the sample count (a filtered "
                     "importance sampling LOD whose solid angle per sample lost n)?";
}

}  // namespace pbrlab::step_grading
