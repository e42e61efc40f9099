// The frame function: GuiState -> evaluation -> images (Lab::update and what it calls).
#include <algorithm>
#include <cmath>
#include <ctime>

#include "assets/envgen.h"
#include "lab.h"
#include "render/display.h"
#include "shader/student_file.h"
#include "steps/contract.h"
#include "term_views.h"
#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// How long the input must be still before the full evaluation runs (the live view until then).
constexpr std::chrono::milliseconds kSettleDelay{200};

// What the renderer has done that is not drawing (compiles, texture loads, precompute
// passes): a frame that did any says nothing about what the picture costs.
int setupWorkDone() {
    return eventCount(Counter::ProgramCompiles) + eventCount(Counter::TextureLoads) +
           eventCount(Counter::PrecomputePasses);
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// The view the state asks for, from these values, in display form, and what of the student's
// cannot be shown honestly (NaN, Inf): compose's CPU work, done on the evaluation thread for
// a fresh evaluation (a second under load on the window's thread).
ComposedView composeView(const ModuleDesc& d, const ViewChoice& choice, const Image& solution,
                         const Image& studentOrEmpty, const Image& reference,
                         const std::vector<Surface>& surfaces) {
    const Image& student = studentOrEmpty.pixels.empty() ? solution : studentOrEmpty;
    ComposedView composed;
    Image& shown = composed.image;
    switch (choice.view) {
        case View::Student:
            shown = displayImage(student, d.display, d.components);
            break;
        case View::Solution:
            shown = displayImage(solution, d.display, d.components);
            break;
        case View::Reference:
            shown = displayImage(reference, d.display, d.components);
            break;
        case View::Difference:
            shown = differenceImage(student, reference, d.components, choice.differenceRange);
            break;
        case View::Split: {
            shown = displayImage(student, d.display, d.components);
            Image ref = displayImage(reference, d.display, d.components);
            int split = int(choice.split * shown.width);
            for (int y = 0; y < shown.height; ++y)
                for (int x = split; x < shown.width; ++x)
                    for (int c = 0; c < 4; ++c)
                        shown.at(x, y, c) = x == split ? 1.0f : ref.at(x, y, c);
            break;
        }
        case View::Term:
            shown = termImage(*choice.term, solution, surfaces);
            break;
    }
    for (size_t i = 0; i + 3 < student.pixels.size(); i += 4)
        for (int c = 0; c < d.components; ++c) {
            composed.nanCount += std::isnan(student.pixels[i + size_t(c)]);
            composed.infCount += std::isinf(student.pixels[i + size_t(c)]);
        }
    return composed;
}

}  // namespace

// A frame's work before the window is drawn: the panels' requests carried out, a saved file
// noticed, a live picture drawn or the evaluation started, and what the evaluation and the
// grades sent back shown.
void Lab::update(GuiState& state, Requests& requests) {
    const bool holding = carryOut(state, requests);
    watchStudentFile(state);
    drawOrEvaluate(state, holding);
    takeResults(state, holding);
}

// The requests of the last frame's panels and console, carried out; all but the screenshot,
// which the window takes after drawing, are cleared. Returns whether a control is held down.
bool Lab::carryOut(GuiState& state, Requests& requests) {
    if (requests.selectStep >= 0) {
        select(state, requests.selectStep);
        showChosenView(state);
    }
    if (requests.reloadScene) loadScene(state);
    if (requests.firstLight && !shown_.scene.lights.empty()) {
        shown_.scene.lights[0] = *requests.firstLight;
        requests.moved = true;
    }
    if (requests.environment) {
        const std::string& env = *requests.environment;
        if (!isGeneratedEnvironment(env) && !fs::exists(env)) {
            shown_.sceneError =
                env +
                ": no such file (use a generated sky such as \"sky\" or \"white\", or an "
                ".hdr/.exr path)";
        } else {
            shown_.scene.environment = env;
            shown_.sceneError.clear();
            dirty_ = true;
        }
    }
    if (requests.moved) moved();
    if (requests.recompose) compose(state);
    if (requests.viewChosen) {
        const std::string& id = module(state).id;
        const std::string view = viewName(state.view, state.term, termViews_);
        state.chosenViews[id] = view;
        if (options_.viewChosen) options_.viewChosen(id, view);
    }
    const bool holding = requests.holding;
    Requests carriedOut;  // all but the screenshot, which the window takes after drawing
    carriedOut.screenshot = requests.screenshot;
    carriedOut.screenshotFile = std::move(requests.screenshotFile);
    requests = std::move(carriedOut);
    return holding;
}

