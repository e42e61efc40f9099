// Values checks of gradeStep (step_grader.h): the step against its reference's band on the
// probe, its scenes, random inputs, every exercised parameter value, coloured lights and the
// host's values (the lights' count, the maps' sizes) over what the host can produce.

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <sstream>

#include "assets/scene.h"
#include "grading/step_grader.h"
#include "render/converge.h"
#include "steps/solution_stub.h"
#include "util/error.h"

namespace pbrlab::step_grading {

namespace {

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

// The light counts graded above the scenes' own (the module's scene has 1, the coloured lights
// 3, the lesson's grid 4): a few points of 1..kMaxSceneLights, the most lights a scene may
// have, included. A loop capped below the host's limit fails at the largest; 12 and 33 bracket
// the caps a student may pick (8, 10, 16, 32) so that the counts either side of a failure are
// known, and 7 is the count no other check uses.
const int kGradedLightCounts[] = {7, 12, 33, int(kMaxSceneLights)};

// The first `count` of kMaxSceneLights lights around the scene's centre, each unlike the
// others: directions from a low-discrepancy set (every prefix spread over the sphere, leaning
// towards the camera), distances 2 to 12 times the unit, colours with every channel lit in
// each light's own mix, intensities scaled by the squared distance so that each light adds a
// comparable share at a point it faces (of the order of 1/count of the sum, far outside the
// band: ignoring any one light shows).
Scene withLights(Scene scene, int count) {
    const glm::dvec3 c = scene.camera.target;
    const double r = std::max(1.0, 0.3 * glm::length(scene.camera.position - c));
    const glm::dvec3 toCamera = glm::normalize(scene.camera.position - c);
    auto fraction = [](double x) { return x - std::floor(x); };
    scene.lights.clear();
    for (int k = 0; k < count; ++k) {
        // The R2 sequence (Roberts 2018): any run of it covers the square evenly.
        const double u = fraction(0.5 + 0.7548776662466927 * k),
                     v = fraction(0.5 + 0.5698402909980532 * k);
        const double z = 1 - 2 * u, phi = 2 * 3.141592653589793 * v, s = std::sqrt(1 - z * z);
        const glm::dvec3 d =
            glm::normalize(0.5 * toCamera + glm::dvec3(s * std::cos(phi), z, s * std::sin(phi)));
        const double distance = r * (2 + 10 * fraction(0.6180339887498949 * (k + 1)));
        const glm::dvec3 colour(0.25 + 0.75 * fraction(0.1 + 0.3819660112501051 * (k + 1)),
                                0.25 + 0.75 * fraction(0.4 + 0.4142135623730950 * (k + 1)),
                                0.25 + 0.75 * fraction(0.7 + 0.7320508075688772 * (k + 1)));
        const double intensity = 4 * (0.5 + fraction(0.2360679774997897 * (k + 1)));
        scene.lights.push_back({c + distance * d, colour * intensity * distance * distance});
    }
    return scene;
}

// The same lights with only those of `on` (0-based, others black: the colour 0, read as the
// others are).
Scene onlyLit(Scene scene, const std::vector<int>& on) {
    for (size_t k = 0; k < scene.lights.size(); ++k)
        if (std::find(on.begin(), on.end(), int(k)) == on.end()) scene.lights[k].color = {0, 0, 0};
    return scene;
}

// The lights an ignored set names, 1-based: "light 9 and up", "every other light from 18 (18,
// 20, ..., 32 of 33)", "lights 3, 7".
std::string ignoredLights(const std::vector<int>& ignored, int count, bool upToTheLimit) {
    const int first = ignored.front(), last = ignored.back(), n = int(ignored.size());
    if (last - first + 1 == n && last == count)
        return upToTheLimit ? "light " + std::to_string(first) + " and up"
                            : "lights " + std::to_string(first) + " to " + std::to_string(last);
    const int step = n > 2 ? ignored[1] - first : 0;
    bool progression = step > 1 && last + step > count;
    for (int i = 1; progression && i < n; ++i) progression = ignored[i] - ignored[i - 1] == step;
    if (progression)
        return (step == 2   ? std::string("every other light")
                : step == 3 ? std::string("every third light")
                            : "one light in " + std::to_string(step)) +
               " from " + std::to_string(first) + " (" + std::to_string(first) + ", " +
               std::to_string(ignored[1]) + ", ..., " + std::to_string(last) + " of " +
               std::to_string(count) + ")";
    if (n == 1) return "light " + std::to_string(first);
    std::string list;
    for (int i = 0; i < n && i < 8; ++i) list += (i ? ", " : "") + std::to_string(ignored[i]);
    return "lights " + list +
           (n > 8 ? ", ... (" + std::to_string(n) + " of " + std::to_string(count) + ")" : "");
}

// The values of two renders the same at every covered point (4 units in the last place: a
// black light adds exactly 0).
bool sameValues(const Image& a, const Image& b, const std::vector<Surface>& surfaces,
                int components) {
    for (size_t i = 0; i < surfaces.size(); ++i) {
        if (!surfaces[i].covered) continue;
        for (int c = 0; c < components; ++c) {
            const double x = a.pixels[i * 4 + size_t(c)], y = b.pixels[i * 4 + size_t(c)];
            if (std::isnan(x) && std::isnan(y)) continue;
            if (!(std::abs(x - y) <= 4.8e-7 * std::max(std::abs(x), std::abs(y)))) return false;
        }
    }
    return true;
}

std::string sizeOf(int width, int height, int mips = 1) {
    return std::to_string(width) + "x" + std::to_string(height) +
           (mips > 1 ? " (" + std::to_string(mips) + " mips)" : "");
}

// The precomputed maps at the ends of what the host makes (docs/ibl.md): the smallest and the
// largest maps of `--error-budget`'s ladder (iblLadder: what the GUI and `precompute
// --error-budget` choose), with `--prefilter-mips` at its ends (one mip, uPrefilterMaxLod = 0;
// the full chain of the ladder's largest prefilter, 256 down to 1: uPrefilterMaxLod = 8), the
// LUT of `precompute --learnopengl` (512 x 512) and one smaller than both presets
// (`--lut-size`, `--lut-height`), and, for a program that reads uEnvironment, LearnOpenGL's
// 512^2 environment (the only other size the host builds). Every value at its two ends in two
// settings: each new setting rebuilds the environment cube (~150 ms), so the values are varied
// together, and one at a time only when a setting fails (hostMapValues), to name the value.
std::pair<IblSettings, IblSettings> hostMapEnds(bool readsEnvironment) {
    const std::vector<IblSettings> ladder = iblLadder();
    const IblSettings learnOpenGl = IblSettings::learnOpenGl();
    auto rung = [](const IblSettings& r) {
        IblSettings s = kGradingIbl;
        s.bins = r.bins;
        s.prefilterSize = r.prefilterSize;
        s.irradianceSize = r.irradianceSize;
        return s;
    };
    IblSettings smallest = rung(ladder.front());
    smallest.prefilterMips = 1;
    smallest.lutWidth = 256;
    smallest.lutHeight = 16;
    IblSettings largest = rung(ladder.back());
    largest.prefilterMips = int(std::log2(largest.prefilterSize)) + 1;
    largest.lutWidth = learnOpenGl.lutWidth;
    largest.lutHeight = learnOpenGl.lutHeight;
    if (readsEnvironment)
        largest.environmentSize =
            std::max(learnOpenGl.environmentSize, kGradingIbl.environmentSize);
    return {smallest, largest};
}

// One host value of `s` at a time, the others at the defaults: what a failed setting is
// taken apart into. The prefilter's size alone keeps the default's mip count (its
// uPrefilterMaxLod); its mip count goes with the size that holds it.
struct HostMapValue {
    std::string value;         // as the student reads it
    std::string right, wrong;  // its value in the defaults, in `settings`
    IblSettings settings;
};
std::vector<HostMapValue> hostMapValues(const IblSettings& s) {
    std::vector<HostMapValue> out;
    const IblSettings& d = kGradingIbl;
    auto side = [](int n) { return std::to_string(n) + "^2"; };
    IblSettings v = d;
    if (s.lutWidth != d.lutWidth || s.lutHeight != d.lutHeight) {
        v = d, v.lutWidth = s.lutWidth, v.lutHeight = s.lutHeight;
        out.push_back({"uBrdfLut's size", sizeOf(d.lutWidth, d.lutHeight),
                       sizeOf(s.lutWidth, s.lutHeight), v});
    }
    if (s.irradianceSize != d.irradianceSize) {
        v = d, v.irradianceSize = s.irradianceSize, v.bins = s.bins;
        out.push_back({"uIrradianceMap's size", side(d.irradianceSize), side(s.irradianceSize), v});
    }
    if (s.prefilterSize != d.prefilterSize) {
        v = d, v.prefilterSize = s.prefilterSize, v.bins = s.bins;
        v.prefilterMips = std::min(d.prefilterMips, int(std::log2(s.prefilterSize)) + 1);
        out.push_back({"uPrefilterMap's size", side(d.prefilterSize), side(s.prefilterSize), v});
    }
    if (s.prefilterMips != d.prefilterMips) {
        v = d, v.prefilterSize = s.prefilterSize, v.prefilterMips = s.prefilterMips;
        out.push_back({"uPrefilterMaxLod", std::to_string(d.prefilterMips - 1),
                       std::to_string(s.prefilterMips - 1), v});
    }
    if (s.environmentSize != d.environmentSize) {
        v = d, v.environmentSize = s.environmentSize;
        out.push_back({"uEnvironment's size", side(d.environmentSize), side(s.environmentSize), v});
    }
    return out;
}

// The host values of the maps, as the student reads them.
std::string mapValues(const IblSettings& s) {
    return "uBrdfLut " + std::to_string(s.lutWidth) + "x" + std::to_string(s.lutHeight) +
           ", uIrradianceMap " + std::to_string(s.irradianceSize) + "^2, uPrefilterMap " +
           std::to_string(s.prefilterSize) +
           "^2 (uPrefilterMaxLod = " + std::to_string(s.prefilterMips - 1) + "), uEnvironment " +
           std::to_string(s.environmentSize) + "^2";
}

// A value the function assumes is wrong wherever the value matters: most points (a
// hard-coded uPrefilterMaxLod or map size is wrong at every roughness above 0, a fixed
// light count at every point the missing lights face). A few points outside say that the
// function is wrong there for another reason (a highlight limited relative to the
// irradiance crossed its limit at 4 of 2048 points with the largest maps), so the name
// needs a tenth of the points.
bool widespread(int outside, int compared) {
    return 10 * outside >= compared;
}

// A failed run's message led by the host value it names as hard-coded, where the failure is
// widespread and the value was right (`right`) in every check before.
void nameHardCoded(ValuesRun& run, const std::string& value, const std::string& right,
                   const std::string& now) {
    if (run.report.passed || right.empty() || !widespread(run.report.outside, run.report.points))
        return;
    run.report.detail = "hard-coded host value (" + value + "): right with " + right +
                        ", wrong with " + now + "; " + run.report.detail;
}

}  // namespace

void StepGrader::noteHostValues(const Scene& scene, const ParamValues& params,
                                const IblSettings& ibl) {
    auto& v = result_.hostValues;
    v["NUM_LIGHTS"].insert(std::to_string(std::max<size_t>(scene.lights.size(), 1)));
    std::string positions, colours;
    for (const auto& l : scene.lights) {
        positions +=
            number(l.position.x) + "," + number(l.position.y) + "," + number(l.position.z) + ";";
        colours += number(l.color.x) + "," + number(l.color.y) + "," + number(l.color.z) + ";";
    }
    v["uLightPositions"].insert(positions);
    v["uLightColors"].insert(colours);
    v["uCameraPosition"].insert(number(scene.camera.position.x) + "," +
                                number(scene.camera.position.y) + "," +
                                number(scene.camera.position.z));
    v["uEnvironment"].insert(scene.environment + " " +
                             sizeOf(ibl.environmentSize, ibl.environmentSize));
    v["uIrradianceMap"].insert(scene.environment + " " +
                               sizeOf(ibl.irradianceSize, ibl.irradianceSize));
    v["uPrefilterMap"].insert(scene.environment + " " +
                              sizeOf(ibl.prefilterSize, ibl.prefilterSize, ibl.prefilterMips));
    v["uPrefilterMaxLod"].insert(std::to_string(ibl.prefilterMips - 1));
    v["uBrdfLut"].insert(sizeOf(ibl.lutWidth, ibl.lutHeight));
    for (const ParamDecl& p : d_.params) v[p.uniformName()].insert(p.format(params.vector(p.name)));
}

ValuesRun StepGrader::runValues(const std::string& name, CheckCategory category, const Scene& scene,
                                const ParamValues& params, const std::vector<Surface>* surfaces,
                                int width, int height, const Probe* probe, const IblSettings& ibl) {
    stage(name);
    noteHostValues(applyParamBindings(scene, d_, params), params, ibl);
    EvalRequest request;
    request.render = {&m_, &params, &scene, source_, surfaces, width, height};
    request.render.ibl = ibl;
    request.render.seamlessCubes = false;
    request.render.isolatePoints = surfaces != nullptr;
    request.render.cacheGBuffer = true;
    request.bandCache = settings_.bands;
    Evaluation e = evaluate(renderer_, request);
    ValuesRun run;
    run.report = reportFor(name, d_, e.comparison, e.render.surfaces, d_.tolerance.outlierFraction,
                           probe, width);
    run.report.category = category;
    run.surfaces = std::move(e.render.surfaces);
    run.value = std::move(e.render.value);
    run.band = std::move(e.band);
    run.scene = scene;
    run.params = params;
    run.fromScene = surfaces == nullptr;
    run.width = width;
    run.height = height;
    run.worstIndex = e.comparison.worstIndex;
    run.outlierFraction = d_.tolerance.outlierFraction;
    return run;
}

// The stub is the kit's (steps/solution_stub.h: the solution's body replaced by `return 0`), the
// file a student starts from. When it cannot be made (no solution.glsl with its markers) or
// does not render, a passed values check is taken as work. An estimator's stub is not
// rescaled (StepGrader::rescale): its values are 0, which no scale changes. Mutation testing
// (stopAtFirstFailure) asks for the verdict only, which this does not change.
void StepGrader::noteWork(ValuesRun& run) {
    CheckReport& report = run.report;
    if (workShown_ || settings_.stopAtFirstFailure || !report.passed || !report.deducted ||
        report.kind != CheckKind::Values)
        return;
    try {
        if (stubDir_.empty()) {
            const std::filesystem::path solution = m_.sourceDir / "solution.glsl";
            std::ifstream in(solution, std::ios::binary);
            std::stringstream text;
            text << in.rdbuf();
            if (!in) throw Error(solution.string() + ": cannot read it");
            const std::string stub = stubSolution(text.str(), d_.function, solution.string());
            // In the cache, written only when its text changes: the stub's program is then
            // compiled once, not once per grade (a rewritten file is a changed program).
            const std::filesystem::path dir = renderer_.cacheRoot() / "stubs" / d_.id;
            const std::filesystem::path file = dir / (d_.id + ".glsl");
            std::ifstream old(file, std::ios::binary);
            std::stringstream oldText;
            oldText << old.rdbuf();
            if (!old || oldText.str() != stub) {
                std::filesystem::create_directories(dir);
                const std::filesystem::path tmp =
                    dir / (d_.id + ".glsl.tmp" + std::to_string(::getpid()));
                std::ofstream(tmp, std::ios::binary) << stub;
                std::filesystem::rename(tmp, file);  // a reader never sees half a stub
            }
            stubDir_ = dir;
        }
        stage(report.name + ": the stub");
        RenderRequest request{&m_,
                              &run.params,
                              &run.scene,
                              {stubDir_, false},
                              run.fromScene ? nullptr : &run.surfaces,
                              run.width,
                              run.height};
        request.seamlessCubes = false;
        request.isolatePoints = !run.fromScene;
        request.cacheGBuffer = true;
        const Image stub = renderer_.render(request).value;
        const Comparison c = compareWithBand(stub, run.surfaces, run.band, d_.components,
                                             d_.nonNegative, run.outlierFraction);
        report.showsWork = !c.passes(d_.nonNegative, run.outlierFraction);
    } catch (const std::exception&) {
        report.showsWork = true;
    }
    workShown_ = report.showsWork;
}

void StepGrader::keep(ValuesRun&& run) {
    noteWork(run);
    const CheckReport report = run.report;
    // The worst failure of the first tier that has one (ValuesRun::tier).
    const bool better = !failed_ || (failed_->tier != run.tier
                                         ? run.tier < failed_->tier
                                         : run.report.worstExcess > failed_->report.worstExcess);
    if (!run.report.passed && run.report.deducted && better)
        failed_ = std::make_unique<ValuesRun>(std::move(run));
    record(report);
}

// The category follows the inputs: the probe, random points of the domain, or a scene
// (`sceneCategory`: the lesson's sphere grid is weighted on its own).
void StepGrader::gradeCase(const std::string& name, GradeCase::Inputs inputs, const Scene& scene,
                           const ParamValues& params, CheckCategory sceneCategory) {
    switch (inputs) {
        case GradeCase::Inputs::Probe: {
            const Probe& p = d_.probe;
            const std::vector<Surface> s = probeSurfaces(p);
            keep(runValues(name, CheckCategory::Probe, scene, params, &s, p.width, p.height, &p));
            return;
        }
        case GradeCase::Inputs::Domain: {
            if (!d_.domain) return;
            const Grid g = grid(domainSurfaces(d_, settings_.seed, settings_.domainPoints));
            keep(runValues(name, CheckCategory::Random, scene, params, &g.surfaces, g.width,
                           g.height, nullptr));
            return;
        }
        case GradeCase::Inputs::Scene:
            keep(runValues(name, sceneCategory, scene, params, nullptr, settings_.size,
                           settings_.size, nullptr));
            return;
    }
}

Scene StepGrader::detailedScene(const Scene& scene) {
    if (!(d_.needs & NeedsEnvironment)) return scene;
    const auto& level = renderer_.environmentInputs(scene, kGradingIbl, false).environment.mips();
    if (level.empty()) return scene;
    const float first = level[0][0].at(0, 0, 0);
    for (const Image& face : level[0])
        for (int y = 0; y < face.height; ++y)
            for (int x = 0; x < face.width; ++x)
                for (int c = 0; c < 3; ++c)
                    if (face.at(x, y, c) != first) return scene;
    Scene detailed = scene;
    detailed.environment = EstimatorSpec{}.environment;
    return detailed;
}

void StepGrader::gradeValues(const Scene& scene) {
    const ParamValues defaults(d_.params);
    const Scene detailed = detailedScene(scene);
    gradeCase("probe", GradeCase::Inputs::Probe, scene, defaults);
    gradeCase("scene " + scene.file.stem().string(), GradeCase::Inputs::Scene, scene, defaults);
    gradeCase(detailed.environment == scene.environment
                  ? "random inputs"
                  : "random inputs (" + detailed.environment + ")",
              GradeCase::Inputs::Domain, detailed, defaults);
    for (const GradeCase& c : d_.cases) {
        const Scene s = c.scene.empty() ? scene : loadScene(paths_.scene(c.scene));
        gradeCase(
            c.name, c.inputs, s, withSets(d_, c.set),
            c.scene == lessonGridCase().scene ? CheckCategory::SphereGrid : CheckCategory::Scenes);
    }
    for (const ParamDecl& p : d_.params)
        for (const std::string& assignment : exercisedValues(p)) {
            const ParamValues params = withSets(d_, {assignment});
            if (p.type == ParamType::Int && params.number(p.name) > kFewPointsAbove) {
                if (!d_.domain) continue;
                const Grid few = grid(domainSurfaces(d_, settings_.seed, kFewPoints));
                keep(runValues("random inputs with " + assignment + " (" +
                                   std::to_string(kFewPoints) + " points)",
                               CheckCategory::Random, scene, params, &few.surfaces, few.width,
                               few.height, nullptr));
                continue;
            }
            if (p.binding == ParamBinding::LightDirection) {
                gradeCase("scene with " + assignment, GradeCase::Inputs::Scene, scene, params);
                continue;
            }
            gradeCase("probe with " + assignment, GradeCase::Inputs::Probe, scene, params);
            gradeCase("scene with " + assignment, GradeCase::Inputs::Scene, scene, params);
            gradeCase("random inputs with " + assignment, GradeCase::Inputs::Domain, detailed,
                      params);
        }
    // The reference's view or the student's (a student's sum may read the lights itself).
    if (readsSceneLights(renderer_, m_, {}, 3) || readsSceneLights(renderer_, m_, source_, 3)) {
        const Scene lit = colouredLights(scene);
        gradeCase("scene with three coloured lights", GradeCase::Inputs::Scene, lit, defaults);
        gradeCase("random inputs with three coloured lights", GradeCase::Inputs::Domain, lit,
                  defaults);
    }
    gradeHostValues(detailed);
}

bool StepGrader::codeQueriesTextureSize() const {
    const std::filesystem::path student = source_.dir / (d_.id + ".glsl");
    std::error_code ec;
    const std::filesystem::path file = !source_.dir.empty() && std::filesystem::exists(student, ec)
                                           ? student
                                           : m_.sourceDir / "solution.glsl";
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    if (!in) return true;
    const std::string code = text.str();
    for (const char* query : {"textureSize", "textureQueryLevels", "textureQueryLod"})
        if (code.find(query) != std::string::npos) return true;
    return false;
}

// What a step that fails with `count` lights does with them, from its own renders on the points
// of `g` (kFewPoints random inputs), asked only on failure: the first light it gets wrong (the
// fewest of the first lights lit, the others black, for which it fails: by bisection), the
// lights it ignores from there on (its values with only those lit are its values with none
// lit: a black light adds exactly 0), up to the host's limit when the count is below it, and
// whether NUM_LIGHTS one below that light is right and at it wrong. "" when the failure does
// not show on those points.
std::string StepGrader::lightsDiagnosis(const Scene& scene, int count, const Grid& g) {
    const ParamValues defaults(d_.params);
    auto run = [&](const Scene& s) { return evaluatePoints(s, defaults, g); };
    auto passes = [&](const Scene& s) {
        return run(s).comparison.passes(d_.nonNegative, d_.tolerance.outlierFraction);
    };
    auto firstOf = [](int k) {
        std::vector<int> on(size_t(std::max(k, 0)));
        std::iota(on.begin(), on.end(), 0);
        return on;
    };
    const Scene all = withLights(scene, count);
    if (passes(all)) return "";
    const Image none = run(onlyLit(all, {})).render.value;
    // Whether the lights `on` of `lights` (0-based) add nothing.
    auto ignores = [&](const Scene& lights, const std::vector<int>& on) {
        const Image unlit = &lights == &all ? none : run(onlyLit(lights, {})).render.value;
        return sameValues(run(onlyLit(lights, on)).render.value, unlit, g.surfaces, d_.components);
    };
    int lo = 0, hi = count;  // the first lo lit pass (none lit: the ambient alone), hi fail
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        (passes(onlyLit(all, firstOf(mid))) ? lo : hi) = mid;
    }
    const int first = hi;  // 1-based, as the student counts them
    std::vector<int> tail;
    for (int k = first - 1; k < count; ++k) tail.push_back(k);
    std::vector<int> ignored;  // 1-based
    bool upToTheLimit = false;
    if (ignores(all, tail)) {
        for (int k : tail) ignored.push_back(k + 1);
        std::vector<int> rest;
        for (int k = first - 1; k < int(kMaxSceneLights); ++k) rest.push_back(k);
        upToTheLimit =
            count == int(kMaxSceneLights) || ignores(withLights(scene, kMaxSceneLights), rest);
    } else {
        for (int k : tail)
            if (ignores(all, {k})) ignored.push_back(k + 1);
    }
    std::string what =
        ignored.empty() ? "gets light " + std::to_string(first) + " wrong: right with the first " +
                              std::to_string(first - 1) + " of " + std::to_string(count) +
                              " lights lit, wrong once light " + std::to_string(first) + " is too"
                        : "ignores " + ignoredLights(ignored, count, upToTheLimit);
    if (first > 1 && passes(withLights(scene, first - 1)) && !passes(withLights(scene, first)))
        what += ": right with NUM_LIGHTS up to " + std::to_string(first - 1) + ", wrong from " +
                std::to_string(first);
    if (upToTheLimit)
        what += " (the host gives up to " + std::to_string(kMaxSceneLights) +
                " lights: is the loop's count fixed or capped instead of NUM_LIGHTS?)";
    return what;
}

