// Values checks of gradeStep (step_grader.h): the step against its reference's band on the
// probe, its scenes, random inputs, every exercised parameter value and coloured lights.

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "grading/step_grader.h"
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

// Seven lights of distinct colours around the scene's centre, at distances 2 to 12 times the
// unit: a count no other check uses (the module's scene has 1, the lesson's grid 4, the
// coloured lights 3), so a loop over a fixed number of lights fails.
Scene sevenLights(Scene scene) {
    const glm::dvec3 c = scene.camera.target;
    const double r = std::max(1.0, 0.3 * glm::length(scene.camera.position - c));
    const glm::dvec3 toCamera = glm::normalize(scene.camera.position - c);
    scene.lights.clear();
    for (int k = 0; k < 7; ++k) {
        const double phi = 2 * 3.141592653589793 * k / 7, up = k % 2 ? 0.8 : -0.3;
        const glm::dvec3 d =
            glm::normalize(toCamera + glm::dvec3(std::cos(phi), up, std::sin(phi)));
        const glm::dvec3 colour(1 + 9 * (k % 3 == 0), 1 + 9 * (k % 3 == 1), 1 + 9 * (k % 3 == 2));
        scene.lights.push_back({c + r * (2 + 1.5 * k) * d, colour * (2.0 + 4.0 * k)});
    }
    return scene;
}

// The precomputed maps with other settings than the defaults, as the host makes them
// (`precompute --prefilter-mips`, `--error-budget`'s rungs: docs/ibl.md), one host value
// varied at a time so that a failure names it.
struct HostMaps {
    std::string value;  // what is varied, as the student reads it
    IblSettings settings;
};
std::vector<HostMaps> hostMapSettings() {
    IblSettings mips = kGradingIbl;
    mips.prefilterMips = 7;  // 128 down to 2: uPrefilterMaxLod = 6 (the default's 5 mips: 4)
    IblSettings sizes = kGradingIbl;
    sizes.environmentSize = 128;
    sizes.irradianceSize = 16;
    sizes.prefilterSize = 64;  // 5 mips still: uPrefilterMaxLod = 4, only the sizes change
    sizes.bins = 8;
    sizes.lutWidth = 256;
    sizes.lutHeight = 16;
    return {{"uPrefilterMaxLod", mips},
            {"the maps' sizes: uBrdfLut, uIrradianceMap, uPrefilterMap, uEnvironment", sizes}};
}

std::string sizeOf(int width, int height, int mips = 1) {
    return std::to_string(width) + "x" + std::to_string(height) +
           (mips > 1 ? " (" + std::to_string(mips) + " mips)" : "");
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

ValuesRun StepGrader::runValues(const std::string& name, const std::string& category,
                                const Scene& scene, const ParamValues& params,
                                const std::vector<Surface>* surfaces, int width, int height,
                                const Probe* probe, const IblSettings& ibl) {
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
        report.kind != "values")
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
    // The worst failure, a failure at the graded counts before one above them.
    const bool better = !failed_ || (failed_->aboveGradedCounts != run.aboveGradedCounts
                                         ? failed_->aboveGradedCounts
                                         : run.report.worstExcess > failed_->report.worstExcess);
    if (!run.report.passed && run.report.deducted && better)
        failed_ = std::make_unique<ValuesRun>(std::move(run));
    record(report);
}

// The category follows the inputs: the probe, random points of the domain, or a scene
// (`sceneCategory`: the lesson's sphere grid is weighted on its own).
void StepGrader::gradeCase(const std::string& name, GradeCase::Inputs inputs, const Scene& scene,
                           const ParamValues& params, const std::string& sceneCategory) {
    switch (inputs) {
        case GradeCase::Inputs::Probe: {
            const Probe& p = d_.probe;
            const std::vector<Surface> s = probeSurfaces(p);
            keep(runValues(name, "probe", scene, params, &s, p.width, p.height, &p));
            return;
        }
        case GradeCase::Inputs::Domain: {
            if (!d_.domain) return;
            const Grid g = grid(domainSurfaces(d_, settings_.seed, settings_.domainPoints));
            keep(runValues(name, "random", scene, params, &g.surfaces, g.width, g.height, nullptr));
            return;
        }
        case GradeCase::Inputs::Scene:
            keep(runValues(name, sceneCategory, scene, params, nullptr, settings_.size,
                           settings_.size, nullptr));
            return;
    }
}