// Hot reload: a saved student file, or a file it includes, marks the view dirty; the renderer
// recompiles it.
void Lab::watchStudentFile(GuiState& state) {
    if (!studentFile(state).empty() && studentWatch_.changed(studentFile(state), submission_)) {
        dirty_ = true;
        // The student's file has appeared: their picture, unless they chose a view here.
        if (state.view == View::Solution && !state.chosenViews.count(module(state).id) &&
            fs::exists(studentFile(state))) {
            state.view = View::Student;
            compose(state);
        }
    }
}

// While the input moves, a live picture; once it is still, the evaluation.
void Lab::drawOrEvaluate(GuiState& state, bool holding) {
    const ModuleDesc& m = module(state);
    const Scene scene = currentScene(state);
    // While the input moves, only the picture is drawn (on the GPU, mapped for display there,
    // nothing read back): 30 frames a second at least. The evaluation against the CPU
    // reference, the probes and the statistics follow once it has been still for a moment
    // (dirty_ stays set until then), on the evaluation thread: the frames go on meanwhile.
    // Without an evaluation thread (a page) the evaluation runs in the window's, where the next
    // move cannot cancel it: a control held still for a moment mid-drag would stop the window
    // for the evaluation (0.8 s for ndf, seconds for the IBL steps). It waits for the release.
    // (An evaluation thread shows it meanwhile, and the next move cancels it.)
    const bool moving = std::chrono::steady_clock::now() - lastMove_ < kSettleDelay ||
                        (!kEvaluationThread && holding);
    // An environment's maps (and --error-budget's settings for them) are made on the
    // evaluation thread, which hands them to the window's renderer with its result
    // (showEvaluation): a live picture before they arrive would make them in the frame (0.1 s
    // to seconds). Until then a drag keeps the picture on screen and says why.
    shown_.liveWaitsForMaps =
        dirty_ && moving && (m.needs & NeedsEnvironment) &&
        (waitsForBudgetSettings(scene) ||
         renderer_->environmentMapsBuilt(scene.environment, iblFor(scene)) == 0);
    if (dirty_ && moving) {
        if (!shown_.liveWaitsForMaps && !drawLive(state)) startEvaluation(state);
    } else if (dirty_) {
        // Still (a step, scene or saved file; the input stopped): the picture on screen stays
        // until the evaluation arrives, with its progress under it. No live picture here: for
        // a new step or a saved file the window's renderer would compile (or precompute maps)
        // first, for tenths of a second to seconds, which the evaluation thread does anyway.
        startEvaluation(state);
    }
}

// What came back since the last frame: the evaluation's result, an evaluation that yielded to
// input, a grade.
void Lab::takeResults(GuiState& state, bool holding) {
    // Without an evaluation thread the posted job runs in take(): not while the button is held.
    if (std::optional<EvaluationResult> result = worker_->take(kEvaluationThread || !holding))
        showEvaluation(std::move(*result), state);
    // A page's evaluation gave the thread to a press or a key (EvaluationWorker::yieldWhen):
    // posted again once the input is still, as after a move.
    if (worker_->takeYielded()) {
        ++evaluationsYielded_;
        dirty_ = true;
        lastMove_ = std::chrono::steady_clock::now();
    }
    // The grades run beside the window: niced processes on the desktop; in a page, a worker
    // that grades a file as soon as the editor writes it (shell.html), so the badge's report
    // is usually made, or on its way, when the badge asks.
    // A grade that arrives changes the badge and the grade line under the picture, which read
    // the badge as they are drawn: the picture is not evaluated again for it.
    if (!badges_->update(*registry_, module(state).id).empty()) ++gradesArrived_;
}

