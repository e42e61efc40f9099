// The GUI's working half, without drawing: the services (step libraries, renderer), what the
// last evaluation produced (Shown), and the frame function that turns the student's choices
// (GuiState) into images. Panels (panels.h) read a const Lab and write only GuiState and
// Requests; the next frame's update() carries the requests out.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "badges.h"
#include "evaluation_worker.h"
#include "gui.h"
#include "live_size.h"
#include "render/compare.h"
#include "render/display_pass.h"
#include "render/renderer.h"
#include "source_watch.h"
#include "state.h"
#include "steps/paths.h"
#include "steps/plugin_host.h"

namespace pbrlab {

constexpr int kRenderSize = 512;  // the lab image; scaled to fit the window

// One-shot requests the panels make while drawing; update() carries them out and clears them.
struct Requests {
    int selectStep = -1;       // go to this step (index into the registry's modules)
    bool reloadScene = false;  // the chosen scene or model changed, or "reset camera"
    bool moved = false;        // camera, parameter or light changed: live frames, then the
                               // evaluation once the input is still
    bool recompose = false;    // the view or its settings changed: the same values shown anew
    bool viewChosen = false;   // the student chose the view: remembered for the step
    // A control is held with the mouse (the picture's orbit, a slider), still or not, or the
    // button has just been pressed: without an evaluation thread it counts as moving (the
    // evaluation would stop the window mid-drag).
    bool holding = false;
    // Save the window, when drawn, to screenshotFile (empty: pbrlab-screenshot.png); the
    // window does it, not update().
    bool screenshot = false;
    std::filesystem::path screenshotFile;
    std::optional<PointLightDesc> firstLight;  // the scene's first light, edited
    std::optional<std::string> environment;    // load this environment: "sky" or a file
};

// How the values are shown: the view chosen and its settings (GuiState's).
struct ViewChoice {
    View view = View::Student;
    const TermView* term = nullptr;  // View::Term's
    float differenceRange = 0, split = 0;
    bool operator==(const ViewChoice&) const = default;
};

// What the last evaluation produced, as the panels show it (caches: rebuilt from the state).
struct Shown {
    Scene scene;          // as loaded, with the lights and environment as edited; camera: GuiState
    std::string handout;  // the step's README.md
    std::string sceneError;   // the scene, model or environment that did not load
    std::string renderError;  // the solution's render failed
    // The student's file does not compile (or may not be read): the compiler's log, with
    // file:line. It stays until a version of the file compiles again; meanwhile the picture
    // and the statistics are the last version's that did (studentValue), if any.
    std::string compileLog;
    std::string compiledAt;  // when the version of the student's file on screen compiled
    // compileLog says why the file may not be read (screenStudentFile) or used: nothing of
    // the student's is shown.
    bool refused = false;
    std::string messages;     // start-up notes for the steps panel (modules, font, state)
    bool hasStudent = false;  // a student file exists for this step
    Image studentValue, solutionValue, referenceValue, probeSolution, probeStudent;
    // The G-buffer's inputs, one per pixel of the picture (never null once evaluated).
    std::shared_ptr<const std::vector<Surface>> surfaces =
        std::make_shared<const std::vector<Surface>>();
    Comparison studentStats, solutionStats;
    // The site has no solution GLSL of this step (EvaluationResult::solutionWithheld): the
    // solution's picture and probe are the CPU reference's.
    bool solutionWithheld = false;
    gl::Handle imageTexture;  // the composed view
    int imageWidth = 1, imageHeight = 1, nanCount = 0, infCount = 0;
    GLuint liveTexture = 0;    // while the input moves: the live picture (0: the settled image)
    const char* liveWho = "";  // whose function the live picture is
    int liveSide = 0;          // the live picture's side (kRenderSize: not reduced)
    // The input moves but no live picture is drawn: the environment's maps are being built
    // on the evaluation thread (they arrive with its result).
    bool liveWaitsForMaps = false;
    // The step's programs for the scene on screen: (label, defines) as compiled() lists them.
    std::set<std::pair<std::string, std::string>> permutation;
    double frameMs = 0, renderMs = 0;
};

class Lab {
public:
    // Loads the step libraries and starts the renderer, then fills `state` from the options
    // and gui.json. Needs a current GL context; `workerContext` is the evaluation thread's
    // (evaluation_worker.h), of the same backend. Throws pbrlab::Error on bad options.
    Lab(const GuiOptions& options, GuiState& state,
        std::unique_ptr<WorkerContext> workerContext = headlessWorkerContext());

    // The frame function: carries out the requests, notices edited student files, and
    // renders what the state asks for: a live picture while the input moves; once it is
    // still, the full evaluation against the CPU reference, on the evaluation thread, shown
    // by the frame in which it arrives (the window keeps drawing meanwhile).
    void update(GuiState& state, Requests& requests);
    // The full evaluation now, waiting for it (--orbit's baseline).
    void render(const GuiState& state);

    const LoadedModule& loaded(const GuiState& state) const {
        return registry_->modules()[size_t(state.step)];
    }
    const ModuleDesc& module(const GuiState& state) const { return *loaded(state).desc; }
    std::filesystem::path studentFile(const GuiState& state) const;
    // The scene with the state's orbit camera.
    Scene currentScene(const GuiState& state) const;

