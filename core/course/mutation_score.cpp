#include "course/mutation_score.h"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>

#include "assets/image_io.h"
#include "course/autograder.h"
#include "gl/context.h"
#include "grading/grade_step.h"
#include "grading/mutants_semantic.h"
#include "grading/stability.h"
#include "render/compare.h"
#include "util/error.h"
#include "util/fs.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

namespace {

std::string number(double v) {
    std::ostringstream o;
    o.precision(3);
    o << v;
    return o.str();
}

// Runs `work` in a child process (GL lives and dies there) and returns what it returned.
std::string inChild(const std::function<std::string()>& work) {
    int fds[2];
    if (pipe(fds) != 0) throw Error("mutants: pipe failed");
    const pid_t pid = fork();
    if (pid < 0) throw Error("mutants: fork failed");
    if (pid == 0) {
        close(fds[0]);
        std::string out;
        try {
            out = work();
        } catch (const std::exception& e) {
            out = json{{"error", e.what()}}.dump();
        }
        for (size_t done = 0; done < out.size();) {
            const ssize_t n = write(fds[1], out.data() + done, out.size() - done);
            if (n <= 0) break;
            done += size_t(n);
        }
        close(fds[1]);
        _exit(0);
    }
    close(fds[1]);
    std::string text;
    char buf[65536];
    for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) text.append(buf, size_t(n));
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    return text;
}

// How far the mutant's values are from the reference solution's on the same inputs, in
// units of float rounding there (1e-5 of the value, the module's absolute floor, or the
// reference's spread under 8 ulps of its inputs): <= 1 means equal within rounding.
struct Difference {
    double worst = 0;
    std::string where;
};

// The reference solution against `other` (the mutant's folder; empty: the solution again, at
// `otherParams`) on the same inputs, under the maps `ibl`.
Difference compareRenders(LabRenderer& renderer, const LoadedModule& m, const Scene& scene,
                          const ParamValues& params, const std::vector<Surface>* surfaces,
                          int width, int height, const fs::path& other, const std::string& label,
                          const IblSettings& ibl = {}, const ParamValues* otherParams = nullptr) {
    const ModuleDesc& d = *m.desc;
    RenderRequest request{&m, &params, &scene, {}, surfaces, width, height};
    request.seamlessCubes = false;  // both sides under the same conditions: no quads needed
    request.readSurfaces = true;
    request.cacheGBuffer = true;
    request.ibl = ibl;
    const RenderResult solution = renderer.render(request);
    request.source = {other, false};
    if (otherParams) request.params = otherParams;
    const RenderResult mutant = renderer.render(request);
    ModuleDesc rounding = d;  // the band of float rounding alone: no alternatives, 1e-5
    rounding.alternatives.clear();
    rounding.tolerance.relative = 1e-5;
    for (Tolerance& t : rounding.componentTolerances) t.relative = 1e-5;
    const Scene bound = applyParamBindings(scene, d, params);
    const ReferenceContext context = referenceContext(renderer, d, bound, params, request.ibl);
    Difference diff;
    for (size_t i = 0; i < solution.surfaces.size(); ++i) {
        const Surface& s = solution.surfaces[i];
        if (!s.covered) continue;
        glm::dvec3 spread(0);
        if (rounding.tolerance.ulps > 0) spread = referenceSpread(d, s, context, 8, i + 1);
        for (int c = 0; c < d.components; ++c) {
            const double a = solution.value.pixels[i * 4 + size_t(c)];
            const double b = mutant.value.pixels[i * 4 + size_t(c)];
            const Tolerance& t = rounding.toleranceFor(c);
            double e;
            if (!std::isfinite(a) || !std::isfinite(b))
                e = (std::isnan(a) && std::isnan(b)) || a == b ? 0 : 1e30;
            else
                e = std::abs(a - b) /
                    std::max({t.absolute, 1e-5 * std::max(std::abs(a), std::abs(b)), spread[c]});
            if (e > diff.worst) {
                diff.worst = e;
                std::ostringstream o;
                o.precision(6);
                o << label << ": solution " << a << ", " << (other.empty() ? "again " : "mutant ")
                  << b << " at " << describeInputs(d, s);
                diff.where = o.str();
            }
        }
    }
    return diff;
}