// The step evaluated against the reference's band at the points of `g`, each drawn alone.
Evaluation StepGrader::evaluatePoints(const Scene& scene, const ParamValues& params, const Grid& g,
                                      const IblSettings& ibl) {
    EvalRequest request;
    request.render = {&m_, &params, &scene, source_, &g.surfaces, g.width, g.height};
    request.render.ibl = ibl;
    request.render.seamlessCubes = false;
    request.render.isolatePoints = true;
    request.bandCache = settings_.bands;
    return evaluate(renderer_, request);
}

// Each value the host provides, at values no other check gives it and over the range the host
// can produce, on random inputs of the domain. When only such a check fails, the step is right
// with the host's defaults and wrong with other values it meets in real use: a hard-coded host
// value, named so (the lights: which ones it ignores). The IBL ones are not handed to the
// feedback (whose references read the default maps).
// The light counts are cheap (64 points each beyond 7 lights); split_sum's map settings each
// rebuild the environment cube, whose maps are then read from the disk cache. The diagnosis (which
// lights are ignored, which map setting is hard-coded) runs only once the check has failed.
void StepGrader::gradeHostValues(const Scene& scene) {
    if (!d_.domain) return;
    const Grid g = grid(domainSurfaces(d_, settings_.seed, settings_.domainPoints));
    const Grid few = grid(domainSurfaces(d_, settings_.seed, kFewPoints));
    if (readsSceneLights(renderer_, m_, {}, 7) || readsSceneLights(renderer_, m_, source_, 7))
        gradeLightCounts(scene, g, few);
    if (!(d_.needs & NeedsPrecomputedMaps)) return;
    gradeMapSizes(scene, g);
}