// An input changed what is drawn (camera, parameter, light): a live frame now, the full
// evaluation when it stops.
void Lab::moved() {
    dirty_ = true;
    lastMove_ = std::chrono::steady_clock::now();
    worker_->cancel();  // out of date: it stops at its next stage, and leaves the cores free
}

// The student's file did not compile (ShaderError): its log stays on screen until a version
// of the file compiles (studentRendered with the files changed since).
void Lab::studentFailed(const std::string& id, const std::string& log) {
    StudentCompile& c = compiles_[id];
    if (c.log != log) logLine("gui", id + ".glsl does not compile");
    c.log = log;
    c.failed = studentWatch_.current();
    showCompile(id);
    badges_->markCompileError(id);
}

// The student's picture rendered. With the files as they were when they failed, that was the
// renderer's last good program: the error stays. Otherwise the files on disk compiled.
void Lab::studentRendered(const std::string& id) {
    StudentCompile& c = compiles_[id];
    const SourceWatch::Stamps now = studentWatch_.current();
    if (!c.log.empty() && now == c.failed) return;
    if (!c.log.empty()) logLine("gui", id + ".glsl compiles again");
    c.log.clear();
    showCompile(id);
    if (now == c.good && !c.compiledAt.empty()) return;
    c.good = now;
    const std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
    std::tm local{};
    localtime_r(&t, &local);
    char text[16];
    std::strftime(text, sizeof text, "%H:%M:%S", &local);
    c.compiledAt = shown_.compiledAt = text;
}

// The step's compile state as the panels show it: a refusal first, else the compile error.
void Lab::showCompile(const std::string& id) {
    const StudentCompile& c = compiles_[id];
    shown_.refused = !c.refusal.empty();
    shown_.compileLog = shown_.refused ? c.refusal : c.log;
    shown_.compiledAt = c.compiledAt;
}

bool Lab::settled(const GuiState& state) const {
    const fs::path file = studentFile(state);
    return !dirty_ && !shown_.liveTexture && !worker_->busy() &&
           (file.empty() || !studentWatch_.stale(file)) && badges_->upToDate(module(state).id);
}

// The picture the student is looking at (theirs when their file has compiled, else the
// solution's), rendered at the live size (LiveSize) and mapped for display on the GPU.
// False when the student's file failed: the error is shown, and the evaluation shows the
// last version that compiled.
bool Lab::drawLive(const GuiState& state) {
    const auto start = std::chrono::steady_clock::now();
    const int setupWork = setupWorkDone();
    const bool student = liveShowsStudent(state);
    const ModuleDesc& m = module(state);
    try {
        shown_.liveTexture = renderLive(state, student);
        // (A withheld solution's program holds the student's file in its place: contract.h.)
        const ContractStep* step = findContractStep(m.id);
        shown_.liveWho = student || (step && solutionWithheld(*step)) ? "your" : "the solution's";
    } catch (const Error& e) {
        // The student's file, saved while the input moves, does not compile (or may not be
        // read): the error stays, and the evaluation shows the last version that compiled.
        // The live pictures are the solution's until the files change (this renderer may
        // have no last good program: it would compile the file again every frame).
        if (student) {
            studentFailed(m.id, e.what());
            liveStudentFailed_ = studentWatch_.current();
        } else {
            shown_.renderError = e.what();
        }
        return false;
    }
    shown_.renderMs = millisecondsSince(start);
    shown_.liveSide = live_.side();
    liveSizes_.push_back(live_.side());
    if (setupWorkDone() == setupWork) live_.frameTook(shown_.renderMs);  // the next side
    return true;
}

bool Lab::liveShowsStudent(const GuiState& state) const {
    return state.view != View::Solution && !shown_.studentValue.pixels.empty() &&
           studentWatch_.current() != liveStudentFailed_ && gate(module(state).id).empty();
}

// What a page's watchdog says of running the student's file now (gui.h, studentFileGate).
std::string Lab::gate(const std::string& id) const {
    return options_.studentFileGate ? options_.studentFileGate(id) : std::string();
}