// Dense comparison over the teaching domain: the probe, many random points of the domain,
// the module's scenes, every exercised parameter value, every graded sample count; and,
// separately, the extreme inputs.
json equivalence(LabRenderer& renderer, const LoadedModule& m, const DataPaths& paths,
                 const fs::path& mutantDir) {
    const ModuleDesc& d = *m.desc;
    Scene scene = loadScene(paths.scene(d.scene));
    std::vector<std::pair<std::string, ParamValues>> settings{{"defaults", ParamValues(d.params)}};
    for (const ParamDecl& p : d.params)
        for (const std::string& a : exercisedValues(p)) {
            ParamValues v(d.params);
            applyAssignment(d.params, v, a);
            // An estimator's counts above kFewPointsAbove are graded on a few points only (a
            // count cap is the semantic family's, with its own witness): thousands of points at
            // 65536 samples would cost minutes, and a float sum that long differs from the
            // solution's by more than rounding wherever one sample lands 1 ulp apart.
            if (d.estimator && p.type == ParamType::Int && v.number(p.name) > kFewPointsAbove)
                continue;
            settings.push_back({a, v});
        }
    if (d.estimator && !d.estimator->samplesParam.empty())
        for (int n : d.estimator->sampleCounts) {
            const std::string a = d.estimator->samplesParam + "=" + std::to_string(n);
            bool seen = false;
            for (const auto& [name, v] : settings) seen = seen || name == a;
            if (seen) continue;
            ParamValues v(d.params);
            applyAssignment(d.params, v, a);
            settings.push_back({a, v});
        }
    std::vector<Scene> scenes{scene};
    for (const GradeCase& c : d.cases)
        if (c.inputs == GradeCase::Inputs::Scene && !c.scene.empty())
            scenes.push_back(loadScene(paths.scene(c.scene)));
    if (d.estimator && !d.estimator->environment.empty()) {
        Scene judged = scene;
        judged.environment = d.estimator->environment;
        scenes.push_back(judged);
    }
    // Estimators run thousands of samples per point: fewer random points there.
    std::vector<Surface> domain = domainSurfaces(d, 4242, d.estimator ? 2048 : 8192);
    domain.resize((domain.size() + 63) / 64 * 64);
    const std::vector<Surface> probe = probeSurfaces(d.probe);
    Difference worst;
    auto take = [&](const Difference& x) {
        if (x.worst > worst.worst) worst = x;
    };
    for (const Scene& s : scenes)
        for (const auto& [name, params] : settings) {
            const std::string at = s.file.stem().string() + "/" + s.environment + ", " + name;
            take(compareRenders(renderer, m, s, params, &probe, d.probe.width, d.probe.height,
                                mutantDir, "probe (" + at + ")"));
            if (!domain.empty())
                take(compareRenders(renderer, m, s, params, &domain, 64, int(domain.size() / 64),
                                    mutantDir, "random inputs (" + at + ")"));
            take(compareRenders(renderer, m, s, params, nullptr, 128, 128, mutantDir,
                                "scene (" + at + ")"));
        }
    const ExtremeSet extreme = extremeSurfaces();
    const Difference onExtremes =
        compareRenders(renderer, m, scene, settings[0].second, &extreme.surfaces, extreme.width,
                       extreme.height, mutantDir, "extreme inputs");
    return {{"equivalent", worst.worst <= 1},
            {"worst", worst.worst},
            {"where", worst.where},
            {"extremes_differ", onExtremes.worst > 1},
            {"extremes_where", onExtremes.where}};
}

