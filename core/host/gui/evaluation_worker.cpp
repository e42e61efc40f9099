#include "evaluation_worker.h"

#include <cstdio>

#include "gl/context.h"
#include "gl/objects.h"
#include "ibl/map_error.h"
#include "platform.h"
#include "render/converge.h"
#include "render/evaluate.h"
#include "render/input_digest.h"
#include "steps/contract.h"
#include "util/error.h"
#include "util/log.h"

namespace pbrlab {

namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

class HeadlessWorkerContext final : public WorkerContext {
public:
    void makeCurrent() override { context_ = createHeadlessContext(); }
    void release() override { context_.reset(); }  // on the worker, whose context it is

private:
    std::unique_ptr<GlContext> context_;
};

class WindowsOwnContext final : public WorkerContext {
public:
    void makeCurrent() override {}
    void release() override {}
};

}  // namespace

std::unique_ptr<WorkerContext> headlessWorkerContext() {
    return std::make_unique<HeadlessWorkerContext>();
}

std::unique_ptr<WorkerContext> windowsOwnContext() {
    return std::make_unique<WindowsOwnContext>();
}

EvaluationWorker::EvaluationWorker(DataPaths paths, std::unique_ptr<WorkerContext> context,
                                   double drawMs)
    : paths_(std::move(paths)), context_(std::move(context)), drawMs_(drawMs) {
    if (kEvaluationThread) thread_ = std::thread([this] { loop(); });
}

EvaluationWorker::~EvaluationWorker() {
    if (!kEvaluationThread) return;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
        ++latest_;  // the job running stops at its next stage
    }
    changed_.notify_all();
    thread_.join();
}

unsigned EvaluationWorker::post(EvaluationJob job) {
    unsigned generation = 0;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        generation = ++latest_;
        pending_ = std::move(job);
        result_.reset();
        wanted_ = true;
    }
    changed_.notify_all();
    return generation;
}

void EvaluationWorker::cancel() {
    std::lock_guard<std::mutex> lock(mutex_);
    ++latest_;
    pending_.reset();
    result_.reset();
    wanted_ = false;
    yieldsLeft_ = kYieldsInARow;  // the input changed the job
}

std::optional<EvaluationResult> EvaluationWorker::take(bool runPending) {
    if (!kEvaluationThread && runPending) runPendingHere();
    std::lock_guard<std::mutex> lock(mutex_);
    if (!result_ || result_->generation != latest_.load()) return std::nullopt;
    std::optional<EvaluationResult> r = std::move(result_);
    result_.reset();
    wanted_ = false;
    return r;
}

EvaluationResult EvaluationWorker::wait() {
    if (!kEvaluationThread) {
        const int yieldsLeft = std::exchange(yieldsLeft_, 0);  // nothing else runs meanwhile
        pendingSeen_ = true;
        runPendingHere();
        if (yieldsLeft_ == 0) yieldsLeft_ = yieldsLeft;  // no job ran (one that did reset it)
    }
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return result_ && result_->generation == latest_.load(); });
    EvaluationResult r = std::move(*result_);
    result_.reset();
    wanted_ = false;
    return r;
}

bool EvaluationWorker::busy() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return wanted_;
}

EvaluationProgress EvaluationWorker::progress() const {
    std::lock_guard<std::mutex> lock(mutex_);
    EvaluationProgress p = progress_;
    if (p.running) p.seconds = millisecondsSince(started_) / 1000;
    return p;
}

void EvaluationWorker::enter(int stage, int stages, const char* what) {
    std::lock_guard<std::mutex> lock(mutex_);
    progress_.stage = stage;
    progress_.stages = stages;
    progress_.what = what;
}

void EvaluationWorker::loop() {
    platform::backgroundPriorityForThisThread();
    // The renderer lives and dies on this thread, with the context current.
    std::unique_ptr<LabRenderer> renderer;
    std::string startError;
    try {
        context_->makeCurrent();
        gl::setDrawBudgetOnThisThread(drawMs_);
        renderer = std::make_unique<LabRenderer>(paths_);
    } catch (const std::exception& e) {
        startError = std::string("the evaluation thread has no OpenGL: ") + e.what();
    }
    for (;;) {
        EvaluationJob job;
        unsigned generation = 0;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait(lock, [&] { return stop_ || pending_; });
            if (stop_) break;
            job = std::move(*pending_);
            pending_.reset();
            generation = latest_.load();
            progress_ = {true, 0, 0, "", 0};
            started_ = std::chrono::steady_clock::now();
        }
        runJob(renderer.get(), startError, job, generation);
    }
    renderer.reset();
    context_->release();
}

