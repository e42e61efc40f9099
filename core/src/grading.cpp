#include "grading.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>

#include "cache_file.h"
#include "digest.h"
#include "feedback.h"
#include "mutants.h"
#include "parallel.h"
#include "pbrlab/contract.h"
#include "pbrlab/error.h"
#include "pbrlab/log.h"
#include "stability.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

constexpr int kRowWidth = 64;  // surface sets are uploaded as rows of 64 points

std::string number(double v, int digits = 4) {
    std::ostringstream o;
    o.precision(digits);
    o << v;
    return o.str();
}

std::string vec(const glm::dvec3& v, int components) {
    std::string s = "(";
    for (int c = 0; c < components; ++c) s += (c ? ", " : "") + number(v[c]);
    return components == 1 ? number(v.x) : s + ")";
}

// Surfaces as a width-64 grid, padded with uncovered points.
struct Grid {
    std::vector<Surface> surfaces;
    int width = kRowWidth, height = 1;
};

Grid grid(std::vector<Surface> surfaces) {
    Grid g;
    g.height = std::max(1, int((surfaces.size() + kRowWidth - 1) / kRowWidth));
    g.surfaces = std::move(surfaces);
    g.surfaces.resize(size_t(g.width) * size_t(g.height));
    return g;
}

ParamValues withSets(const ModuleDesc& d, const std::vector<std::string>& set) {
    ParamValues values(d.params);
    for (const std::string& a : set) applyAssignment(d.params, values, a);
    return values;
}

// Three lights of distinct colours and intensities at distances 3 to 10 from the scene's
// centre: steps that sum the scene's lights are graded with lights unlike the defaults.
Scene colouredLights(Scene scene) {
    const glm::dvec3 c = scene.camera.target;
    const double r = std::max(1.0, 0.3 * glm::length(scene.camera.position - c));
    scene.lights = {{c + r * glm::dvec3(1.2, 0.9, 1.5), {120, 45, 6}},
                    {c + r * glm::dvec3(-2.5, 0.4, 0.8), {2, 18, 60}},
                    {c + r * glm::dvec3(0.3, -1.0, 0.9), {0.9, 0.9, 0.9}}};
    return scene;
}

void addSurface(Digest& d, const Surface& s) {
    d.add(s.covered);
    if (!s.covered) return;
    d.add(s.position), d.add(s.normal), d.add(s.tangent), d.add(s.uv), d.add(s.view);
    d.add(s.light), d.add(s.lightPosition), d.add(s.lightColor), d.add(s.albedoTexel);
    d.add(s.albedo), d.add(s.metallic), d.add(s.roughness), d.add(s.ao), d.add(s.normalTexel);
    d.add(s.emissive), d.add(s.extra);
}

// Converged integrals on disk (cache_file.h): their count, then (mean, sigma) per point as
// doubles.
constexpr char kConvergedMagic[8] = {'P', 'B', 'R', 'L', 'C', 'N', 'V', '2'};

bool readConverged(const fs::path& file, std::vector<Estimate>& truth) {
    CacheReader in(file, kConvergedMagic);
    std::uint64_t count = 0;
    if (!in.get(count) || count != truth.size()) return false;
    std::vector<Estimate> values(truth.size());
    for (Estimate& e : values)
        if (!in.get(e.mean) || !in.get(e.sigma)) return false;
    if (!in.atEnd()) return false;
    truth = std::move(values);
    return true;
}

void writeConverged(const fs::path& file, const std::vector<Estimate>& truth) {
    CacheWriter out(kConvergedMagic);
    out.put(std::uint64_t(truth.size()));
    for (const Estimate& e : truth) out.put(e.mean), out.put(e.sigma);
    out.commit(file);
}

// A check of values against a band, with what feedback needs if it fails.
struct ValuesRun {
    CheckReport report;
    std::vector<Surface> surfaces;  // the inputs, as the view saw them
    Image value;
    Band band;
    Scene scene;
    ParamValues params;
    bool fromScene = false;  // the scene's G-buffer (else the surfaces were uploaded)
    int width = 0, height = 0;
    int worstIndex = -1;  // the point outside the band by most
};

// The name of a typical mistake: its file's leading comment block, one sentence.
std::string mistakeName(const fs::path& file) {
    std::ifstream in(file);
    std::string name;
    for (std::string line; std::getline(in, line) && line.rfind("//", 0) == 0;) {
        line = line.substr(2);
        if (name.empty() && line.rfind(" mistake:", 0) == 0) line = line.substr(9);
        const size_t b = line.find_first_not_of(' ');
        if (b != std::string::npos) name += (name.empty() ? "" : " ") + line.substr(b);
    }
    if (name.empty()) name = file.stem().string();
    if (name.back() != '.') name += '.';
    return name;
}