// For steps judged by convergence (estimators): a survivor whose values differ from the
// reference solution's is a correct estimator when it meets the contract on tests it was not
// graded with. With a sample count: every count and the truth's samples 4x, at the same
// rules (a consistent estimator's error keeps falling; a biased one's does not). Without one
// (a quadrature, whose contract is an accuracy): the same accuracy on the full probe and 4096
// other random points, on the soft sky and on a featureless environment.
json convergence(LabRenderer& renderer, const LoadedModule& m, const DataPaths& paths,
                 const fs::path& mutantDir) {
    std::vector<ModuleDesc> tests;
    std::string how;
    {
        ModuleDesc strict = *m.desc;
        EstimatorSpec& e = *strict.estimator;
        if (!e.sampleCounts.empty()) {
            for (int& n : e.sampleCounts) n *= 4;
            // The counts above stay above: a count graded twice would compare a value with
            // itself ("4096 and 4096 samples give the same value").
            std::erase_if(e.highCounts, [&](int n) { return n <= e.sampleCounts.back(); });
            e.truthSamples *= 4;
            e.minimumFall = 1;  // the fall is the grade's; here: the error at high counts
            how = "at 4x the samples (" + std::to_string(e.sampleCounts.back()) +
                  ") within the noise band of a " + std::to_string(e.truthSamples) +
                  "-sample truth, no bias";
            tests.push_back(strict);
        } else {
            e.probeStride = 1;
            e.domainPoints = 4096;
            // A quadrature's nodes are the map's texels: as an estimator's error at 4x the
            // samples, its error on a map 4x finer (a Riemann sum whose nodes sit anywhere in
            // their texels converges; one that reads a fixed mip does not follow the size).
            e.otherEnvironmentSize *= 4;
            tests.push_back(strict);
            tests.back().estimator->environment = "smooth";
            tests.push_back(strict);
            how = "the contract's accuracy (" + number(e.systematic.relative * 100) +
                  "% after a normalisation within " + number(e.scaleTolerance * 100) +
                  "%) on the full probe and 4096 other random points, on " + e.environment +
                  " and on a featureless environment, the other map size 4x finer (" +
                  std::to_string(e.otherEnvironmentSize) + ")";
        }
    }
    std::string failed;
    for (const ModuleDesc& strict : tests) {
        const LoadedModule strictModule{&strict, m.library, m.sourceDir};
        GradeSettings settings;
        settings.robustness = false;
        settings.feedback = false;
        settings.seed = 99;
        const StepResult r = gradeStep(renderer, strictModule, paths, {mutantDir, false}, settings);
        for (const CheckReport& c : r.checks)
            if (c.deducted && !c.passed)
                failed += (failed.empty() ? "" : "; ") + c.name + ": " + c.detail;
    }
    return {{"passed", failed.empty()}, {"how", how}, {"failed", failed}};
}

// The step's environment with its radiance times `scale`, as an EXR file the scene can name
// (kept in the cache: the maps derived from it are cached by its texels).
std::string scaledEnvironment(LabRenderer& renderer, const std::string& source, double scale) {
    const fs::path dir = renderer.cacheRoot().empty()
                             ? fs::temp_directory_path() / "pbrlab-mutants-environments"
                             : renderer.cacheRoot() / "mutant-environments";
    const fs::path file = dir / (fs::path(source).stem().string() + "-x" + number(scale) + ".exr");
    if (!fs::exists(file)) {
        Image image = loadEnvironmentImage(source, renderer.cacheRoot());
        for (size_t i = 0; i < image.pixels.size(); ++i)
            if (image.channels < 4 || i % 4 != 3) image.pixels[i] *= float(scale);
        fs::create_directories(dir);
        writeImage(file, image, FileDepth::Float32);
    }
    return fs::absolute(file).string();
}

// The scene with one light more, the others moved and recoloured: NUM_LIGHTS, positions and
// colours all differ from the ones grading binds today.
Scene withOtherLights(Scene scene) {
    for (PointLightDesc& l : scene.lights) {
        l.position += glm::dvec3(0.7, -0.4, 0.5);
        l.color *= glm::dvec3(1.3, 0.6, 0.9);
    }
    PointLightDesc extra;
    extra.position = scene.lights.empty() ? glm::dvec3(2, 3, 4) : -scene.lights[0].position;
    extra.color = glm::dvec3(20, 40, 30);
    scene.lights.push_back(extra);
    return scene;
}

void setIblField(IblSettings& s, const std::string& field, int value) {
    if (field == "environmentSize")
        s.environmentSize = value;
    else if (field == "irradianceSize")
        s.irradianceSize = value;
    else if (field == "prefilterSize")
        s.prefilterSize = value;
    else if (field == "prefilterMips")
        s.prefilterMips = value;
    else if (field == "lutWidth")
        s.lutWidth = value;
    else
        throw Error("mutants: no IBL setting '" + field + "'");
}

// A witness's comparisons of the reference solution with the mutant at the step's default
// parameters: the worst difference so far, and the conditions compared under.
struct WitnessComparison {
    LabRenderer& renderer;
    const LoadedModule& m;
    const fs::path& mutantDir;
    const ParamValues& defaults;
    const std::vector<Surface>& domain;
    const std::vector<Surface>& probe;
    Difference worst;
    std::vector<std::string> where;