void EvaluationWorker::runJob(LabRenderer* renderer, const std::string& startError,
                              const EvaluationJob& job, unsigned generation) {
    std::optional<EvaluationResult> result;
    try {
        if (!renderer) throw Error(startError);
        result = run(*renderer, job, generation);
    } catch (const std::exception& e) {  // not the student's: the host's (says what)
        result.emplace();
        result->generation = generation;
        result->renderError = e.what();
    }
    {
        std::lock_guard<std::mutex> lock(mutex_);
        progress_.running = false;
        if (result && !superseded(generation)) result_ = std::move(result);
    }
    changed_.notify_all();
}

void EvaluationWorker::runPendingHere() {
    if (!pending_) return;
    if (!pendingSeen_) {  // let the frame that noticed it draw the progress line first
        pendingSeen_ = true;
        return;
    }
    pendingSeen_ = false;
    EvaluationJob job = std::move(*pending_);
    pending_.reset();
    yielded_ = false;
    const unsigned generation = latest_.load();
    progress_ = {true, 0, 0, "", 0};
    started_ = std::chrono::steady_clock::now();
    std::string startError;
    try {
        if (!hereRenderer_) {
            ownRenderer_ = std::make_unique<LabRenderer>(paths_);
            hereRenderer_ = ownRenderer_.get();
        }
    } catch (const std::exception& e) {
        startError = std::string("the evaluation has no OpenGL: ") + e.what();
    }
    runJob(hereRenderer_, startError, job, generation);
    if (!yielded_) {
        yieldsLeft_ = kYieldsInARow;
    } else if (superseded(generation)) {
        yielded_ = false;  // a newer post or cancel: the window has what it needs
    } else {
        --yieldsLeft_;
        wanted_ = false;  // no result comes: the window posts the job again
    }
}

bool EvaluationWorker::stopRequested(unsigned generation) {
    if (superseded(generation)) return true;
    if (kEvaluationThread || !inputWaiting_ || yieldsLeft_ <= 0 || !inputWaiting_()) return false;
    yielded_ = true;
    return true;
}

namespace {

// The CPU reference at each of these surfaces, as a picture (surface i at pixel i, as the GPU
// writes the probe).
Image referencePicture(LabRenderer& renderer, const EvaluationJob& job, const IblSettings& ibl,
                       const std::vector<Surface>& surfaces, int width, int height) {
    const ModuleDesc& d = *job.module->desc;
    const Scene scene = applyParamBindings(job.scene, d, job.params);
    const ReferenceContext context = referenceContext(renderer, d, scene, job.params, ibl);
    Image picture;
    picture.width = width;
    picture.height = height;
    picture.pixels.assign(size_t(width) * size_t(height) * 4, 1.0f);
    for (size_t i = 0; i < surfaces.size() && i < size_t(width) * size_t(height); ++i) {
        const glm::dvec3 v = d.reference(surfaces[i], context);
        for (int c = 0; c < 3; ++c) picture.pixels[i * 4 + size_t(c)] = float(v[c]);
    }
    return picture;
}

std::vector<std::shared_ptr<const ModelData>> modelsOf(const Scene& scene) {
    std::vector<std::shared_ptr<const ModelData>> models;
    for (const SceneModel& model : scene.models) models.push_back(model.data);
    return models;
}

// The solution's picture as the first stage draws it: what its kept copy is keyed by too
// (renderInputs), so the key holds whatever the drawing reads. Its probe is the module's.
RenderRequest solutionRequest(const EvaluationJob& job, const IblSettings& ibl) {
    RenderRequest request{job.module, &job.params, &job.scene, {}, nullptr, job.side, job.side};
    request.readSurfaces = true;
    request.reuseGBuffer = true;  // a parameter's or a light's edit draws none
    request.seamlessCubes = false;
    request.ibl = ibl;
    return request;
}

}  // namespace