CheckReport reportFor(const std::string& name, const ModuleDesc& d, const Comparison& c,
                      const std::vector<Surface>& surfaces, double outlierFraction,
                      const Probe* probe, int width) {
    CheckReport r;
    r.name = name;
    r.points = c.compared;
    r.outside = c.outside;
    r.nan = c.nanCount;
    r.inf = c.infCount;
    r.negative = c.negativeCount;
    r.worstExcess = c.worstExcess;
    r.worstValue = c.worstValue;
    r.worstExpected = c.worstExpected;
    r.worstLo = c.worstLo;
    r.worstHi = c.worstHi;
    r.passed = c.passes(d.nonNegative, outlierFraction);
    if (c.worstIndex >= 0) {
        r.worstAt = describeInputs(d, surfaces[size_t(c.worstIndex)]);
        if (probe)
            r.worstAt = "probe x " + number(double(c.worstX) / (probe->width - 1), 3) + " (" +
                        probe->xAxis + "), y " +
                        number(1.0 - double(c.worstY) / (probe->height - 1), 3) + " (" +
                        probe->yAxis + "): " + r.worstAt;
        else if (width > kRowWidth || surfaces.size() > size_t(kRowWidth) * 64)
            r.worstAt = "pixel (" + std::to_string(c.worstX) + ", " + std::to_string(c.worstY) +
                        "): " + r.worstAt;
    }
    std::ostringstream o;
    o << c.compared << " points: " << c.outside << " outside the band";
    if (outlierFraction > 0) o << " (" << outlierFraction * 100 << "% may be)";
    o << ", worst " << number(c.worstExcess, 3) << "x the tolerance";
    if (c.nonFinite()) o << ", " << c.nanCount << " NaN, " << c.infCount << " Inf";
    if (c.negativeCount) o << ", " << c.negativeCount << " negative";
    r.detail = o.str();
    return r;
}

// The IBL settings of the maps grading reads: the defaults, as every RenderRequest below
// leaves them, so that the references read the maps the views read.
const IblSettings kGradingIbl{};

class StepGrader {
public:
    StepGrader(LabRenderer& renderer, const LoadedModule& m, const DataPaths& paths,
               const StudentSource& source, const GradeSettings& settings)
        : renderer_(renderer),
          m_(m),
          d_(*m.desc),
          paths_(paths),
          source_(source),
          settings_(settings) {}

    StepResult run() {
        auto start = std::chrono::steady_clock::now();
        const Scene scene = loadScene(paths_.scene(d_.scene));
        // Compile the student's program first: a compile error is the result.
        stage("compile");
        const auto program = renderer_.programs().get(renderer_.viewRecipe(m_, source_, true, 1));
        try {
            checkSamplers(*program);
            if (d_.estimator)
                gradeEstimator(scene);
            else
                gradeValues(scene);
            gradeInvariants(scene);
            if (settings_.robustness) gradeRobustness(scene);
        } catch (const Stopped&) {
            // stopAtFirstFailure: the verdict is known.
        }
        result_.passed = true;
        for (const CheckReport& c : result_.checks)
            if (c.deducted && !c.passed) result_.passed = false;
        if (!result_.passed) explain();
        stage("");  // the last stage's time
        result_.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return std::move(result_);
    }

private:
    struct Stopped {};

    // Every check goes in through here.
    void record(const CheckReport& c) {
        result_.checks.push_back(c);
        if (settings_.stopAtFirstFailure && c.deducted && !c.passed) throw Stopped{};
    }