    // Keeps `x` when it is the worst difference so far.
    void take(const Difference& x) {
        if (x.worst > worst.worst) worst = x;
    }

    // The probe, the random points and the scene at 64 x 64, in `s` under the maps `ibl`.
    void everywhere(const Scene& s, const IblSettings& ibl, const std::string& at) {
        const ModuleDesc& d = *m.desc;
        where.push_back(at);
        take(compareRenders(renderer, m, s, defaults, &probe, d.probe.width, d.probe.height,
                            mutantDir, "probe (" + at + ")", ibl));
        if (!domain.empty())
            take(compareRenders(renderer, m, s, defaults, &domain, 64, int(domain.size() / 64),
                                mutantDir, "random inputs (" + at + ")", ibl));
        take(compareRenders(renderer, m, s, defaults, nullptr, 64, 64, mutantDir,
                            "scene (" + at + ")", ibl));
    }
};

// Counts: the step's integer parameters at each of `counts`, compared on 64 random points (or
// the scene at 16 x 16) after the control at n and n / 2. Returns why no value can show the
// cap (empty: every count was compared).
std::string compareAtCounts(WitnessComparison& c, const Scene& scene,
                            const std::vector<int>& counts) {
    const ModuleDesc& d = *c.m.desc;
    std::string unseen;
    for (int n : counts) {
        ParamValues at(d.params), half(d.params);
        bool any = false;
        for (const ParamDecl& p : d.params)
            if (p.type == ParamType::Int) {
                at.set(p.name, glm::dvec3(n, 0, 0));
                half.set(p.name, glm::dvec3(n / 2, 0, 0));
                any = true;
            }
        if (!any) {
            unseen = "the step's view cannot show: it has no count parameter";
            continue;
        }
        // 64 random points, or a 16 x 16 picture of the scene for a step without a domain.
        const std::vector<Surface> few(c.domain.begin(),
                                       c.domain.begin() + std::min<size_t>(64, c.domain.size()));
        const bool onScene = few.empty();
        const std::string label =
            (onScene ? "scene" : "random inputs") + std::string(" at count ") + std::to_string(n);
        c.where.push_back("count " + std::to_string(n) +
                          (onScene ? " (the scene at 16 x 16)" : " (64 random points)"));
        auto compareAt = [&](const fs::path& other, const ParamValues* otherParams) {
            return compareRenders(c.renderer, c.m, scene, at, onScene ? nullptr : &few,
                                  onScene ? 16 : 64, onScene ? 16 : 1, other, label, {},
                                  otherParams);
        };
        if (compareAt({}, &half).worst <= 1) {
            unseen = "no comparison of values can show: the solution's own values at counts " +
                     std::to_string(n / 2) + " and " + std::to_string(n) +
                     " agree within float rounding's band there";
            continue;
        }
        c.take(compareAt(c.mutantDir, nullptr));
    }
    return unseen;
}

// A semantic mutant (same values as the reference solution on the graded inputs) compared
// again where its change would show: its witness. Smaller sets than the graded comparison's
// (the probe, 512 other random points, the scene at 64 x 64; 64 points at large counts): a
// change of meaning there shows on every point it touches, not on a rare one.
json witnessEquivalence(LabRenderer& renderer, const LoadedModule& m, const DataPaths& paths,
                        const fs::path& mutantDir, const Witness& w) {
    const ModuleDesc& d = *m.desc;
    Scene scene = loadScene(paths.scene(d.scene));
    if (d.estimator && !d.estimator->environment.empty())
        scene.environment = d.estimator->environment;
    const ParamValues defaults(d.params);
    std::vector<Surface> domain = domainSurfaces(d, 4343, 512);
    domain.resize((domain.size() + 63) / 64 * 64);
    const std::vector<Surface> probe = probeSurfaces(d.probe);
    WitnessComparison c{renderer, m, mutantDir, defaults, domain, probe, {}, {}};
    for (double scale : w.environmentScales) {
        Scene s = scene;
        s.environment = scaledEnvironment(renderer, scene.environment, scale);
        c.everywhere(s, {}, "the environment x" + number(scale));
    }
    for (const auto& [field, value] : w.ibl) {
        IblSettings ibl;
        setIblField(ibl, field, value);
        c.everywhere(scene, ibl, field + " " + std::to_string(value));
    }
    if (w.otherLights) c.everywhere(withOtherLights(scene), {}, "another light count and lights");
    // Counts: the step's integer parameters at n (beyond what the view declares: the contract's
    // count is any uint). The control: the solution's own values at n and n / 2; the same
    // values there (a view that clamps the count, an estimator converged below the band of
    // rounding) mean no value can show the cap, which then differs by construction only.
    const std::string unseen = compareAtCounts(c, scene, w.counts);
    std::string conditions;
    for (const std::string& x : c.where) conditions += (conditions.empty() ? "" : ", ") + x;
    return {{"equivalent", c.worst.worst <= 1 && unseen.empty()},
            {"worst", c.worst.worst},
            {"where", c.worst.where},
            {"conditions", conditions},
            {"unseen", unseen}};
}

}  // namespace

