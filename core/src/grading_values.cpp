// Values checks of gradeStep (step_grader.h): the step against its reference's band on the
// probe, its scenes, random inputs, every exercised parameter value and coloured lights.

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "kit.h"
#include "pbrlab/error.h"
#include "step_grader.h"

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

}  // namespace

ValuesRun StepGrader::runValues(const std::string& name, const std::string& category,
                                const Scene& scene, const ParamValues& params,
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

// The stub is the kit's (kit.h stubSolution: the solution's body replaced by `return 0`), the
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
    if (!run.report.passed && run.report.deducted &&
        (!failed_ || run.report.worstExcess > failed_->report.worstExcess))
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
}

}  // namespace pbrlab::step_grading
