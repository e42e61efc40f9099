// The settled evaluation (the picture at full size read back and compared with the CPU
// reference, the probes, the student's picture and its statistics: 1-6 s on llvmpipe) on a
// thread of its own, with its own GL context and renderer, so that the window keeps drawing
// while it runs. One job at a time; a newer job supersedes an older one, which stops at its
// next stage (its CPU reference between two points) and is never delivered (a generation
// counter: each post or cancel is newer).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "assets/scene.h"
#include "pbrlab/params.h"
#include "render/compare.h"
#include "render/evaluate.h"
#include "render/renderer.h"
#include "shader/program.h"
#include "steps/paths.h"
#include "steps/plugin_host.h"
#include "util/parallel.h"

namespace pbrlab {

// A GL context for the evaluation thread: made where its backend allows (a GLFW window only on
// the main thread), current on the worker only.
//
// Not shared with the window's context: the worker hands back images in memory (what the
// panels show and the statistics are read back anyway), so no GL object crosses threads and
// neither thread waits on the other's GL work; the cost is that the worker compiles its own
// programs (once per step, off the UI thread). Same backend as the window's, because the GL
// entry points (gl/gl.h) are loaded once per process from the window's backend.
class WorkerContext {
public:
    virtual ~WorkerContext() = default;
    virtual void makeCurrent() = 0;  // on the worker, before its first GL call
    virtual void release() = 0;      // on the worker, after its last
};

// An OSMesa context made on the worker: for a Lab whose own context is OSMesa (the tests).
std::unique_ptr<WorkerContext> headlessWorkerContext();

// The picture to show, composed from a result on the worker (Lab composes its view), and what
// of the student's cannot be shown honestly.
struct ComposedView {
    Image image;
    int nanCount = 0, infCount = 0;
};
struct EvaluationResult;

// Everything one evaluation depends on, copied: the UI thread goes on editing its own.
struct EvaluationJob {
    const LoadedModule* module = nullptr;  // the registry outlives the worker
    ParamValues params;
    Scene scene;  // with the state's camera
    IblSettings ibl;
    // --error-budget (> 0), when the window has no settings for the environment yet: the
    // worker chooses them first (chooseIblSettings, 0.6-0.8 s measured) and renders with them
    // instead of `ibl`; the result brings the choice.
    double errorBudget = 0;
    std::filesystem::path submission;
    bool student = false;  // the student's file exists and may be read: render it too
    int side = 0;          // the picture's width and height
    // The environment's maps the window's renderer holds (LabRenderer::environmentMapsBuilt):
    // the result brings the worker's when it has built more (-1: never).
    int environmentMapsHeld = -1;
    // Run on the worker after the evaluation, when the solution's rendered (empty: not run).
    std::function<ComposedView(const EvaluationResult&)> compose;
};

// --error-budget's settings for an environment, as `pbrlab precompute --error-budget` chooses
// them, and the line that says how they meet it (or why the defaults are used).
struct BudgetChoice {
    std::string environment;
    IblSettings settings;
    std::string summary;
};

struct EvaluationResult {
    unsigned generation = 0;
    std::optional<BudgetChoice> budgetChoice;  // EvaluationJob::errorBudget's
    std::string renderError;  // the solution's evaluation failed (its fields are empty)
    Image solutionValue, referenceValue, probeSolution;
    // The site withholds the step's solution (an assignment's page, contract.h): the solution's
    // picture and probe are the CPU reference's, and solutionStats are the student's file's.
    bool solutionWithheld = false;
    // The G-buffer's inputs, one per pixel (shared with the worker, which keeps the last
    // solution's: KeptSolution).
    std::shared_ptr<const std::vector<Surface>> surfaces;
    Comparison solutionStats;
    bool solutionKept = false;  // the fields above are the last evaluation's (the same inputs)
    double solutionMs = 0;      // the solution's view pass and read-back at full size (LiveSize)
    // The student's file: each failed attempt's message in order (a new file that does not
    // compile fails twice, then renders with the last good programs), then whether it rendered.
    std::vector<std::string> studentErrors;
    bool studentRendered = false;
    Image studentValue, probeStudent;
    Comparison studentStats;
    double milliseconds = 0;                // the whole evaluation, on the worker
    std::vector<CompiledProgram> compiled;  // the worker's programs so far, in order
    std::optional<ComposedView> composed;   // EvaluationJob::compose's
    // The maps of the job's environment, when the worker built more than the window held:
    // the window's renderer takes them instead of building them in a frame.
    std::string environment;
    std::shared_ptr<const IblMapImages> environmentMaps;
};

// Where the job running is, for the progress line under the picture.
struct EvaluationProgress {
    bool running = false;
    int stage = 0, stages = 0;  // 1-based
    std::string what;           // the stage's picture, in words
    double seconds = 0;         // since the job started
};

// Whether the evaluation runs on a thread of its own. A page without shared memory has one
// thread: there the worker runs each job in the window's context, inside the frame after the
// one that posted it (which draws the progress line), and the window waits for it.
constexpr bool kEvaluationThread = kThreads;

// The evaluation's context in a page: the window's own, already current.
std::unique_ptr<WorkerContext> windowsOwnContext();

class EvaluationWorker {
public:
    // `drawMs`: the longest one of its draws may take (FrameEconomies::evaluationDrawMs).
    EvaluationWorker(DataPaths paths, std::unique_ptr<WorkerContext> context, double drawMs);
    EvaluationWorker(const EvaluationWorker&) = delete;
    EvaluationWorker& operator=(const EvaluationWorker&) = delete;
    ~EvaluationWorker();  // the job running stops at its next stage; the thread ends