int ModuleMutation::count(MutantStatus status) const {
    int n = 0;
    for (const MutantOutcome& m : mutants) n += m.status == status;
    return n;
}

int ModuleMutation::nonEquivalentSurvivors() const {
    int n = 0;
    for (const MutantOutcome& m : mutants)
        n += m.status == MutantStatus::Survived && m.equivalence != "equivalent";
    return n;
}

namespace {

// The step's semantic mutants, made in a child process (the host values they need come from a
// renderer, and GL lives and dies there).
std::vector<Mutant> semanticMutantsOf(const LoadedModule& m, const DataPaths& paths,
                                      const std::string& solution) {
    const std::string text = inChild([&] {
        auto context = createHeadlessContext();
        LabRenderer renderer(paths);
        return mutantsToJson(generateSemanticMutants({renderer, m, paths, solution})).dump();
    });
    const json j = json::parse(text);
    if (j.is_object() && j.contains("error"))
        throw Error("mutants: semantic mutants of " + m.desc->id + ": " +
                    j["error"].get<std::string>());
    return mutantsFromJson(j);
}

// The verdict on a survivor from the comparison's answer (see equivalence, convergence and
// witnessEquivalence).
void judgeSurvivor(MutantOutcome& r, const ModuleDesc& d, const json& j) {
    if (j.contains("error")) {
        r.equivalence = "unknown";
        r.evidence = j["error"];
    } else if (j["equivalent"] && !j.contains("witness")) {
        r.equivalence = "equivalent";
        r.evidence = "same values within float rounding on the probe, " +
                     std::to_string(d.estimator ? 2048 : 8192) +
                     " random points of the domain and every graded scene and setting "
                     "(worst " +
                     std::to_string(double(j["worst"])) + " x rounding)";
        if (j["extremes_differ"])
            r.evidence +=
                "; differs only on extreme inputs (robustness, not graded "
                "for correctness): " +
                std::string(j["extremes_where"]);
    } else if (j["equivalent"]) {  // a semantic mutant, also compared on its witness
        const json& w = j["witness"];
        if (w["equivalent"]) {
            r.equivalence = "equivalent";
            r.evidence =
                "same values within float rounding on every graded input, and where "
                "its change would show: " +
                std::string(w["conditions"]) + " (worst " + std::to_string(double(w["worst"])) +
                " x rounding)";
        } else {
            r.equivalence = "differs";
            r.evidence =
                !std::string(w["unseen"]).empty()
                    ? "the same values as the solution on every graded input; by construction "
                      "it differs above its cap, which " +
                          std::string(w["unseen"])
                    : "the same values as the solution on every graded input, not where its "
                      "change shows: " +
                          std::string(w["where"]) + " (" + std::to_string(double(w["worst"])) +
                          " x rounding)";
        }
    } else if (j.contains("convergence") && j["convergence"]["passed"]) {
        r.equivalence = "equivalent";
        r.evidence =
            "a correct estimator of the same integral: " + std::string(j["convergence"]["how"]) +
            " (its values differ from the reference solution's: " + std::string(j["where"]) + ")";
    } else {
        r.equivalence = "differs";
        r.evidence =
            std::string(j["where"]) + " (" + std::to_string(double(j["worst"])) + " x rounding)";
        if (j.contains("convergence"))
            r.evidence += "; stricter grade: " + std::string(j["convergence"]["failed"]);
    }
}

// Writes the mutants to be graded (every o.every-th of `all`) to folders under `root`, each
// with an outcome in `result`; returns their grading jobs, in the same order.
std::vector<GradeJob> writeMutantJobs(const LoadedModule& m, const std::string& kind,
                                      const std::vector<Mutant>& all, const MutationOptions& o,
                                      const fs::path& root, ModuleMutation& result) {
    const ModuleDesc& d = *m.desc;
    std::vector<GradeJob> jobs;
    for (size_t i = 0; i < all.size(); ++i) {
        if (o.every > 1 && i % size_t(o.every) != 0) continue;
        const fs::path dir = root / d.id / kind / std::to_string(i);
        fs::create_directories(dir);
        std::ofstream(dir / (d.id + ".glsl"), std::ios::binary) << all[i].text;
        jobs.push_back({&m, fs::canonical(dir)});
        MutantOutcome outcome;
        outcome.mutant = all[i];
        result.mutants.push_back(outcome);
    }
    return jobs;
}

// How the mutants are graded: quickly, and on what decides a verdict only.
GradeOptions mutantGradeOptions(const MutationOptions& o) {
    GradeOptions g;
    g.jobs = o.jobs;
    g.timeoutSeconds = 120;
    g.settings.robustness = false;  // reported, never deducted: it decides no verdict
    g.settings.feedback = o.feedback;
    g.settings.stopAtFirstFailure = !o.feedback;
    return g;
}

// The mutant's status from its grade, and the check (or message) that killed it.
void recordGrade(MutantOutcome& r, const ModuleGrade& grade) {
    switch (grade.status) {
        case GradeStatus::Passed:
            r.status = MutantStatus::Survived;
            break;
        case GradeStatus::CompileError:
            r.status = MutantStatus::Stillborn;
            break;
        case GradeStatus::Failed:
            r.status = MutantStatus::Killed;
            break;
        case GradeStatus::Timeout:
            r.status = MutantStatus::Timeout;
            break;
        case GradeStatus::Missing:  // its file is written before the grade: never missing
        case GradeStatus::Crashed:
            r.status = MutantStatus::Crashed;
            break;
    }
    r.mistake = grade.mistake;
    r.namedBy = grade.namedBy;
    for (const auto& c : grade.checks)
        if (!c.value("passed", true) && c.value("deducted", true)) {
            r.killedBy = c.value("name", "");
            break;
        }
    if (r.status == MutantStatus::Killed && r.killedBy.empty())
        r.killedBy = grade.message.substr(0, 200);
}

// A survivor (its folder `dir`): not equivalent when its family or its witness says so, else
// compared with the reference solution in a child process, where GL lives and dies.
void judgeSurvivorIn(MutantOutcome& r, const fs::path& dir, const LoadedModule& m,
                     const DataPaths& paths, bool semantic) {
    const ModuleDesc& d = *m.desc;
    const Witness& witness = r.mutant.witness;
    const SemanticFamily* family = semantic ? semanticFamily(r.mutant.family) : nullptr;
    if (family && family->neverEquivalent) {
        r.equivalence = "differs";
        r.evidence = family->neverEquivalent;
        return;
    }
    if (!witness.byConstruction.empty()) {  // no view shows where it differs
        r.equivalence = "differs";
        r.evidence =
            "by construction: " + witness.byConstruction + " (no step's view reaches such inputs)";
        return;
    }
    const std::string text = inChild([&] {
        auto context = createHeadlessContext();
        LabRenderer renderer(paths);
        json j = equivalence(renderer, m, paths, dir);
        if (j["equivalent"] && !witness.empty())
            j["witness"] = witnessEquivalence(renderer, m, paths, dir, witness);
        // A change of meaning is never another correct estimator: no convergence
        // proof for semantic mutants.
        if (!j["equivalent"] && d.estimator && !semantic)
            j["convergence"] = convergence(renderer, m, paths, dir);
        return j.dump();
    });
    try {
        judgeSurvivor(r, d, json::parse(text));
    } catch (const std::exception& e) {
        r.equivalence = "unknown";
        r.evidence = std::string("no answer from the comparison: ") + e.what();
    }
}

// The progress line that sums up one step's mutants of one kind.
std::string mutationSummary(const ModuleMutation& result) {
    return result.id + " (" + result.kind +
           "): " + std::to_string(result.count(MutantStatus::Killed)) + " killed, " +
           std::to_string(result.count(MutantStatus::Survived)) + " survived (" +
           std::to_string(result.nonEquivalentSurvivors()) + " not equivalent), " +
           std::to_string(result.count(MutantStatus::Stillborn)) + " do not compile, " +
           std::to_string(int(result.seconds)) + " s";
}

// One step's mutants of one kind: made, written under `root`, graded, survivors judged, and
// their folders removed.
ModuleMutation mutateStep(const LoadedModule& m, const std::string& kind,
                          const std::string& solution, const DataPaths& paths,
                          const MutationOptions& o, const fs::path& root) {
    const ModuleDesc& d = *m.desc;
    const bool semantic = kind == "semantic";
    const auto start = std::chrono::steady_clock::now();
    ModuleMutation result;
    result.id = d.id;
    result.kind = kind;
    const std::vector<Mutant> all =
        semantic ? semanticMutantsOf(m, paths, solution) : generateMutants(solution);
    const std::vector<GradeJob> jobs = writeMutantJobs(m, kind, all, o, root, result);
    if (o.progress)
        o.progress(d.id + ": " + std::to_string(jobs.size()) + " of " + std::to_string(all.size()) +
                   " " + kind + " mutants");
    const std::vector<ModuleGrade> grades =
        jobs.empty() ? std::vector<ModuleGrade>{} : gradeJobs(jobs, paths, mutantGradeOptions(o));
    for (size_t i = 0; i < grades.size(); ++i) recordGrade(result.mutants[i], grades[i]);
    // Survivors: the measured proof of equivalence, or the evidence of a hole.
    for (size_t i = 0; i < result.mutants.size(); ++i)
        if (result.mutants[i].status == MutantStatus::Survived)
            judgeSurvivorIn(result.mutants[i], jobs[i].submission, m, paths, semantic);
    std::error_code ec;
    fs::remove_all(root / d.id / kind, ec);
    result.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (o.progress) o.progress(mutationSummary(result));
    return result;
}

}  // namespace