// The solution's picture, evaluated against the CPU reference (its band), and its probe: the
// first two stages. Returns early when superseded (the caller checks).
void EvaluationWorker::runSolution(LabRenderer& renderer, const EvaluationJob& job,
                                   const IblSettings& ibl, unsigned generation, int& stage,
                                   int stages, EvaluationResult& r, Band& band) {
    const LoadedModule& m = *job.module;
    const ModuleDesc& d = *m.desc;
    enter(++stage, stages, "the solution's picture and the reference");
    EvalRequest request;
    request.render = solutionRequest(job, ibl);
    // Asked between points of the CPU reference (microseconds each): the browser at every
    // 64th (before each stage, stopRequested asks it every time). With a thread, the
    // reference's threads call this at once: the count is only a page's, which has one.
    request.stop = [this, generation, points = 0]() mutable {
        if (kEvaluationThread || ++points % 64 != 0) return superseded(generation);
        return stopRequested(generation);
    };
    request.bandCache = &bandCache_;
    Evaluation solution = evaluate(renderer, request);
    r.solutionMs = solution.render.pictureMilliseconds;
    r.solutionValue = std::move(solution.render.value);
    r.surfaces = std::make_shared<const std::vector<Surface>>(std::move(solution.render.surfaces));
    band = std::move(solution.band);
    r.solutionStats = solution.comparison;
    r.referenceValue = r.solutionValue;
    for (size_t i = 0; i < band.expected.size(); ++i)
        for (int c = 0; c < 3; ++c)
            r.referenceValue.pixels[i * 4 + size_t(c)] = float(band.expected[i][c]);
    // Without the solution's GLSL the picture above was the student's file (or the
    // starter) in its place: what is shown as the solution is the CPU reference.
    const ContractStep* step = findContractStep(d.id);
    r.solutionWithheld = step && solutionWithheld(*step);
    if (r.solutionWithheld) r.solutionValue = r.referenceValue;
    if (stopRequested(generation)) return;
    enter(++stage, stages, "the solution's probe");
    const std::vector<Surface> probe = probeSurfaces(d.probe);
    if (r.solutionWithheld) {
        r.probeSolution =
            referencePicture(renderer, job, ibl, probe, d.probe.width, d.probe.height);
    } else {
        RenderRequest probeRequest{&m,     &job.params,   &job.scene,    {},
                                   &probe, d.probe.width, d.probe.height};
        probeRequest.seamlessCubes = false;
        probeRequest.ibl = ibl;
        r.probeSolution = renderer.render(probeRequest).value;
    }
}

// The solution's picture, band and probe: the last evaluation's when their inputs are the same
// (after a student's edit), else drawn and kept. `studentBand` is then the band the student's
// picture is compared with. False: stopped midway, nothing to keep.
bool EvaluationWorker::evaluateSolution(LabRenderer& renderer, const EvaluationJob& job,
                                        const IblSettings& ibl, unsigned generation, int& stage,
                                        int stages, EvaluationResult& r, Band& band,
                                        const Band*& studentBand) {
    // The solution's stage depends on these inputs only (none: it may link a student's file).
    const std::optional<std::uint64_t> inputs =
        job.errorBudget > 0 ? std::nullopt : renderInputs(renderer, solutionRequest(job, ibl));
    if (inputs && keptSolution_ && keptSolution_->inputs == *inputs) {
        // The same picture, band and probe as the last evaluation's: taken, not drawn.
        const KeptSolution& kept = *keptSolution_;
        stage += 2;
        r.solutionKept = true;
        r.solutionMs = kept.solutionMs;
        r.solutionValue = kept.solutionValue;
        r.referenceValue = kept.referenceValue;
        r.probeSolution = kept.probeSolution;
        r.surfaces = kept.surfaces;
        r.solutionStats = kept.solutionStats;
        studentBand = &kept.band;
        return true;
    }
    keptSolution_.reset();  // its memory, before the next band's
    runSolution(renderer, job, ibl, generation, stage, stages, r, band);
    if (yielded_ || superseded(generation)) return false;
    if (inputs) {
        keptSolution_ = KeptSolution{*inputs,         r.solutionValue, r.referenceValue,
                                     r.probeSolution, r.surfaces,      std::move(band),
                                     r.solutionStats, r.solutionMs,    modelsOf(job.scene)};
        studentBand = &keptSolution_->band;
    }
    return true;
}

// The student's picture, compared with `band`, and its probe (when the job shows the student's
// file). A new file that does not compile fails twice (the view's program, then the probe's),
// and renders the third time with the last good programs (this renderer's cache kept them).
// False: stopped.
bool EvaluationWorker::renderStudent(LabRenderer& renderer, const EvaluationJob& job,
                                     const IblSettings& ibl, unsigned generation, int stage,
                                     int stages, const Band& band, EvaluationResult& r) {
    const LoadedModule& m = *job.module;
    const ModuleDesc& d = *m.desc;
    const StudentSource studentSource{job.submission, false};
    for (int attempt = 0; job.student && attempt < 3 && !r.studentRendered; ++attempt) {
        try {
            enter(stage + 1, stages, "your picture");
            RenderRequest request{&m,      &job.params, &job.scene, studentSource,
                                  nullptr, job.side,    job.side};
            request.reuseGBuffer = true;  // the solution's (drawn anew when not held: a live frame)
            request.seamlessCubes = false;
            request.ibl = ibl;
            r.studentValue = renderer.render(request).value;
            // Without the solution's band (its render failed) there is nothing to compare with.
            if (r.renderError.empty())
                r.studentStats = compareWithBand(r.studentValue, *r.surfaces, band, d.components,
                                                 d.nonNegative, d.tolerance.outlierFraction);
            if (stopRequested(generation)) return false;
            enter(stage + 2, stages, "your probe");
            const std::vector<Surface> probe = probeSurfaces(d.probe);
            RenderRequest probeRequest{&m,     &job.params,   &job.scene,    studentSource,
                                       &probe, d.probe.width, d.probe.height};
            probeRequest.seamlessCubes = false;
            probeRequest.ibl = ibl;
            r.probeStudent = renderer.render(probeRequest).value;
            r.studentRendered = true;
        } catch (const Error& e) {
            // The new file does not compile (ShaderError), or a file it includes may not be
            // read: the UI thread shows why; once more with the last good program.
            r.studentErrors.push_back(e.what());
        }
        if (stopRequested(generation)) return false;
    }
    return true;
}