void StepGrader::gradeValues(const Scene& scene) {
    const ParamValues defaults(d_.params);
    gradeCase("probe", GradeCase::Inputs::Probe, scene, defaults);
    gradeCase("scene " + scene.file.stem().string(), GradeCase::Inputs::Scene, scene, defaults);
    gradeCase("random inputs", GradeCase::Inputs::Domain, scene, defaults);
    for (const GradeCase& c : d_.cases) {
        const Scene s = c.scene.empty() ? scene : loadScene(paths_.scene(c.scene));
        gradeCase(c.name, c.inputs, s, withSets(d_, c.set),
                  c.scene == lessonGridCase().scene ? "sphere_grid" : "scenes");
    }
    for (const ParamDecl& p : d_.params)
        for (const std::string& assignment : exercisedValues(p)) {
            const ParamValues params = withSets(d_, {assignment});
            if (p.type == ParamType::Int && params.number(p.name) > kFewPointsAbove) {
                if (!d_.domain) continue;
                const Grid few = grid(domainSurfaces(d_, settings_.seed, kFewPoints));
                keep(runValues("random inputs with " + assignment + " (" +
                                   std::to_string(kFewPoints) + " points)",
                               "random", scene, params, &few.surfaces, few.width, few.height,
                               nullptr));
                continue;
            }
            if (p.binding == ParamBinding::LightDirection) {
                gradeCase("scene with " + assignment, GradeCase::Inputs::Scene, scene, params);
                continue;
            }
            gradeCase("probe with " + assignment, GradeCase::Inputs::Probe, scene, params);
            gradeCase("scene with " + assignment, GradeCase::Inputs::Scene, scene, params);
            gradeCase("random inputs with " + assignment, GradeCase::Inputs::Domain, scene, params);
        }
    // The reference's view or the student's (a student's sum may read the lights itself).
    if (readsSceneLights(renderer_, m_, {}, 3) || readsSceneLights(renderer_, m_, source_, 3)) {
        const Scene lit = colouredLights(scene);
        gradeCase("scene with three coloured lights", GradeCase::Inputs::Scene, lit, defaults);
        gradeCase("random inputs with three coloured lights", GradeCase::Inputs::Domain, lit,
                  defaults);
    }
    gradeHostValues(scene);
}

// Each value the host provides, at a value no other check gives it, on random inputs of the
// domain. When only such a check fails, the step is right with the host's defaults and wrong
// with other values it meets in real use: a hard-coded host value, named so. The IBL ones are
// not handed to the feedback (whose references read the default maps).
// Cost (2-core llvmpipe, warm caches, measured): seven lights 31 ms (reflectance), 11 ms
// (tonemap); the two map settings 198 and 73 ms (split_sum), each precomputed once and then
// read from the disk cache.
void StepGrader::gradeHostValues(const Scene& scene) {
    if (!d_.domain) return;
    const ParamValues defaults(d_.params);
    const Grid g = grid(domainSurfaces(d_, settings_.seed, settings_.domainPoints));
    // The values each host value had in the checks before (all passed: a failure below is the
    // value itself).
    auto before = [&](const std::string& name) {
        for (const CheckReport& c : result_.checks)
            if (c.kind == "values" && c.deducted && !c.passed) return std::string();
        std::string values;
        for (const std::string& v : result_.hostValues[name])
            values += (values.empty() ? "" : ", ") + v;
        return values;
    };
    auto named = [&](ValuesRun& run, const std::string& value, const std::string& right,
                     const std::string& now) {
        if (run.report.passed || right.empty()) return;
        run.report.detail = "hard-coded host value (" + value + "): right with " + right +
                            ", wrong with " + now + "; " + run.report.detail;
    };
    if (readsSceneLights(renderer_, m_, {}, 7) || readsSceneLights(renderer_, m_, source_, 7)) {
        const std::string right = before("NUM_LIGHTS");
        ValuesRun run =
            runValues("random inputs with seven lights (NUM_LIGHTS = 7)", "random",
                      sevenLights(scene), defaults, &g.surfaces, g.width, g.height, nullptr);
        named(run, "NUM_LIGHTS", "NUM_LIGHTS = " + right, "7");
        keep(std::move(run));
    }
    if (d_.needs & NeedsPrecomputedMaps)
        for (const HostMaps& h : hostMapSettings()) {
            const bool lod = h.value == "uPrefilterMaxLod";
            const std::string right = before(lod ? "uPrefilterMaxLod" : "uBrdfLut");
            const std::string now =
                lod ? std::to_string(h.settings.prefilterMips - 1)
                    : "uBrdfLut " + sizeOf(h.settings.lutWidth, h.settings.lutHeight) +
                          ", uIrradianceMap " +
                          sizeOf(h.settings.irradianceSize, h.settings.irradianceSize) +
                          ", uPrefilterMap " +
                          sizeOf(h.settings.prefilterSize, h.settings.prefilterSize) +
                          ", uEnvironment " +
                          sizeOf(h.settings.environmentSize, h.settings.environmentSize);
            ValuesRun run =
                runValues("random inputs with other maps (" + h.value + ")", "random", scene,
                          defaults, &g.surfaces, g.width, g.height, nullptr, h.settings);
            named(run, h.value, (lod ? "uPrefilterMaxLod = " : "uBrdfLut ") + right, now);
            record(run.report);
        }
}

}  // namespace pbrlab::step_grading