    const GuiOptions& options() const { return options_; }
    const DataPaths& paths() const { return paths_; }
    const ModuleRegistry& registry() const { return *registry_; }
    LabRenderer& renderer() const { return *renderer_; }
    const std::filesystem::path& submission() const { return submission_; }
    const Badges& badges() const { return *badges_; }
    const Shown& shown() const { return shown_; }
    Shown& shown() { return shown_; }
    const std::vector<int>& liveSizes() const { return liveSizes_; }  // for --orbit's report
    // The picture is evaluated for the state, and the step's badge graded for the file on
    // disk: nothing is left to update (the console's `wait`).
    bool settled(const GuiState& state) const;
    // Evaluations against the CPU reference finished so far, and whether one is running now:
    // --frame-times tells the frames drawn while one ran.
    int evaluationsDone() const { return evaluationsDone_; }
    // Evaluations a page dropped for the student's input (EvaluationWorker::yieldWhen).
    int evaluationsYielded() const { return evaluationsYielded_; }
    bool evaluating() const { return worker_->busy(); }
    // What is on screen changes without input: an evaluation is due or running, or a live
    // picture waits for it.
    bool changing() const { return dirty_ || worker_->busy() || shown_.liveTexture != 0; }
    int gradesArrived() const { return gradesArrived_; }  // grades the badges have taken
    EvaluationProgress evaluationProgress() const { return worker_->progress(); }
    // The programs the evaluation thread's renderer compiled, in order, as of its last
    // evaluation (the window's own: renderer().programs().compiled()).
    const std::vector<CompiledProgram>& evaluationPrograms() const { return evaluationPrograms_; }
    LiveSize& liveSize() { return live_; }  // the live picture's side (tests set it)
    // The term views of the loaded steps (term_views.h), in the view chooser's order.
    const std::vector<TermView>& termViews() const { return termViews_; }
    // The IBL settings the scene's maps are built with (--error-budget's, else the defaults).
    IblSettings iblFor(const Scene& scene) const;

private:
    // update()'s parts, in its order (frame.cpp).
    bool carryOut(GuiState& state, Requests& requests);
    void watchStudentFile(GuiState& state);
    void drawOrEvaluate(GuiState& state, bool holding);
    void takeResults(GuiState& state, bool holding);
    void select(GuiState& state, int index);
    void showChosenView(GuiState& state) const;
    void loadScene(GuiState& state);
    void noteModelWarnings(const Scene& scene);
    // --error-budget's settings for the scene's environment are still being chosen.
    bool waitsForBudgetSettings(const Scene& scene) const;
    bool drawLive(const GuiState& state);
    // The live picture is the student's (their file has rendered, and has not failed since).
    bool liveShowsStudent(const GuiState& state) const;
    std::string gate(const std::string& id) const;
    GLuint renderLive(const GuiState& state, bool student);
    void startEvaluation(const GuiState& state);
    void showEvaluation(EvaluationResult result, const GuiState& state);
    void compose(const GuiState& state);
    ViewChoice viewChoice(const GuiState& state) const;
    void show(const ComposedView& composed);  // into imageTexture
    void updatePermutation(const GuiState& state, const Scene& scene);
    void moved();
    void studentFailed(const std::string& id, const std::string& log);
    void studentRendered(const std::string& id);
    void showCompile(const std::string& id);

    GuiOptions options_;
    DataPaths paths_;
    std::unique_ptr<ModuleRegistry> registry_;
    std::vector<TermView> termViews_;
    std::unique_ptr<LabRenderer> renderer_;
    std::unique_ptr<DisplayPass> displayPass_;
    std::filesystem::path submission_;
    std::unique_ptr<Badges> badges_;
    Shown shown_;
    SourceWatch studentWatch_;  // hot reload of the step on screen
    // Per step, the student's file's compile error (Shown::compileLog for the step on screen)
    // and the files as they were when it failed, and when a version last compiled: a render
    // that succeeds with the files unchanged since the failure used the renderer's last good
    // program (kept across steps), and the error stays on screen.
    struct StudentCompile {
        std::string log, compiledAt;
        std::string refusal;  // the file may not be read or used, and why (before log)
        SourceWatch::Stamps failed, good;
    };
    std::map<std::string, StudentCompile> compiles_;
    // What is on screen, for the chooser to return to when a file does not load.
    std::string shownSceneName_;
    std::filesystem::path shownModel_;
    std::set<std::filesystem::path> warnedModels_;
    std::map<std::string, IblSettings> budgetSettings_;  // --error-budget, per environment
    // The evaluation is out of date (dirty_) and the input last moved at lastMove_.
    bool dirty_ = true;
    std::chrono::steady_clock::time_point lastMove_{};
    // The live picture's side (after options_, whose economies it follows).
    LiveSize live_{kRenderSize, kLiveFramesTimed, options_.economies.liveSize()};
    std::vector<int> liveSizes_;  // of every live frame, for --orbit's report
    int evaluationsDone_ = 0, evaluationsYielded_ = 0;
    int gradesArrived_ = 0;
    std::vector<CompiledProgram> evaluationPrograms_;
    ViewChoice postedChoice_;  // the view the evaluation running composes
    // The student's files as they were when the window's renderer could not compile them for
    // a live picture (it has no last good program when the evaluation thread compiled them
    // all): live pictures are the solution's until the files change.
    SourceWatch::Stamps liveStudentFailed_;
    // Last: stopped first, before the registry whose steps its job points to.
    std::unique_ptr<EvaluationWorker> worker_;
};

}  // namespace pbrlab