    // Each stage is also a journal line (`--verbose`) with the time the previous one took: wall
    // clock and the CPU time of every thread of the process (the GL driver's and the CPU
    // references' included), which a busy machine does not inflate.
    // "" ends the last stage.
    void stage(const std::string& what) {
        const auto now = std::chrono::steady_clock::now();
        timespec cpu{};
        clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &cpu);
        const double cpuMs = double(cpu.tv_sec) * 1e3 + double(cpu.tv_nsec) * 1e-6;
        if (!stageName_.empty())
            logLine("grade",
                    d_.id + ": " + stageName_ + " " +
                        number(std::chrono::duration<double, std::milli>(now - stageStart_).count(),
                               4) +
                        " ms (cpu " + number(cpuMs - stageCpuMs_, 4) + " ms)");
        stageName_ = what;
        stageStart_ = now;
        stageCpuMs_ = cpuMs;
        if (settings_.stage && !what.empty()) settings_.stage(d_.id + ": " + what);
    }

    // No step may read what its own or a later step's reference solution computed (the
    // host precomputes those maps with the reference solutions).
    void checkSamplers(const Program& program) {
        const std::vector<std::string> forbidden = LabRenderer::forbiddenSamplers(d_, program);
        CheckReport c;
        c.name = "reads only the inputs this step may read";
        c.kind = "contract";
        c.passed = forbidden.empty();
        if (forbidden.empty()) {
            c.detail = "no map computed by this step's or a later step's reference solution";
        } else {
            for (const std::string& f : forbidden) {
                const ContractStep* step = findProvider(f);
                c.detail += (c.detail.empty() ? "" : "; ") + f +
                            (step ? " is computed by the reference solution of step " +
                                        std::to_string(step->step) + " (" + step->id + ")"
                                  : " is not an input of this step");
            }
            c.detail +=
                ": your function may not read it here (it reads black); compute the "
                "value from uEnvironment instead";
        }
        record(c);
    }

    ValuesRun runValues(const std::string& name, const Scene& scene, const ParamValues& params,
                        const std::vector<Surface>* surfaces, int width, int height,
                        const Probe* probe) {
        stage(name);
        EvalRequest request;
        request.render = {&m_, &params, &scene, source_, surfaces, width, height};
        request.render.seamlessCubes = false;
        request.render.isolatePoints = surfaces != nullptr;
        request.render.cacheGBuffer = true;
        Evaluation e = evaluate(renderer_, request);
        ValuesRun run;
        run.report = reportFor(name, d_, e.comparison, e.render.surfaces,
                               d_.tolerance.outlierFraction, probe, width);
        run.surfaces = std::move(e.render.surfaces);
        run.value = std::move(e.render.value);
        run.band = std::move(e.band);
        run.scene = scene;
        run.params = params;
        run.fromScene = surfaces == nullptr;
        run.width = width;
        run.height = height;
        run.worstIndex = e.comparison.worstIndex;
        return run;
    }

    void keep(ValuesRun&& run) {
        const CheckReport report = run.report;
        if (!run.report.passed && run.report.deducted &&
            (!failed_ || run.report.worstExcess > failed_->report.worstExcess))
            failed_ = std::make_unique<ValuesRun>(std::move(run));
        record(report);
    }

    void gradeCase(const std::string& name, GradeCase::Inputs inputs, const Scene& scene,
                   const ParamValues& params) {
        switch (inputs) {
            case GradeCase::Inputs::Probe: {
                const Probe& p = d_.probe;
                const std::vector<Surface> s = probeSurfaces(p);
                keep(runValues(name, scene, params, &s, p.width, p.height, &p));
                return;
            }
            case GradeCase::Inputs::Domain: {
                if (!d_.domain) return;
                const Grid g = grid(domainSurfaces(d_, settings_.seed, settings_.domainPoints));
                keep(runValues(name, scene, params, &g.surfaces, g.width, g.height, nullptr));
                return;
            }
            case GradeCase::Inputs::Scene:
                keep(runValues(name, scene, params, nullptr, settings_.size, settings_.size,
                               nullptr));
                return;
        }
    }

    void gradeValues(const Scene& scene) {
        const ParamValues defaults(d_.params);
        gradeCase("probe", GradeCase::Inputs::Probe, scene, defaults);
        gradeCase("scene " + scene.file.stem().string(), GradeCase::Inputs::Scene, scene, defaults);
        gradeCase("random inputs", GradeCase::Inputs::Domain, scene, defaults);
        for (const GradeCase& c : d_.cases) {
            const Scene s = c.scene.empty() ? scene : loadScene(paths_.scene(c.scene));
            gradeCase(c.name, c.inputs, s, withSets(d_, c.set));
        }
        for (const ParamDecl& p : d_.params)
            for (const std::string& assignment : exercisedValues(p)) {
                const ParamValues params = withSets(d_, {assignment});
                if (p.binding == ParamBinding::LightDirection) {
                    gradeCase("scene with " + assignment, GradeCase::Inputs::Scene, scene, params);
                    continue;
                }
                gradeCase("probe with " + assignment, GradeCase::Inputs::Probe, scene, params);
                gradeCase("scene with " + assignment, GradeCase::Inputs::Scene, scene, params);
                gradeCase("random inputs with " + assignment, GradeCase::Inputs::Domain, scene,
                          params);
            }
        // The reference's view or the student's (a student's sum may read the lights itself).
        if (readsSceneLights(renderer_, m_, {}, 3) || readsSceneLights(renderer_, m_, source_, 3)) {
            const Scene lit = colouredLights(scene);
            gradeCase("scene with three coloured lights", GradeCase::Inputs::Scene, lit, defaults);
            gradeCase("random inputs with three coloured lights", GradeCase::Inputs::Domain, lit,
                      defaults);
        }
    }

    // Estimators: against the converged integral on an environment where every correct
    // estimator converges, at several sample counts, within a noise-aware band; the error
    // must fall as the count grows. The module's own scene is the quality report.
    void gradeEstimator(const Scene& scene) {
        const EstimatorSpec& e = *d_.estimator;
        Scene judged = scene;
        if (!e.environment.empty()) judged.environment = e.environment;
        const ParamValues defaults(d_.params);
        const ReferenceContext context =
            referenceContext(renderer_, d_, judged, defaults, kGradingIbl);
        struct PointSet {
            std::string name;
            std::vector<Surface> surfaces;
            int width, height;
            const Probe* probe;
            std::vector<Estimate> truth;
            Image last;  // the values at the largest count
        };
        std::vector<PointSet> sets;
        // The probe at every probeStride-th row and column (its ends kept when the stride
        // divides size - 1): converged integrals cost thousands of samples per point.
        Probe probe = d_.probe;
        probe.width = (probe.width - 1) / e.probeStride + 1;
        probe.height = (probe.height - 1) / e.probeStride + 1;
        const double xScale = double(e.probeStride * (probe.width - 1)) / (d_.probe.width - 1),
                     yScale = double(e.probeStride * (probe.height - 1)) / (d_.probe.height - 1);
        probe.at = [&, xScale, yScale](double x, double y) {
            return d_.probe.at(std::min(x * xScale, 1.0), 1.0 - std::min((1.0 - y) * yScale, 1.0));
        };
        probe_ = probe;
        sets.push_back(
            {"probe", probeSurfaces(probe_), probe_.width, probe_.height, &probe_, {}, {}});
        if (d_.domain) {
            Grid g = grid(domainSurfaces(d_, settings_.seed, e.domainPoints));
            sets.push_back(
                {"random inputs", std::move(g.surfaces), g.width, g.height, nullptr, {}, {}});
        }
        stage("converged integrals");
        std::vector<const Surface*> points;
        for (const PointSet& set : sets)
            for (const Surface& surface : set.surfaces) points.push_back(&surface);
        std::vector<Estimate> truth(points.size());
        // Seconds of work per step, and a pure function of the reference's code, the
        // environment's texels, the points and the sample count: kept on disk, keyed by all of
        // them (a rebuild, another seed or other maps is another file).
        fs::path cached;
        // The code: the module's library (its CPU reference, linked in whole: it calls nothing
        // of pbrlab's executable) and the maths libraries it calls.
        if (const std::string code =
                buildIds({m_.library.filename().string(), "libm.so.6", "libstdc++.so.6"});
            !code.empty() && !renderer_.cacheRoot().empty()) {
            Digest key;
            key.add(std::string("converged integrals v1"));
            key.add(code);
            key.add(d_.id);
            key.add(e.truthSamples);
            if (d_.needs & NeedsEnvironment)
                key.add(renderer_.environmentDigest(judged, kGradingIbl,
                                                    d_.needs & NeedsPrecomputedMaps));
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
                if (points[i]->covered) truth[i] = e.converged(*points[i], context, e.truthSamples);
            });
            if (!cached.empty()) writeConverged(cached, truth);
        }
        logLine("grade", d_.id + ": converged integrals " +
                             (fromCache ? "read from " : "computed, kept in ") +
                             (cached.empty() ? std::string("no cache") : cached.string()));
        for (size_t k = 0; PointSet & set : sets) {
            set.truth.assign(truth.begin() + long(k),
                             truth.begin() + long(k + set.surfaces.size()));
            k += set.surfaces.size();
        }
        const std::vector<int> counts =
            e.sampleCounts.empty() ? std::vector<int>{0} : e.sampleCounts;
        std::vector<double> meanError;  // per count, over every point set
        for (int n : counts) {
            const ParamValues params =
                n > 0 ? withSets(d_, {e.samplesParam + "=" + std::to_string(n)}) : defaults;
            const double noise = n > 0 ? e.sigmas / std::sqrt(double(n)) : 0.0;
            double errorSum = 0;
            int errorCount = 0;
            for (PointSet& set : sets) {
                const std::string name =
                    set.name +
                    (n > 0 ? " with " + e.samplesParam + " = " + std::to_string(n) : "") +
                    (e.environment.empty() ? "" : " (" + e.environment + ")");
                stage(name);
                RenderRequest request{&m_,           &params,   &judged,   source_,
                                      &set.surfaces, set.width, set.height};
                request.seamlessCubes = false;
                request.isolatePoints = true;
                RenderResult r = renderer_.render(request);
                if (e.scaleTolerance > 0) rescale(set.name, r.value, set.surfaces, set.truth);
                Band band;
                band.resize(set.surfaces.size());
                for (size_t i = 0; i < set.surfaces.size(); ++i) {
                    if (!set.surfaces[i].covered) continue;
                    const Estimate& t = set.truth[i];
                    band.expected[i] = band.lo[i] = band.hi[i] = t.mean;
                    for (int c = 0; c < d_.components; ++c)
                        band.slack[i][c] = std::max(e.systematic.absolute,
                                                    e.systematic.relative * std::abs(t.mean[c])) +
                                           noise * t.sigma[c];
                    for (int c = 0; c < d_.components; ++c) {
                        const double v = r.value.pixels[i * 4 + size_t(c)];
                        if (!std::isfinite(v)) continue;
                        errorSum += std::abs(v - t.mean[c]) /
                                    std::max(std::abs(t.mean[c]), e.systematic.absolute);
                        ++errorCount;
                    }
                }
                const Comparison c = compareWithBand(r.value, set.surfaces, band, d_.components,
                                                     d_.nonNegative, e.systematic.outlierFraction);
                ValuesRun run;
                if (n == counts.back()) set.last = r.value;
                run.report = reportFor(name, d_, c, set.surfaces, e.systematic.outlierFraction,
                                       set.probe, set.width);
                run.report.detail += "; band: converged integral +- (" +
                                     number(e.systematic.relative) + " of it + " +
                                     number(e.sigmas) + " sigma / sqrt(n))";
                run.surfaces = set.surfaces;
                run.value = std::move(r.value);
                run.band = std::move(band);
                run.scene = judged;
                run.params = params;
                run.width = set.width;
                run.height = set.height;
                run.worstIndex = c.worstIndex;
                keep(std::move(run));
            }
            meanError.push_back(errorCount ? errorSum / errorCount : 0);
        }
        if (counts.size() > 1) {
            CheckReport fall;
            fall.name = "the error falls as the sample count grows";
            fall.kind = "convergence";
            const double ratio = meanError.front() / std::max(meanError.back(), 1e-12);
            fall.measured = ratio;
            fall.expected = ">= " + number(e.minimumFall);
            fall.passed = ratio >= e.minimumFall;
            fall.detail = "mean relative error " + number(meanError.front(), 3) + " at " +
                          std::to_string(counts.front()) + " samples, " +
                          number(meanError.back(), 3) + " at " + std::to_string(counts.back()) +
                          ": it fell " + number(ratio, 3) +
                          "x (an estimator of n samples: >= " + number(e.minimumFall) + "x)";
            record(fall);
        }
        if (counts.back() > 0) biasTest(sets, counts.back());
        // NaN, Inf and negatives are never excused: the module's own scene (64^2) at the
        // smallest count (other samples than the default's; the quality report below checks
        // that one).
        std::vector<int> finiteCounts;
        if (counts.front() > 0) finiteCounts.push_back(counts.front());
        for (int n : finiteCounts) {
            const ParamValues params = withSets(d_, {e.samplesParam + "=" + std::to_string(n)});
            stage("finite values with " + e.samplesParam + " = " + std::to_string(n));
            RenderRequest request{&m_, &params, &scene, source_, nullptr, 64, 64};
            request.seamlessCubes = false;
            request.readSurfaces = true;
            request.cacheGBuffer = true;
            const RenderResult r = renderer_.render(request);
            CheckReport finite;
            finite.name = "finite values on the scene " + scene.file.stem().string() + " with " +
                          e.samplesParam + " = " + std::to_string(n);
            for (size_t i = 0; i < r.surfaces.size(); ++i) {
                if (!r.surfaces[i].covered) continue;
                ++finite.points;
                bool nan = false, inf = false, negative = false;
                for (int c = 0; c < d_.components; ++c) {
                    const double v = r.value.pixels[i * 4 + size_t(c)];
                    nan = nan || std::isnan(v);
                    inf = inf || std::isinf(v);
                    negative = negative || (d_.nonNegative && v < 0);
                }
                finite.nan += nan;
                finite.inf += inf;
                finite.negative += negative;
            }
            finite.passed = finite.nan + finite.inf + finite.negative == 0;
            finite.detail = std::to_string(finite.nan) + " NaN, " + std::to_string(finite.inf) +
                            " Inf, " + std::to_string(finite.negative) + " negative of " +
                            std::to_string(finite.points) + " pixels";
            record(finite);
        }
        // The module's own scene, with its own sampling, against the same-sample reference:
        // how the picture compares, not a grade (a sub-degree sun decides it).
        ValuesRun quality = runValues(
            "quality: scene " + scene.file.stem().string() + " against the same-sample reference",
            scene, defaults, nullptr, settings_.size, settings_.size, nullptr);
        // Reported as a measurement: an estimator with other samples differs from this
        // picture as much as its noise, by design.
        CheckReport& q = quality.report;
        q.kind = "quality";
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
            finite.kind = "values";
            finite.deducted = true;
            finite.detail = std::to_string(q.nan) + " NaN, " + std::to_string(q.inf) + " Inf, " +
                            std::to_string(q.negative) + " negative of " +
                            std::to_string(q.points) + " pixels";
            record(finite);
        }
    }

    // EstimatorSpec::scaleTolerance: the overall factor between the value and the converged
    // integral (the median ratio) is checked on its own, and divided out before the band.
    void rescale(const std::string& name, Image& value, const std::vector<Surface>& surfaces,
                 const std::vector<Estimate>& truth) {
        const EstimatorSpec& e = *d_.estimator;
        std::vector<double> ratios;
        for (size_t i = 0; i < surfaces.size(); ++i) {
            if (!surfaces[i].covered) continue;
            for (int c = 0; c < d_.components; ++c) {
                const double v = value.pixels[i * 4 + size_t(c)], t = truth[i].mean[c];
                if (std::isfinite(v) && std::abs(t) > e.systematic.absolute)
                    ratios.push_back(v / t);
            }
        }
        double k = 1;
        if (!ratios.empty()) {
            std::nth_element(ratios.begin(), ratios.begin() + long(ratios.size() / 2),
                             ratios.end());
            k = ratios[ratios.size() / 2];
        }
        CheckReport c;
        c.name = name + ": overall scale";
        c.kind = "convergence";
        c.measured = k;
        c.expected = "1 +- " + number(e.scaleTolerance);
        c.passed = std::abs(k - 1) <= e.scaleTolerance;
        c.detail = "your values are " + number(k, 4) +
                   " x the converged integral overall (median ratio); a correct quadrature's "
                   "normalisation is within " +
                   number(e.scaleTolerance * 100) + "%";
        const std::string constant = nameConstant(k);
        if (!c.passed && !constant.empty()) c.detail += ": off by " + constant + "?";
        record(c);
        if (k > 0 && std::isfinite(k))
            for (size_t i = 0; i < surfaces.size(); ++i)
                for (int ch = 0; ch < d_.components; ++ch)
                    value.pixels[i * 4 + size_t(ch)] /= float(k);
    }

    // At the largest count a correct estimator's error is noise of scale sigma / sqrt(n),
    // independent from point to point or (for one low-discrepancy set shared by every point)
    // far smaller than that; a mistake's is a bias that keeps its sign over a region of
    // inputs. Per region (4 x 4 blocks of the probe, the random points by roughness), the sum
    // of the errors in units of sigma / sqrt(n), beyond the systematic allowance, over the
    // square root of their number must stay within 5 (a correct estimator: |z| > 5 with
    // probability 6e-7 per region).
    template <class Sets>
    void biasTest(const Sets& sets, int n) {
        const EstimatorSpec& e = *d_.estimator;
        struct Region {
            double sum = 0;
            int count = 0;
        };
        std::map<std::string, Region> regions;
        for (const auto& set : sets)
            for (size_t i = 0; i < set.surfaces.size(); ++i) {
                const Surface& s = set.surfaces[i];
                if (!s.covered) continue;
                std::string region;
                if (set.probe) {
                    const int x = int(i % size_t(set.width)), y = int(i / size_t(set.width));
                    region = "probe x " + std::to_string(4 * x / set.width) + "/4, y " +
                             std::to_string(3 - 4 * y / set.height) + "/4";
                } else {
                    region = "random inputs, roughness " +
                             std::to_string(std::min(3, int(s.roughness * 4))) + "/4";
                }
                const Estimate& t = set.truth[i];
                for (int c = 0; c < d_.components; ++c) {
                    const double v = set.last.pixels[i * 4 + size_t(c)];
                    const double scale = t.sigma[c] / std::sqrt(double(n));
                    if (!std::isfinite(v) || scale <= 0) continue;
                    const double allowed = std::max(e.systematic.absolute,
                                                    e.systematic.relative * std::abs(t.mean[c]));
                    const double error = v - t.mean[c];
                    const double beyond =
                        std::copysign(std::max(std::abs(error) - allowed, 0.0), error);
                    Region& r = regions[region];
                    r.sum += beyond / scale;
                    ++r.count;
                }
            }
        CheckReport c;
        c.name = "no systematic error at " + std::to_string(n) + " samples";
        c.kind = "convergence";
        std::string worst;
        double worstZ = 0;
        for (const auto& [name, r] : regions) {
            const double z = r.count ? r.sum / std::sqrt(double(r.count)) : 0;
            if (std::abs(z) > std::abs(worstZ)) worstZ = z, worst = name;
        }
        c.measured = worstZ;
        c.expected = "|z| <= 5";
        c.passed = std::abs(worstZ) <= 5;
        c.detail = "the errors at " + std::to_string(n) +
                   " samples sum to z = " + number(worstZ, 3) + " noise units in " +
                   (worst.empty() ? "no region" : worst) +
                   (c.passed ? " (noise: |z| <= 5)"
                             : ": a bias that keeps its sign there, " +
                                   std::string(worstZ < 0 ? "too low" : "too high") +
                                   " (noise alone stays within |z| <= 5)");
        record(c);
    }

    void gradeInvariants(const Scene& scene) {
        if (!d_.invariants) return;
        stage("invariants");
        Evaluator evaluator;
        evaluator.run = [&](const std::vector<Surface>& surfaces, const std::string& view,
                            const std::vector<std::string>& set) {
            // Rows of kRowWidth points; a copy only when the last row needs padding (the
            // chi-square test's 131072 samples do not).
            const bool whole = !surfaces.empty() && surfaces.size() % kRowWidth == 0;
            const Grid g = whole ? Grid() : grid(surfaces);
            const ParamValues params = withSets(d_, set);
            RenderRequest request{&m_,
                                  &params,
                                  &scene,
                                  source_,
                                  whole ? &surfaces : &g.surfaces,
                                  kRowWidth,
                                  whole ? int(surfaces.size() / kRowWidth) : g.height};
            request.seamlessCubes = false;
            request.isolatePoints = true;
            request.view = view;
            RenderResult r = renderer_.render(request);
            std::vector<glm::dvec3> values;
            for (size_t i = 0; i < surfaces.size(); ++i)
                values.emplace_back(r.value.pixels[i * 4], r.value.pixels[i * 4 + 1],
                                    r.value.pixels[i * 4 + 2]);
            return values;
        };
        for (const InvariantResult& inv : d_.invariants(evaluator)) {
            CheckReport c;
            c.name = inv.name;
            c.kind = "invariant";
            c.measured = inv.measured;
            c.expected = inv.expected;
            c.passed = inv.holds;
            c.detail = inv.name + " = " + number(inv.measured) + ", expected " + inv.expected;
            if (!inv.holds && !inv.hint.empty()) c.detail += " (" + inv.hint + ")";
            record(c);
        }
    }

    void gradeRobustness(const Scene& scene) {
        stage("robustness");
        const StabilityResult st = stabilitySweep(renderer_, m_, scene, source_);
        CheckReport c;
        c.name = "robustness on extreme inputs";
        c.kind = "robustness";
        c.deducted = false;
        c.points = st.gpu.compared;
        c.nan = st.gpu.nanCount;
        c.inf = st.gpu.infCount;
        c.negative = d_.nonNegative ? st.gpu.negativeCount : 0;
        c.passed = c.nan + c.inf + c.negative == 0;
        c.worstAt = st.firstProblem;
        c.detail = std::to_string(c.points) + " extreme inputs: " + std::to_string(c.nan) +
                   " NaN, " + std::to_string(c.inf) + " Inf, " + std::to_string(c.negative) +
                   " negative" + (st.firstProblem.empty() ? "" : "; first at " + st.firstProblem);
        record(c);
    }

    // The failure message: the first failed check, and the mistake named from the shape of
    // the error of the check that failed worst.
    void explain() {
        // What leads the message: a broken contract (it reads what it may not) explains
        // everything after it; else the values check with its worst input.
        const CheckReport* first = nullptr;
        for (const char* kind : {"contract", "values", ""})
            for (const CheckReport& c : result_.checks)
                if (!first && c.deducted && !c.passed && (!*kind || c.kind == kind)) first = &c;
        std::string message;
        if (first) {
            message = first->name + ": " + first->detail;
            if (first->kind == "values" && !first->worstAt.empty())
                message += "; at " + first->worstAt + ": yours " +
                           vec(first->worstValue, d_.components) + ", expected " +
                           vec(first->worstExpected, d_.components) + " (accepted " +
                           vec(first->worstLo, d_.components) + " .. " +
                           vec(first->worstHi, d_.components) + ")";
        }
        if (failed_ && settings_.feedback) {
            stage("feedback");
            FeedbackInputs in;
            in.module = &d_;
            const ValuesRun& f = *failed_;
            for (size_t i = 0; i < f.surfaces.size(); ++i) {
                if (!f.surfaces[i].covered) continue;
                in.surfaces.push_back(f.surfaces[i]);
                in.values.emplace_back(f.value.pixels[i * 4], f.value.pixels[i * 4 + 1],
                                       f.value.pixels[i * 4 + 2]);
                in.expected.push_back(f.band.expected[i]);
                in.slack.push_back(f.band.slack[i]);
            }
            const Scene bound = applyParamBindings(f.scene, d_, f.params);
            auto context = std::make_shared<ReferenceContext>(
                referenceContext(renderer_, d_, bound, f.params, kGradingIbl));
            in.reference = [this, context](const Surface& s) { return d_.reference(s, *context); };
            in.student = [this, &f](const std::vector<Surface>& surfaces) {
                const Grid g = grid(surfaces);
                RenderRequest request{&m_,         &f.params, &f.scene, source_,
                                      &g.surfaces, g.width,   g.height};
                request.seamlessCubes = false;
                request.isolatePoints = true;
                RenderResult r = renderer_.render(request);
                std::vector<glm::dvec3> values;
                for (size_t i = 0; i < surfaces.size(); ++i)
                    values.emplace_back(r.value.pixels[i * 4], r.value.pixels[i * 4 + 1],
                                        r.value.pixels[i * 4 + 2]);
                return values;
            };
            // The estimator's bands are not the reference's: the sensitivity test would
            // compare against the same-sample reference, so it is left out there.
            if (!d_.estimator) in.domain = d_.domain;
            bool exact = false;
            result_.mistake = classifyError(in, &exact);
            if (!result_.mistake.empty()) result_.namedBy = "pattern";
            // The candidates below are compared on a sample of the failed check's points.
            Sample points;
            if (settings_.typicalMistakes || settings_.mutantCatalogue) points = sample(f);
            const std::string typical = settings_.typicalMistakes ? typicalMistake(f, points) : "";
            if (!typical.empty()) {
                result_.mistake += (result_.mistake.empty() ? "" : " ") +
                                   std::string("It matches a typical mistake: ") + typical;
                if (!exact) result_.namedBy = "typical";
            }
            // When no pattern accounts for every point, the mutants of the reference solution:
            // the one change the student's values equal.
            if (!exact && typical.empty() && settings_.mutantCatalogue) {
                stage("feedback: one change from the reference");
                const MutantMatch match = mutantMatch(f, points);
                if (!match.mistake.empty()) {
                    result_.mistake += (result_.mistake.empty() ? "" : " ") + match.mistake;
                    result_.namedBy = "mutant";
                    result_.instructorNote = "the reference with " + match.change;
                }
            }
        }
        for (const CheckReport& c : result_.checks)
            if (c.deducted && !c.passed && c.kind != "values" && &c != first)
                message += "; " + c.name + ": " + c.detail;
        result_.message = result_.mistake.empty() || (first && first->kind == "contract")
                              ? message + (result_.mistake.empty() ? "" : " " + result_.mistake)
                              : result_.mistake + " " + message;
    }

    // What the typical mistakes and the mutants are compared with: up to 96 points of the failed
    // check (evenly spread, its worst among them) and the student's values there, rendered
    // once. Every candidate is then one small render on the same points.
    struct Sample {
        std::vector<size_t> picked;   // indices into the failed check's points
        std::vector<Surface> points;  // those points, in rows of kRowWidth (padded)
        int height = 0;
        Image student;
    };

    Sample sample(const ValuesRun& f) {
        Sample out;
        std::vector<size_t> covered;
        for (size_t i = 0; i < f.surfaces.size(); ++i)
            if (f.surfaces[i].covered) covered.push_back(i);
        if (covered.empty()) return out;
        const size_t step = std::max<size_t>(1, covered.size() / 95);
        for (size_t k = 0; k < covered.size() && out.picked.size() < 95; k += step)
            out.picked.push_back(covered[k]);
        if (f.worstIndex >= 0 && f.surfaces[size_t(f.worstIndex)].covered)
            out.picked.push_back(size_t(f.worstIndex));
        for (size_t i : out.picked) out.points.push_back(f.surfaces[i]);
        out.points.resize((out.points.size() + kRowWidth - 1) / kRowWidth * kRowWidth);
        out.height = int(out.points.size() / kRowWidth);
        out.student = valuesOn(f, out, source_);
        return out;
    }

    Image valuesOn(const ValuesRun& f, const Sample& sample, const StudentSource& source) {
        RenderRequest request{&m_,       &f.params,    &f.scene, source, &sample.points,
                              kRowWidth, sample.height};
        request.seamlessCubes = false;
        request.isolatePoints = true;
        return renderer_.render(request).value;
    }

    // At how many of the sampled points a candidate's values equal the student's (within twice
    // the band's width), and how far apart they are over all of them (0: equal everywhere).
    struct Agreement {
        int same = 0;
        double distance = 0;
    };

    Agreement agreement(const ValuesRun& f, const Sample& sample, const Image& candidate) const {
        Agreement a;
        for (size_t p = 0; p < sample.picked.size(); ++p) {
            bool equal = true;
            for (int c = 0; c < d_.components; ++c) {
                const double v = sample.student.pixels[p * 4 + size_t(c)],
                             m = candidate.pixels[p * 4 + size_t(c)];
                const double slack = 2 * f.band.slack[sample.picked[p]][c] + 1e-6 * std::abs(m);
                const double e = v == m ? 0 : std::abs(v - m) / std::max(slack, 1e-300);
                equal = equal && e <= 1;
                a.distance += std::isfinite(e) ? std::min(e, 1e6) : 1e6;
            }
            a.same += equal;
        }
        return a;
    }

    // The step's typical mistakes (labs/<id>/mistakes/*.glsl): the one the student's values
    // equal at 95% of the sampled points names the mistake outright.
    std::string typicalMistake(const ValuesRun& f, const Sample& sample) {
        const fs::path dir = m_.sourceDir / "mistakes";
        std::error_code ec;
        if (sample.picked.empty() || !fs::is_directory(dir, ec)) return "";
        std::vector<fs::path> files;
        for (const auto& e : fs::directory_iterator(dir, ec))
            if (e.path().extension() == ".glsl") files.push_back(e.path());
        std::sort(files.begin(), files.end());
        const fs::path tmp =
            fs::temp_directory_path() / ("pbrlab-mistake-" + std::to_string(::getpid()));
        std::string best;
        double bestShare = 0.95;
        for (const fs::path& file : files) {
            fs::create_directories(tmp, ec);
            fs::copy_file(file, tmp / (d_.id + ".glsl"), fs::copy_options::overwrite_existing, ec);
            try {
                const Agreement a = agreement(f, sample, valuesOn(f, sample, {tmp, false}));
                const double share = double(a.same) / double(sample.picked.size());
                if (share >= bestShare) bestShare = share, best = mistakeName(file);
            } catch (const Error&) {
            }
        }
        fs::remove_all(tmp, ec);
        return best;
    }

    // Each mutant of the reference solution (mutants.h) on the sampled points: one the student's
    // values equal (at 95% of them, the closest overall) is the mistake, said to the student by
    // its family; its change quotes the reference and goes to the instructor only. One equal
    // everywhere cannot be beaten: the search stops there.
    struct MutantMatch {
        std::string mistake;  // for the student
        std::string change;   // for the instructor: `mutated` for `reference`
    };
    MutantMatch mutantMatch(const ValuesRun& f, const Sample& sample) {
        if (sample.picked.empty()) return {};
        std::ifstream in(m_.sourceDir / "solution.glsl", std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        const std::vector<Mutant> mutants = generateMutants(text.str());
        const fs::path tmp =
            fs::temp_directory_path() / ("pbrlab-feedback-" + std::to_string(::getpid()));
        std::error_code ec;
        fs::create_directories(tmp, ec);
        MutantMatch best;
        double bestDistance = 1e300;
        for (size_t k = 0; k < mutants.size() && bestDistance > 0; ++k) {
            const fs::path dir = tmp / std::to_string(k);
            fs::create_directories(dir, ec);
            std::ofstream(dir / (d_.id + ".glsl"), std::ios::binary) << mutants[k].text;
            Image mutant;
            try {
                mutant = valuesOn(f, sample, {dir, false});
            } catch (const Error&) {
                continue;  // does not compile
            }
            const Agreement a = agreement(f, sample, mutant);
            if (a.same >= 0.95 * double(sample.picked.size()) && a.distance < bestDistance) {
                bestDistance = a.distance;
                std::string mistake = mutants[k].family;
                for (const MutantFamily& family : mutantFamilies())
                    if (mutants[k].family == family.name) mistake = family.mistake;
                best = {"It behaves like the reference with one change: " + mistake + ".",
                        mutants[k].change};
            }
        }
        fs::remove_all(tmp, ec);
        return best;
    }

    LabRenderer& renderer_;
    const LoadedModule& m_;
    const ModuleDesc& d_;
    const DataPaths& paths_;
    const StudentSource& source_;
    const GradeSettings& settings_;
    StepResult result_;
    std::unique_ptr<ValuesRun> failed_;  // the values check that failed worst
    Probe probe_;                        // the estimator's subsampled probe
    std::string stageName_;              // the stage running, and since when
    std::chrono::steady_clock::time_point stageStart_;
    double stageCpuMs_ = 0;
};

}  // namespace