std::vector<ModuleMutation> runMutants(const ModuleRegistry& modules, const DataPaths& paths,
                                       const MutationOptions& o) {
    std::vector<ModuleMutation> out;
    const fs::path root =
        fs::temp_directory_path() / ("pbrlab-mutants-" + std::to_string(getpid()));
    std::vector<std::string> kinds;
    if (o.mechanical) kinds.push_back("mechanical");
    if (o.semantic) kinds.push_back("semantic");
    for (const LoadedModule& m : modules.modules()) {
        const ModuleDesc& d = *m.desc;
        if (!o.modules.empty() &&
            std::find(o.modules.begin(), o.modules.end(), d.id) == o.modules.end())
            continue;
        const std::string solution = readFile(m.sourceDir / "solution.glsl");
        for (const std::string& kind : kinds)
            out.push_back(mutateStep(m, kind, solution, paths, o, root));
    }
    std::error_code ec;
    fs::remove_all(root, ec);
    return out;
}

json toJson(const std::vector<ModuleMutation>& result) {
    json modules = json::array();
    for (const ModuleMutation& m : result) {
        json list = json::array();
        for (const MutantOutcome& r : m.mutants)
            list.push_back({{"family", r.mutant.family},
                            {"change", r.mutant.change},
                            {"line", r.mutant.line},
                            {"description", r.mutant.description},
                            {"status", r.status},
                            {"killed_by", r.killedBy},
                            {"mistake", r.mistake},
                            {"named_by", r.namedBy},
                            {"equivalence", r.equivalence},
                            {"evidence", r.evidence}});
        modules.push_back({{"id", m.id},
                           {"kind", m.kind},
                           {"made", m.mutants.size()},
                           {"killed", m.count(MutantStatus::Killed)},
                           {"survived", m.count(MutantStatus::Survived)},
                           {"not_equivalent", m.nonEquivalentSurvivors()},
                           {"stillborn", m.count(MutantStatus::Stillborn)},
                           {"seconds", m.seconds},
                           {"mutants", list}});
    }
    return {{"modules", modules}};
}

}  // namespace pbrlab