// The values a host value had in the checks before, as a message lists them; "" when a
// deducted values check failed (all passed: a failure after is the value itself).
std::string StepGrader::hostValuesBefore(const std::string& name) {
    for (const CheckReport& c : result_.checks)
        if (c.kind == CheckKind::Values && c.deducted && !c.passed) return std::string();
    std::string values;
    for (const std::string& v : result_.hostValues[name])
        values += (values.empty() ? "" : ", ") + v;
    return values;
}

// NUM_LIGHTS at kGradedLightCounts, up to the first count that fails (the lights it ignores
// named).
void StepGrader::gradeLightCounts(const Scene& scene, const Grid& g, const Grid& few) {
    const ParamValues defaults(d_.params);
    for (int count : kGradedLightCounts) {
        const std::string right = hostValuesBefore("NUM_LIGHTS"), n = std::to_string(count);
        // Above the first count on kFewPoints points: the reference's band sums every light
        // at each of its perturbed inputs (64 lights on 2048 points: 180 ms of CPU, on 64:
        // 6 ms), and a light ignored shows at the points it faces, about half of any set.
        const Grid& points = count == kGradedLightCounts[0] ? g : few;
        ValuesRun run =
            runValues("random inputs with " + n + " lights (NUM_LIGHTS = " + n + ")" +
                          (&points == &few ? " (" + std::to_string(kFewPoints) + " points)" : ""),
                      CheckCategory::Random, withLights(scene, count), defaults, &points.surfaces,
                      points.width, points.height, nullptr);
        const bool failed = !run.report.passed && run.report.deducted;
        const std::string what =
            failed && !settings_.stopAtFirstFailure ? lightsDiagnosis(scene, count, few) : "";
        if (what.empty()) {
            nameHardCoded(run, "NUM_LIGHTS", "NUM_LIGHTS = " + right, n);
            keep(std::move(run));
        } else {
            // The cause is named: not handed to the feedback, whose patterns read the
            // inputs of one light (they told a loop capped at 32 "wrong only where N.L <
            // 0.56", the N.L of light 1).
            run.report.detail = what + "; " + run.report.detail;
            record(run.report);
        }
        if (failed) break;  // the counts above say no more
    }
}