// The stages Lab::render ran in the frame before: the solution's picture, evaluated against
// the CPU reference; its probe (both the last evaluation's when their inputs are the same: after
// a student's edit); then the student's picture, compared with the same band, and its probe.
// Views read cube maps as the CPU reference does (seamlessCubes off), so the statistics are
// the ones `pbrlab check` grades with.
std::optional<EvaluationResult> EvaluationWorker::run(LabRenderer& renderer,
                                                      const EvaluationJob& job,
                                                      unsigned generation) {
    const auto start = std::chrono::steady_clock::now();
    const int stages = (job.student ? 4 : 2) + (job.errorBudget > 0 ? 1 : 0);
    int stage = 0;
    EvaluationResult r;
    r.generation = generation;
    IblSettings ibl = job.ibl;
    if (job.errorBudget > 0) {
        enter(++stage, stages, "the IBL settings within the error budget");
        r.budgetChoice = chooseForBudget(renderer, job.scene.environment, job.errorBudget);
        ibl = r.budgetChoice->settings;
        if (stopRequested(generation)) return std::nullopt;
    }
    Band band;  // the reference's band on the picture, for the student's statistics
    const Band* studentBand = &band;
    try {
        if (!evaluateSolution(renderer, job, ibl, generation, stage, stages, r, band, studentBand))
            return std::nullopt;
    } catch (const Cancelled&) {
        return std::nullopt;
    } catch (const Error& e) {
        r.renderError = e.what();
    }
    if (stopRequested(generation)) return std::nullopt;
    if (!renderStudent(renderer, job, ibl, generation, stage, stages, *studentBand, r))
        return std::nullopt;
    if (!r.studentRendered) r.studentValue = Image();
    if (job.compose && r.renderError.empty()) r.composed = job.compose(r);
    if (job.environmentMapsHeld >= 0 && !windowsRenderer_ &&
        renderer.environmentMapsBuilt(job.scene.environment, ibl) > job.environmentMapsHeld) {
        r.environment = job.scene.environment;
        r.environmentMaps = renderer.environmentMapImages(job.scene.environment, ibl);
    }
    r.compiled = renderer.programs().compiled();
    r.milliseconds = millisecondsSince(start);
    return r;
}

// Measured the first time an environment is shown, as `pbrlab precompute --error-budget`
// measures it (with the disk cache of maps and exact sums); an environment that cannot be
// measured gets the defaults, and the line says why.
const BudgetChoice& EvaluationWorker::chooseForBudget(LabRenderer& renderer,
                                                      const std::string& environment,
                                                      double budget) {
    const auto key = std::make_pair(environment, budget);
    if (const auto found = budgetChoices_.find(key); found != budgetChoices_.end())
        return found->second;
    BudgetChoice chosen{environment, IblSettings(), ""};
    try {
        const Image equirect = loadEnvironmentImage(environment, renderer.cacheRoot());
        IblTruth truth(equirect);
        IblPrecompute precompute(renderer.programs(), paths_.shaders());
        const IblDiskCache cache(renderer.cacheRoot());
        const IblChoice choice = chooseIblSettings(precompute, equirect, truth, budget,
                                                   renderer.cacheRoot().empty() ? nullptr : &cache);
        const IblErrors& e = choice.run.errors;
        char line[256];
        std::snprintf(line, sizeof line,
                      "error budget %g on %s: %s; mean errors irradiance %.4f, prefilter %.4f, "
                      "LUT %.4f",
                      budget, environment.c_str(),
                      choice.met ? "met" : "NOT met (the most accurate settings)",
                      e.irradiance.mean, e.prefilter.mean, e.lut.mean);
        chosen.settings = choice.settings;
        chosen.summary = std::string(line) + "; " + choice.settings.describe();
    } catch (const Error& e) {
        chosen.summary = std::string("error budget: ") + e.what();
    }
    return budgetChoices_.emplace(key, std::move(chosen)).first->second;
}

}  // namespace pbrlab
