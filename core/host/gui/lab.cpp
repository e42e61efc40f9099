#include "lab.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "platform.h"
#include "term_views.h"
#include "util/error.h"
#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

std::string describeDirs(const std::vector<fs::path>& dirs) {
    std::string text;
    for (const fs::path& dir : dirs) text += (text.empty() ? "" : ", ") + dir.string();
    return text;
}

// The index of step `id`; throws, listing the known ids, when there is none.
int indexOf(const ModuleRegistry& registry, const std::string& id) {
    const auto& ms = registry.modules();
    for (size_t i = 0; i < ms.size(); ++i)
        if (ms[i].desc->id == id) return int(i);
    registry.find(id);  // throws, listing the known ids
    return 0;
}

// The side tabs, as --tab names them.
const std::vector<std::string> kTabs = {"handout", "plot", "log", "programs", "console"};

}  // namespace

Lab::Lab(const GuiOptions& options, GuiState& state, std::unique_ptr<WorkerContext> workerContext)
    : options_(options) {
    paths_ = DataPaths::locate();
    registry_ = std::make_unique<ModuleRegistry>(options.modulesDirs);
    termViews_ = pbrlab::termViews(*registry_);
    for (const auto& f : registry_->failures())
        shown_.messages += "module " + f.library.string() + " not loaded: " + f.reason + "\n";
    if (registry_->modules().empty())
        throw Error("no step libraries in " + describeDirs(options.modulesDirs));
    renderer_ = std::make_unique<LabRenderer>(paths_);
    submission_ = options.submission;
    if (submission_.empty()) {
        for (const auto& m : registry_->modules())
            if (fs::exists(fs::current_path() / (m.desc->id + ".glsl")))
                submission_ = fs::current_path();
    }
    badges_ = std::make_unique<Badges>(options.modulesDirs, submission_);
    for (const auto& m : registry_->modules())
        state.params[m.desc->id] = ParamValues(m.desc->params);
    select(state, 0);
    const RememberedChoice remembered = restoreState(*registry_, state, shown_.messages);
    for (const auto& [id, view] : options.chosenViews) state.chosenViews[id] = view;
    if (!remembered.step.empty() && options.module.empty())
        for (size_t i = 0; i < registry_->modules().size(); ++i)
            if (registry_->modules()[i].desc->id == remembered.step) select(state, int(i));
    if (!options.module.empty()) select(state, indexOf(*registry_, options.module));
    // The command line wins over the remembered model: --scene alone shows that scene,
    // --model the model (lit like --scene when both are given, as `pbrlab render` does).
    if (!options.scene.empty() || !options.model.empty()) {
        state.sceneName = options.scene;
        state.model = options.model.empty() ? fs::path() : canonicalFile(options.model);
    } else {
        state.model = remembered.model;
    }
    if (!state.sceneName.empty() || !state.model.empty()) loadScene(state);
    for (const auto& s : options.sets)
        applyAssignment(module(state).params, state.params[module(state).id], s);
    if (!options.view.empty()) parseView(options.view, termViews_, state.view, state.term);
    if (!options.tab.empty() && std::find(kTabs.begin(), kTabs.end(), options.tab) == kTabs.end())
        throw Error("--tab " + options.tab +
                    ": unknown tab; one of handout, plot, log, programs, console");
    state.openTab = options.tab;
    if (options.view.empty()) showChosenView(state);
    shown_.imageTexture = gl::makeTexture();
    displayPass_ = std::make_unique<DisplayPass>(renderer_->programs(), paths_.shaders());
    worker_ = std::make_unique<EvaluationWorker>(paths_, std::move(workerContext),
                                                 options_.economies.evaluationDrawMs());
    if (!kEvaluationThread) worker_->runWith(*renderer_);
    if (std::function<bool()> pending = platform::inputPending()) worker_->yieldWhen(pending);
}

fs::path Lab::studentFile(const GuiState& state) const {
    return submission_.empty() ? fs::path() : submission_ / (module(state).id + ".glsl");
}

// The step's view: the one the student chose for it, else their picture when their file
// exists, else the solution's.
void Lab::showChosenView(GuiState& state) const {
    const auto chosen = state.chosenViews.find(module(state).id);
    if (chosen != state.chosenViews.end()) {
        try {
            parseView(chosen->second, termViews_, state.view, state.term);
            return;
        } catch (const Error&) {
            // A view this build does not have (a term view of an older version): the default.
        }
    }
    const fs::path file = studentFile(state);
    state.view = !file.empty() && fs::exists(file) ? View::Student : View::Solution;
}

void Lab::select(GuiState& state, int index) {
    state.step = std::clamp(index, 0, int(registry_->modules().size()) - 1);
    state.sceneName.clear();
    state.plotRow = module(state).probe.height / 2;
    studentWatch_.forget();
    showCompile(module(state).id);
    live_.reset();  // another view, another cost (render() measures it)
    loadScene(state);
    std::ifstream in(loaded(state).sourceDir / "README.md");
    std::stringstream s;
    s << in.rdbuf();
    shown_.handout = s.str();
}

// The chosen scene (default: the step's own), or a glTF model framed and lit like it.
void Lab::loadScene(GuiState& state) {
    std::string name = state.sceneName.empty() ? module(state).scene : state.sceneName;
    try {
        Scene scene = pbrlab::loadScene(paths_.scene(name));
        if (!state.model.empty()) scene = sceneForModel(scene, state.model);
        noteModelWarnings(scene);  // a JSON scene may hold models too
        shown_.scene = std::move(scene);
        shownSceneName_ = state.sceneName;
        shownModel_ = state.model;
        shown_.sceneError.clear();
    } catch (const Error& e) {
        // Keep the previous scene on screen, and the chooser (and the saved state) on it,
        // so a broken file is neither remembered nor half-shown.
        shown_.sceneError = e.what();
        state.sceneName = shownSceneName_;
        state.model = shownModel_;
        logLine("scene", shown_.sceneError);
    }
    const Camera& camera = shown_.scene.camera;
    glm::dvec3 offset = camera.position - camera.target;
    state.camera.distance = glm::length(offset);
    state.camera.yaw = std::atan2(offset.x, offset.z);
    state.camera.pitch = std::asin(std::clamp(offset.y / state.camera.distance, -1.0, 1.0));
    dirty_ = true;
    if (worker_) worker_->cancel();  // another step or scene: the evaluation running is not it
}

// What the model loader read but does not render goes to the host log (the Log tab), once
// per file.
void Lab::noteModelWarnings(const Scene& scene) {
    for (const SceneModel& m : scene.models)
        if (warnedModels_.insert(m.data->file).second)
            for (const std::string& w : m.data->warnings)
                logLine("model", m.data->file.string() + ": " + w);
}

Scene Lab::currentScene(const GuiState& state) const {
    Scene s = shown_.scene;
    const OrbitCamera& c = state.camera;
    s.camera.position =
        s.camera.target + c.distance * glm::dvec3(std::cos(c.pitch) * std::sin(c.yaw),
                                                  std::sin(c.pitch),
                                                  std::cos(c.pitch) * std::cos(c.yaw));
    return s;
}

// The IBL settings of every request for this scene: --error-budget's choice for its
// environment (made on the evaluation thread, the first time it is shown), else the defaults.
IblSettings Lab::iblFor(const Scene& scene) const {
    const auto chosen = budgetSettings_.find(scene.environment);
    return chosen != budgetSettings_.end() ? chosen->second : IblSettings();
}

bool Lab::waitsForBudgetSettings(const Scene& scene) const {
    return options_.errorBudget > 0 && !budgetSettings_.count(scene.environment);
}

}  // namespace pbrlab