std::vector<std::string> exercisedValues(const ParamDecl& p) {
    std::vector<glm::dvec3> values;
    switch (p.type) {
        case ParamType::Int: {
            const double lo = std::max(p.min, 1.0), hi = std::min(p.max, 1024.0);
            for (double v : {lo, 7.0, hi})
                if (v >= p.min && v <= p.max) values.push_back(glm::dvec3(v));
            break;
        }
        case ParamType::Float:
            values = {glm::dvec3(p.min), glm::dvec3(p.max)};
            break;
        case ParamType::Bool:
            values = {glm::dvec3(0), glm::dvec3(1)};
            break;
        case ParamType::Enum:
            for (size_t i = 0; i < p.choices.size(); ++i) values.push_back(glm::dvec3(double(i)));
            break;
        case ParamType::Color:
            values = {{0.9, 0.5, 0.1}, {0.1, 0.3, 0.8}};
            break;
        case ParamType::Direction:
            values = {glm::normalize(glm::dvec3(-5, 3, 6)), glm::normalize(glm::dvec3(2, -4, 7))};
            break;
    }
    std::vector<std::string> out;
    for (const glm::dvec3& v : values)
        if (v != p.defaultValue) out.push_back(p.name + "=" + p.format(v));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

std::vector<Surface> domainSurfaces(const ModuleDesc& module, std::uint64_t seed, int count) {
    std::vector<Surface> out;
    if (!module.domain) return out;
    DomainRandom random(seed);
    for (int i = 0; i < count; ++i) {
        Surface s = module.domain(random);
        s.covered = true;
        out.push_back(s);
    }
    return out;
}

StepResult gradeStep(LabRenderer& renderer, const LoadedModule& module, const DataPaths& paths,
                     const StudentSource& source, const GradeSettings& settings) {
    return StepGrader(renderer, module, paths, source, settings).run();
}

nlohmann::json toJson(const CheckReport& c) {
    nlohmann::json j = {{"name", c.name},
                        {"kind", c.kind},
                        {"passed", c.passed},
                        {"deducted", c.deducted},
                        {"detail", c.detail}};
    if (c.kind == "values" || c.kind == "quality") {
        j["points"] = c.points;
        j["outside"] = c.outside;
        j["nan"] = c.nan;
        j["inf"] = c.inf;
        j["negative"] = c.negative;
        j["worst_excess"] = std::isfinite(c.worstExcess) ? c.worstExcess : 1e300;
        j["worst_at"] = c.worstAt;
        auto arr = [](const glm::dvec3& v) {
            auto f = [](double x) { return std::isfinite(x) ? x : 0.0; };
            return nlohmann::json::array({f(v.x), f(v.y), f(v.z)});
        };
        j["worst_value"] = arr(c.worstValue);
        j["worst_expected"] = arr(c.worstExpected);
        j["worst_accepted"] = {arr(c.worstLo), arr(c.worstHi)};
    } else if (c.kind == "robustness") {
        j["points"] = c.points;
        j["nan"] = c.nan;
        j["inf"] = c.inf;
        j["negative"] = c.negative;
        j["first_problem"] = c.worstAt;
    } else {
        j["measured"] = std::isfinite(c.measured) ? c.measured : 1e300;
        j["expected"] = c.expected;
    }
    return j;
}

}  // namespace pbrlab