// The live picture at LiveSize's side, mapped for display: its texture.
GLuint Lab::renderLive(const GuiState& state, bool student) {
    const Scene scene = currentScene(state);
    const ModuleDesc& m = module(state);
    RenderRequest request{
        &loaded(state), &state.params.at(m.id),
        &scene,         student ? StudentSource{submission_, false} : StudentSource{},
        nullptr,        live_.side(),
        live_.side()};
    request.seamlessCubes = false;  // as the settled picture: no jump when it lands
    request.readValue = false;
    request.coarseSpheres = options_.economies.coarseLiveSpheres();
    request.ibl = iblFor(scene);
    const RenderResult r = renderer_->render(request);
    const GLuint texture =
        displayPass_->run(r.valueTexture, live_.side(), live_.side(), m.display, m.components);
    // Magnified smoothly, as dynamic resolution does (the line under it gives its size).
    gl::BindTexture(GL_TEXTURE_2D, texture);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return texture;
}

void Lab::render(const GuiState& state) {
    startEvaluation(state);
    showEvaluation(worker_->wait(), state);
}

// What the evaluation needs from the state, copied, to the evaluation thread (superseding the
// one it runs); what the panels show of the student's file is decided here, before anything
// reads it.
void Lab::startEvaluation(const GuiState& state) {
    dirty_ = false;
    const LoadedModule& m = loaded(state);
    const ModuleDesc& d = *m.desc;
    EvaluationJob job;
    job.module = &m;
    job.params = state.params.at(d.id);
    job.scene = currentScene(state);
    job.ibl = iblFor(job.scene);
    if (d.needs & NeedsEnvironment) {
        const bool choose = waitsForBudgetSettings(job.scene);
        job.errorBudget = choose ? options_.errorBudget : 0;
        // The window holds no maps for settings not chosen yet.
        job.environmentMapsHeld =
            choose ? 0 : renderer_->environmentMapsBuilt(job.scene.environment, job.ibl);
    }
    job.submission = submission_;
    job.side = kRenderSize;
    updatePermutation(state, applyParamBindings(job.scene, d, job.params));
    const fs::path file = studentFile(state);
    std::error_code ec;
    shown_.hasStudent = !file.empty() && fs::exists(fs::symlink_status(file, ec));
    if (!shown_.hasStudent) compiles_.erase(d.id);  // deleted: nothing to compile
    // Screened before anything reads it (the renderer reads it through the same screening):
    // a FIFO, a device, a file over 10 MB or with NUL bytes, or a link out of the workspace is
    // refused, with the reason on screen, and never opened for reading.
    StudentCompile& c = compiles_[d.id];
    std::string refusal = shown_.hasStudent ? screenStudentFile(file, submission_) : "";
    if (refusal.empty() && shown_.hasStudent) {
        refusal = gate(d.id);  // a page's watchdog: a file that did not finish last time
        if (refusal == kStudentFileNotYet) {
            dirty_ = true;  // asked again next frame, once the page has noted it
            return;
        }
    }
    if (!refusal.empty() && c.refusal != file.string() + ": " + refusal)
        logLine("gui", file.string() + ": " + refusal);
    c.refusal = refusal.empty() ? "" : file.string() + ": " + refusal;
    showCompile(d.id);
    job.student = shown_.hasStudent && !shown_.refused;
    // The view as the state asks for it now, composed on the worker (a view change meanwhile
    // composes again here, as it always did).
    postedChoice_ = viewChoice(state);
    job.compose = [&d, choice = postedChoice_](const EvaluationResult& r) {
        return composeView(d, choice, r.solutionValue, r.studentValue, r.referenceValue,
                           *r.surfaces);
    };
    worker_->post(std::move(job));
}

