// Estimators graded by convergence (estimator.h): the order of their checks, converged integrals
// and the band around them, finite values, the overall scale, the quality report.

#include <algorithm>
#include <cmath>

#include "grading/estimator.h"
#include "ibl/precompute.h"
#include "util/cache_file.h"
#include "util/digest.h"
#include "util/log.h"
#include "util/parallel.h"

namespace fs = std::filesystem;

namespace pbrlab::step_grading {

namespace {

void addSurface(Digest& d, const Surface& s) {
    d.add(s.covered);
    if (!s.covered) return;
    d.add(s.position), d.add(s.normal), d.add(s.tangent), d.add(s.uv), d.add(s.view);
    d.add(s.light), d.add(s.lightPosition), d.add(s.lightColor), d.add(s.albedoTexel);
    d.add(s.albedo), d.add(s.metallic), d.add(s.roughness), d.add(s.ao), d.add(s.normalTexel);
    d.add(s.emissive), d.add(s.extra);
}

// Converged integrals on disk (cache_file.h): their count, then (mean, sigma, error) per
// point as doubles.
constexpr char kConvergedMagic[8] = {'P', 'B', 'R', 'L', 'C', 'N', 'V', '3'};

bool readConverged(const fs::path& file, std::vector<Estimate>& truth) {
    CacheReader in(file, kConvergedMagic);
    std::uint64_t count = 0;
    if (!in.get(count) || count != truth.size()) return false;
    std::vector<Estimate> values(truth.size());
    for (Estimate& e : values)
        if (!in.get(e.mean) || !in.get(e.sigma) || !in.get(e.error)) return false;
    if (!in.atEnd()) return false;
    truth = std::move(values);
    return true;
}

void writeConverged(const fs::path& file, const std::vector<Estimate>& truth) {
    CacheWriter out(kConvergedMagic);
    out.put(std::uint64_t(truth.size()));
    for (const Estimate& e : truth) out.put(e.mean), out.put(e.sigma), out.put(e.error);
    out.commit(file);
}

}  // namespace

// The noise a value at n samples has around the converged value: the estimator's own,
// sigma / sqrt(n), and the converged value's own error (independent of it).
glm::dvec3 noiseAt(const Estimate& t, int n) {
    return glm::sqrt(t.sigma * t.sigma / double(std::max(n, 1)) + t.error * t.error);
}

// The band around the converged integrals at n samples (0: no noise term), for the covered
// points: |v - mean| <= systematic + sigmas * sqrt(sigma^2 / n + error^2).
Band convergedBand(const ModuleDesc& d, const std::vector<Surface>& surfaces,
                   const std::vector<Estimate>& truth, int n, const Tolerance& systematic) {
    Band band;
    band.resize(surfaces.size());
    for (size_t i = 0; i < truth.size() && i < surfaces.size(); ++i) {
        if (!surfaces[i].covered) continue;
        const Estimate& t = truth[i];
        band.expected[i] = band.lo[i] = band.hi[i] = t.mean;
        const glm::dvec3 noise = n > 0 ? noiseAt(t, n) : glm::dvec3(0);
        for (int c = 0; c < d.components; ++c)
            band.slack[i][c] =
                std::max(systematic.absolute, systematic.relative * std::abs(t.mean[c])) +
                d.estimator->sigmas * noise[c];
    }
    return band;
}

// A values check against the converged integral (`value` compared with `band` here), as
// feedback keeps it: the estimator's own category (not the probe's or the random inputs' band
// of the reference) and its band's rule.
ValuesRun estimatorRun(const std::string& name, const ModuleDesc& d,
                       const std::vector<Surface>& surfaces, Image value, Band band,
                       const Scene& scene, const ParamValues& params, const Probe* probe, int width,
                       int height, const Tolerance* systematicHere) {
    const EstimatorSpec& e = *d.estimator;
    const Tolerance& systematic = systematicHere ? *systematicHere : e.systematic;
    const Comparison c = compareWithBand(value, surfaces, band, d.components, d.nonNegative,
                                         systematic.outlierFraction);
    ValuesRun run;
    run.report = reportFor(name, d, c, surfaces, systematic.outlierFraction, probe, width);
    run.report.category = CheckCategory::Estimator;
    run.report.detail += "; band: converged integral +- (" + number(systematic.relative) +
                         " of it + " + number(e.sigmas) + " sqrt(sigma^2 / n + its own error^2))";
    run.surfaces = surfaces;
    run.value = std::move(value);
    run.band = std::move(band);
    run.scene = scene;
    run.params = params;
    run.width = width;
    run.height = height;
    run.worstIndex = c.worstIndex;
    run.outlierFraction = systematic.outlierFraction;
    return run;
}

// NaN, Inf and (for a non-negative step) negatives among the covered points: never excused,
// whatever the noise.
CheckReport finiteValues(const std::string& name, const ModuleDesc& d, const Image& value,
                         const std::vector<Surface>& surfaces, const std::string& points) {
    CheckReport finite;
    finite.category = CheckCategory::Estimator;
    finite.name = name;
    for (size_t i = 0; i < surfaces.size(); ++i) {
        if (!surfaces[i].covered) continue;
        ++finite.points;
        bool nan = false, inf = false, negative = false;
        for (int c = 0; c < d.components; ++c) {
            const double v = value.pixels[i * 4 + size_t(c)];
            nan = nan || std::isnan(v);
            inf = inf || std::isinf(v);
            negative = negative || (d.nonNegative && v < 0);
        }
        finite.nan += nan;
        finite.inf += inf;
        finite.negative += negative;
    }
    finite.passed = finite.nan + finite.inf + finite.negative == 0;
    finite.detail = std::to_string(finite.nan) + " NaN, " + std::to_string(finite.inf) + " Inf, " +
                    std::to_string(finite.negative) + " negative of " +
                    std::to_string(finite.points) + " " + points;
    return finite;
}

// The module's parameters with its sample count set to n.
ParamValues withSamples(const ModuleDesc& d, int n) {
    return withSets(d, {d.estimator->samplesParam + "=" + std::to_string(n)});
}

// The parameters a check at n samples renders with: the defaults at 0 (no count to set).
ParamValues paramsAt(const ModuleDesc& d, int n) {
    return n > 0 ? withSamples(d, n) : ParamValues(d.params);
}

// " with samples = n" in a check's name ("" at 0: no count).
std::string atCount(const EstimatorSpec& e, int n) {
    return n > 0 ? " with " + e.samplesParam + " = " + std::to_string(n) : "";
}

// The addresses of `surfaces`, as convergedIntegrals takes its points.
std::vector<const Surface*> addresses(const std::vector<Surface>& surfaces) {
    std::vector<const Surface*> points;
    for (const Surface& surface : surfaces) points.push_back(&surface);
    return points;
}

// Each point drawn alone, as the estimator's checks render them.
RenderResult StepGrader::renderPoints(const ParamValues& params, const Scene& scene,
                                      const std::vector<Surface>& surfaces, int width, int height,
                                      const IblSettings& ibl) {
    RenderRequest request{&m_, &params, &scene, source_, &surfaces, width, height};
    request.ibl = ibl;
    request.seamlessCubes = false;
    request.isolatePoints = true;
    return renderer_.render(request);
}

// renderPoints, then the overall scale against `truth` checked and divided out where the
// estimator's scale is checked on its own (EstimatorSpec::scaleTolerance).
RenderResult StepGrader::renderRescaled(const std::string& scaleName, const ParamValues& params,
                                        const Scene& scene, const std::vector<Surface>& surfaces,
                                        int width, int height, const std::vector<Estimate>& truth,
                                        const IblSettings& ibl) {
    RenderResult r = renderPoints(params, scene, surfaces, width, height, ibl);
    if (d_.estimator->scaleTolerance > 0) rescale(scaleName, r.value, surfaces, truth);
    return r;
}

// The converged integrals at `points` with `samples` samples of the reference's estimator.
// Seconds of work per step, and a pure function of the reference's code, the environment's
// texels, the points and the sample count: kept on disk, keyed by all of them (a rebuild,
// another seed or other maps is another file).
std::vector<Estimate> StepGrader::convergedIntegrals(const std::vector<const Surface*>& points,
                                                     const Scene& judged,
                                                     const ReferenceContext& context,
                                                     std::uint32_t samples) {
    const EstimatorSpec& e = *d_.estimator;
    std::vector<Estimate> truth(points.size());
    fs::path cached;
    // The code: the module's library (its CPU reference, linked in whole: it calls nothing
    // of pbrlab's executable) and the maths libraries it calls.
    if (const std::string code =
            buildIds({m_.library.filename().string(), "libm.so.6", "libstdc++.so.6"});
        !code.empty() && !renderer_.cacheRoot().empty()) {
        Digest key;
        key.add(std::string("converged integrals v2"));
        key.add(code);
        key.add(d_.id);
        key.add(samples);
        if (d_.needs & NeedsEnvironment)
            key.add(
                renderer_.environmentDigest(judged, kGradingIbl, d_.needs & NeedsPrecomputedMaps));
        for (const ParamDecl& p : d_.params) {
            key.add(p.name);
            key.add(context.params.vector(p.name));
        }
        for (const ref::PointLight& l : context.lights) key.add(l.position), key.add(l.color);
        key.add(context.cameraPosition);
        key.add(points.size());
        for (const Surface* surface : points) addSurface(key, *surface);
        cached = renderer_.cacheRoot() / "converged" / (d_.id + "-" + key.hex() + ".bin");
    }
    const bool fromCache = !cached.empty() && readConverged(cached, truth);
    if (!fromCache) {
        // Thousands of samples per point, on every core (the references are pure).
        parallelFor(points.size(), [&](size_t i) {
            if (points[i]->covered) truth[i] = e.converged(*points[i], context, samples);
        });
        if (!cached.empty()) writeConverged(cached, truth);
    }
    logLine("grade", d_.id + ": converged integrals " +
                         (fromCache ? "read from " : "computed, kept in ") +
                         (cached.empty() ? std::string("no cache") : cached.string()));
    return truth;
}

// Estimators: against the converged integral on environments where every correct
// estimator converges (the soft sky, and the same with radiance of real dynamic range), at
// several sample counts, within a noise-aware band; the error must fall as the count grows,
// and the values must keep changing with counts above the graded ones. The module's own
// scene is the quality report.
void StepGrader::gradeEstimator(const Scene& scene) {
    const EstimatorSpec& e = *d_.estimator;
    std::vector<std::string> environments;
    if (d_.needs & NeedsEnvironment)
        for (const std::string& name : {e.environment, e.hdrEnvironment})
            if (!name.empty()) environments.push_back(name);
    if (environments.empty()) environments.push_back("");  // the scene's own (none read)
    if (statisticsParts_ & Convergence) {
        for (size_t k = 0; k < environments.size(); ++k)
            gradeConvergence(scene, environments[k], k == 0);
        gradeNoise(scene);
    }
    if (statisticsParts_ & Sun) gradeSun(scene);
    if (statisticsParts_ & Picture) gradePicture(scene);
    if (statisticsOnly_) return;
    const ParamValues defaults(d_.params);
    const std::vector<int> counts = e.sampleCounts.empty() ? std::vector<int>{0} : e.sampleCounts;
    // NaN, Inf and negatives are never excused: the module's own scene (64^2) at the
    // smallest count (other samples than the default's; the quality report below checks
    // that one).
    std::vector<int> finiteCounts;
    if (counts.front() > 0) finiteCounts.push_back(counts.front());
    for (int n : finiteCounts) {
        const ParamValues params = withSamples(d_, n);
        stage("finite values with " + e.samplesParam + " = " + std::to_string(n));
        RenderRequest request{&m_, &params, &scene, source_, nullptr, 64, 64};
        request.seamlessCubes = false;
        request.readSurfaces = true;
        request.cacheGBuffer = true;
        const RenderResult r = renderer_.render(request);
        record(finiteValues("finite values on the scene " + scene.file.stem().string() + " with " +
                                e.samplesParam + " = " + std::to_string(n),
                            d_, r.value, r.surfaces, "pixels"));
    }
    // The module's own scene, with its own sampling, against the same-sample reference:
    // how the picture compares, not a grade (a sub-degree sun decides it).
    ValuesRun quality = runValues(
        "quality: scene " + scene.file.stem().string() + " against the same-sample reference",
        CheckCategory::Estimator, scene, defaults, nullptr, settings_.size, settings_.size,
        nullptr);
    // Reported as a measurement: an estimator with other samples differs from this
    // picture as much as its noise, by design.
    CheckReport& q = quality.report;
    q.kind = CheckKind::Quality;
    q.deducted = false;
    double sum = 0;
    int count = 0;
    for (size_t i = 0; i < quality.surfaces.size(); ++i) {
        if (!quality.surfaces[i].covered) continue;
        for (int c = 0; c < d_.components; ++c) {
            const double v = quality.value.pixels[i * 4 + size_t(c)];
            const double r = quality.band.expected[i][c];
            if (!std::isfinite(v)) continue;
            sum += std::abs(v - r) / std::max(std::abs(r), e.systematic.absolute);
            ++count;
        }
    }
    q.measured = count ? sum / count : 0;
    q.detail = "mean relative difference " + number(q.measured, 3) +
               " from the reference solution's own picture (" + q.detail +
               "): how the picture looks, not a grade";
    q.passed = q.nan + q.inf + q.negative == 0;
    record(q);
    // Whatever the picture's differences, NaN, Inf and negatives are never excused.
    if (!q.passed) {
        CheckReport finite = q;
        finite.name = "finite, non-negative values on the scene " + scene.file.stem().string();
        finite.kind = CheckKind::Values;
        finite.deducted = true;
        finite.detail = std::to_string(q.nan) + " NaN, " + std::to_string(q.inf) + " Inf, " +
                        std::to_string(q.negative) + " negative of " + std::to_string(q.points) +
                        " pixels";
        record(finite);
    }
}

// EstimatorSpec::scaleTolerance: the overall factor between the value and the converged
// integral (the median ratio) is checked on its own, and divided out before the band.
void StepGrader::rescale(const std::string& name, Image& value,
                         const std::vector<Surface>& surfaces, const std::vector<Estimate>& truth,
                         bool nameConstants) {
    const EstimatorSpec& e = *d_.estimator;
    std::vector<double> ratios;
    for (size_t i = 0; i < surfaces.size(); ++i) {
        if (!surfaces[i].covered) continue;
        for (int c = 0; c < d_.components; ++c) {
            const double v = value.pixels[i * 4 + size_t(c)], t = truth[i].mean[c];
            if (std::isfinite(v) && std::abs(t) > e.systematic.absolute) ratios.push_back(v / t);
        }
    }
    double k = 1;
    if (!ratios.empty()) {
        std::nth_element(ratios.begin(), ratios.begin() + long(ratios.size() / 2), ratios.end());
        k = ratios[ratios.size() / 2];
    }
    CheckReport c;
    c.name = name + ": overall scale";
    c.kind = CheckKind::Convergence;
    c.category = CheckCategory::Estimator;
    c.measured = k;
    c.expected = "1 +- " + number(e.scaleTolerance);
    c.passed = std::abs(k - 1) <= e.scaleTolerance;
    c.detail = "your values are " + number(k, 4) +
               " x the converged integral overall (median ratio); a correct quadrature's "
               "normalisation is within " +
               number(e.scaleTolerance * 100) + "%";
    const std::string constant = nameConstant(k);
    if (!c.passed && nameConstants && !constant.empty()) c.detail += ": off by " + constant + "?";
    record(c);
    if (k > 0 && std::isfinite(k))
        for (size_t i = 0; i < surfaces.size(); ++i)
            for (int ch = 0; ch < d_.components; ++ch) value.pixels[i * 4 + size_t(ch)] /= float(k);
}

StepResult StepGrader::runEstimatorStatistics(unsigned parts) {
    statisticsOnly_ = true;
    statisticsParts_ = parts;
    const Scene scene = loadScene(paths_.scene(d_.scene));
    try {
        if (d_.estimator) gradeEstimator(scene);
    } catch (const Stopped&) {
    }
    result_.passed = true;
    for (const CheckReport& c : result_.checks)
        if (c.deducted && !c.passed) result_.passed = false;
    return std::move(result_);
}

}  // namespace pbrlab::step_grading