// The precomputed maps at the smallest and the largest the host makes (hostMapEnds), each
// failure taken apart into the values that are hard-coded where everything before passed.
void StepGrader::gradeMapSizes(const Scene& scene, const Grid& g) {
    const ParamValues defaults(d_.params);
    auto reads = [&](const StudentSource& source, const char* name) {
        return renderer_.programs().get(renderer_.viewRecipe(m_, source, true, 1))->uses(name);
    };
    const auto [smallest, largest] =
        hostMapEnds(reads({}, "uEnvironment") || reads(source_, "uEnvironment"));
    const bool passedBefore = !hostValuesBefore("uBrdfLut").empty();
    for (const auto& [label, s] :
         {std::pair{"the smallest maps", smallest}, std::pair{"the largest maps", largest}}) {
        ValuesRun run = runValues(
            std::string("random inputs with ") + label + " the host makes (" + mapValues(s) + ")",
            CheckCategory::Random, scene, defaults, &g.surfaces, g.width, g.height, nullptr, s);
        // Taken apart only where it can name the value: everything before passed.
        if (!run.report.passed && passedBefore && !settings_.stopAtFirstFailure) {
            const std::string wrong = hardCodedMapValues(label, s, scene, g);
            if (!wrong.empty()) run.report.detail = wrong + "; " + run.report.detail;
        }
        record(run.report);
    }
}

// The values of map settings `s` (labelled `label`) that fail on their own, widespread, each
// as "hard-coded host value (...)"; "" when none does.
std::string StepGrader::hardCodedMapValues(const std::string& label, const IblSettings& s,
                                           const Scene& scene, const Grid& g) {
    const ParamValues defaults(d_.params);
    std::string wrong;
    for (const HostMapValue& v : hostMapValues(s)) {
        stage(label + std::string(": ") + v.value + " alone");
        const Evaluation e = evaluatePoints(scene, defaults, g, v.settings);
        if (!e.comparison.passes(d_.nonNegative, d_.tolerance.outlierFraction) &&
            widespread(e.comparison.outside, e.comparison.compared))
            wrong += (wrong.empty() ? "" : "; ") +
                     ("hard-coded host value (" + v.value + "): right with " + v.right +
                      ", wrong with " + v.wrong);
    }
    return wrong;
}

}  // namespace pbrlab::step_grading