// The evaluation thread's result, for the state it was started from (a newer edit would have
// superseded it): what the panels show.
void Lab::showEvaluation(EvaluationResult r, const GuiState& state) {
    shown_.liveTexture = 0;
    if (r.budgetChoice &&
        budgetSettings_.emplace(r.budgetChoice->environment, r.budgetChoice->settings).second)
        logLine("gui", r.budgetChoice->summary);
    if (r.environmentMaps) renderer_->adoptEnvironmentMaps(r.environment, *r.environmentMaps);
    const ModuleDesc& d = module(state);
    if (r.renderError.empty()) {
        shown_.solutionValue = std::move(r.solutionValue);
        live_.fullSizeTook(r.solutionMs);
        try {
            displayPass_->prepare();  // compiled now, not in the first live frame
        } catch (const Error&) {
            // The first live frame compiles it again and says why (drawLive's renderError).
        }
        shown_.surfaces = std::move(r.surfaces);
        shown_.solutionStats = r.solutionStats;
        shown_.solutionWithheld = r.solutionWithheld;
        shown_.referenceValue = std::move(r.referenceValue);
        shown_.probeSolution = std::move(r.probeSolution);
        shown_.renderError.clear();
    } else {
        shown_.renderError = r.renderError;
    }
    for (const std::string& error : r.studentErrors) studentFailed(d.id, error);
    if ((r.studentRendered || !r.studentErrors.empty()) && options_.studentFileCameBack)
        options_.studentFileCameBack(d.id);
    if (r.studentRendered) {
        shown_.studentValue = std::move(r.studentValue);
        shown_.studentStats = r.studentStats;
        shown_.probeStudent = std::move(r.probeStudent);
        studentRendered(d.id);
    } else {
        // No version of the student's file has compiled yet: nothing of theirs to show.
        shown_.studentValue = Image();
    }
    evaluationPrograms_ = std::move(r.compiled);
    ++evaluationsDone_;
    shown_.renderMs = r.milliseconds;
    logLine("gui", "evaluated " + d.id + " against the CPU reference in " +
                       std::to_string(int(shown_.renderMs)) + " ms");
    if (r.composed && viewChoice(state) == postedChoice_)
        show(*r.composed);
    else
        compose(state);
    // In a page the live frames share the evaluation's renderer: its value target, which the
    // evaluation has just made full size, and the live G-buffer, which the new side allowed
    // (LiveSize) may resize. The next drag's first live frame made them again and drew into
    // them first, 70-100 ms where the next frames took 25-35 (headless Chromium). A live
    // picture drawn now, while nothing moves, pays that instead of the drag.
    if (!kEvaluationThread && r.renderError.empty()) {
        try {
            renderLive(state, liveShowsStudent(state));
        } catch (const Error&) {
            // The next drag's first live frame meets it again and says why (drawLive).
        }
    }
}

// The programs this step needs for the scene on screen, as `pbrlab permutations` lists them:
// one G-buffer define set per kind of material drawn (a map adds a HAS_*_MAP define), and the
// view's (the student's file compiles with the same defines).
void Lab::updatePermutation(const GuiState& state, const Scene& scene) {
    shown_.permutation.clear();
    std::set<std::string> gbuffers;
    for (const DrawItem& item : drawItems(scene))
        gbuffers.insert(definesText(
            renderer_->gbufferRecipe(scene.materials.at(size_t(item.material)), module(state).needs)
                .defines));
    for (const std::string& d : gbuffers) shown_.permutation.insert({"G-buffer", d});
    ProgramRecipe view = renderer_->viewRecipe(loaded(state), {}, false, int(scene.lights.size()));
    shown_.permutation.insert({view.label, definesText(view.defines)});
}

ViewChoice Lab::viewChoice(const GuiState& state) const {
    return {state.view, state.view == View::Term ? &termViews_.at(size_t(state.term)) : nullptr,
            state.differenceRange, state.split};
}

// The view the state asks for, from the values of the last evaluation, into imageTexture.
void Lab::compose(const GuiState& state) {
    if (shown_.solutionValue.pixels.empty()) return;
    show(composeView(module(state), viewChoice(state), shown_.solutionValue, shown_.studentValue,
                     shown_.referenceValue, *shown_.surfaces));
}

void Lab::show(const ComposedView& composed) {
    const Image& shown = composed.image;
    shown_.nanCount = composed.nanCount;
    shown_.infCount = composed.infCount;
    gl::BindTexture(GL_TEXTURE_2D, shown_.imageTexture.id());
    gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Row 0 of the image is its top; ImGui draws uv (0,0) at the top-left: no flip.
    gl::TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, shown.width, shown.height, 0, GL_RGBA, GL_FLOAT,
                   shown.pixels.data());
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    shown_.imageWidth = shown.width;
    shown_.imageHeight = shown.height;
}

}  // namespace pbrlab