    // Starts this job when the worker is free, replacing one not started; the one running is
    // superseded. Returns its generation.
    unsigned post(EvaluationJob job);
    // The input changed: the job running stops at its next stage, and none is delivered.
    void cancel();
    // The latest job's result, once, when it has finished. Without a thread, a job posted
    // before the last take() runs here first, unless `runPending` is false (the student holds
    // the mouse button down: the job would stop the page for the drag that follows).
    std::optional<EvaluationResult> take(bool runPending = true);
    // Blocks until the latest job has finished, and returns its result (--orbit's baseline).
    EvaluationResult wait();
    // A job is posted whose result has not been taken (and which was not cancelled).
    bool busy() const;
    EvaluationProgress progress() const;
    // Without a thread, the jobs run in the window's context: with the window's renderer
    // (Lab's), whose programs and maps the live pictures then share, instead of a second
    // renderer compiling and precomputing them again in the same context (a step's first drag
    // compiled its live programs in its first frames).
    void runWith(LabRenderer& windowsRenderer) {
        hereRenderer_ = &windowsRenderer;
        windowsRenderer_ = true;
    }
    // Without a thread, the job running yields to the student when `inputWaiting` says a press
    // or a key waits (a page: navigator.scheduling.isInputPending): it stops at its next point
    // of the CPU reference or its next stage, is dropped, and takeYielded() says so once; the
    // window posts it again when the input is still. A student who grabs the picture again while it
    // settles turns it at once, instead of after the evaluation (1.1-1.4 s for ndf). At most
    // kYieldsInARow times without a result or a change (cancel): clicks that change nothing cannot
    // keep a long evaluation (irradiance's 12-15 s) from ever finishing.
    void yieldWhen(std::function<bool()> inputWaiting) { inputWaiting_ = std::move(inputWaiting); }
    bool takeYielded() { return std::exchange(yielded_, false); }
    static constexpr int kYieldsInARow = 3;

private:
    void loop();
    // The job, run: its result kept unless superseded, or the host's error (`renderer` null:
    // startError says why).
    void runJob(LabRenderer* renderer, const std::string& startError, const EvaluationJob& job,
                unsigned generation);
    // Without a thread: the pending job, run now when it was posted before the last take().
    void runPendingHere();
    // The job's stages; empty when a newer generation superseded it between two.
    std::optional<EvaluationResult> run(LabRenderer& renderer, const EvaluationJob& job,
                                        unsigned generation);
    void runSolution(LabRenderer& renderer, const EvaluationJob& job, const IblSettings& ibl,
                     unsigned generation, int& stage, int stages, EvaluationResult& r, Band& band);
    bool evaluateSolution(LabRenderer& renderer, const EvaluationJob& job, const IblSettings& ibl,
                          unsigned generation, int& stage, int stages, EvaluationResult& r,
                          Band& band, const Band*& studentBand);
    bool renderStudent(LabRenderer& renderer, const EvaluationJob& job, const IblSettings& ibl,
                       unsigned generation, int stage, int stages, const Band& band,
                       EvaluationResult& r);
    bool superseded(unsigned generation) const { return generation != latest_.load(); }
    // What the CPU reference asks between points, and each stage before it starts:
    // superseded, or (without a thread) yielding to the student's input.
    bool stopRequested(unsigned generation);
    void enter(int stage, int stages, const char* what);
    const BudgetChoice& chooseForBudget(LabRenderer& renderer, const std::string& environment,
                                        double budget);

    DataPaths paths_;
    std::unique_ptr<WorkerContext> context_;
    double drawMs_;  // the longest one draw of the evaluation may take (0: no limit)
    std::atomic<unsigned> latest_{0};  // the newest post or cancel
    mutable std::mutex mutex_;         // everything below
    std::condition_variable changed_;
    std::optional<EvaluationJob> pending_;  // posted, not started (generation: latest_)
    std::optional<EvaluationResult> result_;
    bool wanted_ = false;  // the latest generation is a job whose result is not taken yet
    bool stop_ = false;
    EvaluationProgress progress_;
    std::chrono::steady_clock::time_point started_;
    // The worker's own: choices already made, kept when the job that made one was superseded.
    std::map<std::pair<std::string, double>, BudgetChoice> budgetChoices_;
    // The worker's own: the last solution's band, which a student's edit reuses (the edit
    // changes GLSL only: the band is what the CPU reference says), also where no solution's
    // stage is kept (a withheld step's picture is the student's file, its band is not).
    BandCache bandCache_;
    // The worker's own: the last solution's stage (its picture, the reference's band on it,
    // its probe), which the next evaluation on the same inputs takes instead of drawing and
    // reading back the picture again: after a student's edit, only the student's file changed.
    struct KeptSolution {
        std::uint64_t inputs = 0;  // solutionInputs()
        Image solutionValue, referenceValue, probeSolution;
        std::shared_ptr<const std::vector<Surface>> surfaces;
        Band band;
        Comparison solutionStats;
        double solutionMs = 0;
        std::vector<std::shared_ptr<const ModelData>> models;  // the scene's, held
    };
    std::optional<KeptSolution> keptSolution_;
    // Without a thread: the renderer (runWith's, else made at the first job), and whether
    // take() has seen the pending job once (the frame that saw it drew the progress line).
    LabRenderer* hereRenderer_ = nullptr;
    std::unique_ptr<LabRenderer> ownRenderer_;
    bool windowsRenderer_ = false;  // runWith's: the maps built are the window's already
    bool pendingSeen_ = false;
    std::function<bool()> inputWaiting_;  // yieldWhen's
    int yieldsLeft_ = kYieldsInARow;
    bool yielded_ = false;  // the last job stopped for the student's input (takeYielded)
    std::thread thread_;    // last: started once the members above exist (kEvaluationThread)
};

}  // namespace pbrlab
