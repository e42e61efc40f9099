#include "gui.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "converge.h"
#include "display_pass.h"
#include "evaluate.h"
#include "gl/context.h"
#include "grade.h"
#include "handout.h"
#include "pbrlab/contract.h"
#include "pbrlab/display.h"
#include "pbrlab/error.h"
#include "pbrlab/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

constexpr int kRenderSize = 512;  // the lab image; scaled to fit the window
// How long the input must be still before the full evaluation runs (the live view until then).
constexpr std::chrono::milliseconds kSettleDelay{200};
// The live picture's time budget: its side shrinks (to 128 at least) while a frame of it takes
// longer, and grows back (to kRenderSize) while it takes much less, so that dragging stays at
// 30 frames a second or more whatever the step costs per pixel. The settled image is full size.
constexpr double kLiveBudgetMs = 18;

enum class Status { Unknown, Missing, CompileError, Passes, Fails };

const char* statusBadge(Status s) {
    switch (s) {
        case Status::Missing:
            return "missing";
        case Status::CompileError:
            return "compile error";
        case Status::Passes:
            return "passes";
        case Status::Fails:
            return "fails";
        default:
            return "...";
    }
}

ImVec4 statusColor(Status s) {
    switch (s) {
        case Status::Passes:
            return {0.35f, 0.85f, 0.4f, 1};
        case Status::Fails:
            return {1.0f, 0.55f, 0.2f, 1};
        case Status::CompileError:
            return {1.0f, 0.3f, 0.3f, 1};
        default:
            return {0.6f, 0.6f, 0.6f, 1};
    }
}

// The views: four images, a comparison, and term views computed from the G-buffer on the CPU.
const std::vector<std::string> kViews = {
    "student",  "solution", "reference", "difference",    "split",   "albedo", "roughness",
    "metallic", "ao",       "normal",    "mapped normal", "N.L",     "D",      "G",
    "F",        "kS",       "kD",        "diffuse",       "specular"};
constexpr int kFirstTermView = 5;

// The side tabs, as --tab names them.
const std::vector<std::string> kTabs = {"handout", "plot", "log", "programs"};

struct ModuleState {
    ParamValues params;
    Status status = Status::Unknown;
    std::string gradeMessage;  // why the badge says "fails": the grader's message
    fs::file_time_type stamp{};
    bool stampKnown = false;
};

std::string describeDirs(const std::vector<fs::path>& dirs) {
    std::string text;
    for (const fs::path& dir : dirs) text += (text.empty() ? "" : ", ") + dir.string();
    return text;
}

fs::path configFile() {
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    const char* home = std::getenv("HOME");
    fs::path base = xdg && *xdg ? fs::path(xdg) : fs::path(home ? home : ".") / ".config";
    return base / "pbrlab" / "gui.json";
}

// Model files are compared (chooser entries, --model, the saved choice) as absolute,
// canonical paths, so one file is one entry however it was named.
fs::path canonicalFile(const fs::path& file) {
    std::error_code ec;
    fs::path absolute = fs::absolute(file, ec);
    if (ec) return file;
    fs::path canonical = fs::weakly_canonical(absolute, ec);
    return ec ? absolute : canonical;
}

// A small 2D pad for directions: the disk is the hemisphere seen from +z (towards the
// viewer); dragging sets x and y, z follows on the chosen side.
bool directionPad(const char* id, glm::dvec3& dir) {
    const float radius = 52;
    ImVec2 origin = ImGui::GetCursorScreenPos();
    ImVec2 centre(origin.x + radius, origin.y + radius);
    ImGui::InvisibleButton(id, ImVec2(2 * radius, 2 * radius));
    bool changed = false;
    if (ImGui::IsItemActive()) {
        ImVec2 m = ImGui::GetIO().MousePos;
        glm::dvec2 p((m.x - centre.x) / radius, -(m.y - centre.y) / radius);
        if (glm::length(p) > 1) p = glm::normalize(p);
        double z = std::sqrt(std::max(0.0, 1 - glm::dot(p, p)));
        dir = glm::dvec3(p, dir.z < 0 ? -z : z);
        changed = true;
    }
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddCircleFilled(centre, radius, IM_COL32(40, 44, 52, 255));
    dl->AddCircle(centre, radius, IM_COL32(120, 120, 130, 255));
    dl->AddLine(ImVec2(centre.x - radius, centre.y), ImVec2(centre.x + radius, centre.y),
                IM_COL32(70, 70, 80, 255));
    dl->AddLine(ImVec2(centre.x, centre.y - radius), ImVec2(centre.x, centre.y + radius),
                IM_COL32(70, 70, 80, 255));
    ImVec2 dot(centre.x + float(dir.x) * radius, centre.y - float(dir.y) * radius);
    if (dir.z >= 0)
        dl->AddCircleFilled(dot, 5, IM_COL32(255, 210, 90, 255));
    else
        dl->AddCircle(dot, 5, IM_COL32(255, 210, 90, 255), 12, 2);
    return changed;
}

class GuiApp {
public:
    explicit GuiApp(const GuiOptions& options) : options_(options) {
        context_ = createWindowContext(options.width, options.height, "pbrlab");
        paths_ = DataPaths::locate();
        registry_ = std::make_unique<ModuleRegistry>(options.modulesDirs);
        for (const auto& f : registry_->failures())
            messages_ += "module " + f.library.string() + " not loaded: " + f.reason + "\n";
        if (registry_->modules().empty())
            throw Error("no step libraries in " + describeDirs(options.modulesDirs));
        renderer_ = std::make_unique<LabRenderer>(paths_);
        submission_ = options.submission;
        if (submission_.empty()) {
            for (const auto& m : registry_->modules())
                if (fs::exists(fs::current_path() / (m.desc->id + ".glsl")))
                    submission_ = fs::current_path();
        }
        for (const auto& m : registry_->modules())
            states_[m.desc->id].params = ParamValues(m.desc->params);
        select(0);
        fs::path rememberedModel = loadState();
        if (!options.module.empty()) select(indexOf(options.module));
        // The command line wins over the remembered model: --scene alone shows that scene,
        // --model the model (lit like --scene when both are given, as `pbrlab render` does).
        if (!options.scene.empty() || !options.model.empty()) {
            sceneName_ = options.scene;
            model_ = options.model.empty() ? fs::path() : canonicalFile(options.model);
        } else {
            model_ = rememberedModel;
        }
        if (!sceneName_.empty() || !model_.empty()) loadScene();
        for (const auto& s : options.sets) applyAssignment(module().params, state().params, s);
        if (!options.view.empty()) {
            auto it = std::find(kViews.begin(), kViews.end(), options.view);
            if (it == kViews.end()) {
                std::string known;
                for (const auto& v : kViews) known += (known.empty() ? "" : ", ") + v;
                throw Error("--view " + options.view + ": unknown view; one of " + known);
            }
            view_ = int(it - kViews.begin());
        }
        if (!options.tab.empty() &&
            std::find(kTabs.begin(), kTabs.end(), options.tab) == kTabs.end())
            throw Error("--tab " + options.tab +
                        ": unknown tab; one of handout, plot, log, programs");
        openTab_ = options.tab;
        if (options_.view.empty() && !studentFile().empty() && fs::exists(studentFile()))
            view_ = 0;
        else if (options_.view.empty())
            view_ = 1;  // no student file: show the solution

        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // the layout is computed, not saved
        loadFont();
        styleUi();
        ImGui_ImplGlfw_InitForOpenGL(context_->window(), true);
        ImGui_ImplOpenGL3_Init("#version 450 core");
        imageTexture_ = gl::makeTexture();
        displayPass_ = std::make_unique<DisplayPass>(renderer_->programs(), paths_.shaders());
    }

    ~GuiApp() {
        if (badgeJob_.pid > 0) {  // a badge still grading: not needed any more
            kill(badgeJob_.pid, SIGKILL);
            waitpid(badgeJob_.pid, nullptr, 0);
            std::error_code ec;
            fs::remove(badgeJob_.json, ec);
        }
        saveState();
        imageTexture_.reset();
        displayPass_.reset();
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }

    int run() {
        GLFWwindow* window = context_->window();
        int frame = 0;
        std::vector<double> frameTimes, renderTimes;
        int w = 0, h = 0;
        while (!glfwWindowShouldClose(window)) {
            glfwPollEvents();
            auto start = std::chrono::steady_clock::now();
            if (options_.orbit) {
                yaw_ += 0.02;
                moved();
            }
            update();
            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            drawUi();
            ImGui::Render();
            glfwGetFramebufferSize(window, &w, &h);
            gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
            gl::Viewport(0, 0, w, h);
            gl::ClearColor(0.08f, 0.08f, 0.09f, 1);
            gl::Clear(GL_COLOR_BUFFER_BIT);
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            ++frame;
            bool last = options_.frames > 0 && frame >= options_.frames;
            if (screenshotRequested_ || (last && !options_.screenshot.empty())) {
                fs::path file = last && !options_.screenshot.empty()
                                    ? options_.screenshot
                                    : fs::path("pbrlab-screenshot.png");
                saveScreenshot(file, w, h);
                screenshotRequested_ = false;
            }
            glfwSwapBuffers(window);
            frameMs_ =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
            frameTimes.push_back(frameMs_);
            renderTimes.push_back(renderMs_);
            if (last) break;
        }
        if (options_.orbit) {
            printFrameTimes("frame", frameTimes, w, h);
            std::vector<int> sizes = liveSizes_;
            std::sort(sizes.begin(), sizes.end());
            const int side = sizes.empty() ? 0 : sizes[sizes.size() / 2];
            printFrameTimes("  of which the picture (median side)", renderTimes, side, side);
            // The baseline, in the same run: the settled frame, what every frame cost before
            // the live view (the picture at full size, read back and evaluated on the CPU).
            const auto start = std::chrono::steady_clock::now();
            render();
            const double settledMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count();
            std::vector<double> live(
                frameTimes.begin() + std::min<std::ptrdiff_t>(3, std::ptrdiff_t(frameTimes.size())),
                frameTimes.end());
            std::sort(live.begin(), live.end());
            if (!live.empty())
                std::printf(
                    "settled frame (%dx%d, evaluated against the CPU reference): %.1f ms; "
                    "live frame median / settled: %.3f\n",
                    kRenderSize, kRenderSize, settledMs, live[live.size() / 2] / settledMs);
        }
        return 0;
    }

private:
    // The first frames compile programs (llvmpipe compiles at first draw): left out.
    static void printFrameTimes(const char* what, std::vector<double> ms, int w, int h) {
        const size_t warmup = std::min<size_t>(3, ms.size());
        if (warmup > 0) {
            std::printf("%s: the first %zu frames (compiles, precompute), ms:", what, warmup);
            for (size_t i = 0; i < warmup; ++i) std::printf(" %.0f", ms[i]);
            std::printf("\n");
        }
        ms.erase(ms.begin(), ms.begin() + std::ptrdiff_t(warmup));
        if (ms.empty()) return;
        std::sort(ms.begin(), ms.end());
        const double median = ms[ms.size() / 2];
        const double p95 = ms[std::min(ms.size() - 1, size_t(0.95 * double(ms.size())))];
        std::printf(
            "%s: %zu frames at %dx%d (after %zu warm-up): median %.1f ms, 95th percentile %.1f "
            "ms\n",
            what, ms.size(), w, h, warmup, median, p95);
    }

    // ---- state ------------------------------------------------------------------------------
    const LoadedModule& loaded() const { return registry_->modules()[size_t(current_)]; }
    const ModuleDesc& module() const { return *loaded().desc; }
    ModuleState& state() { return states_[module().id]; }
    int indexOf(const std::string& id) const {
        const auto& ms = registry_->modules();
        for (size_t i = 0; i < ms.size(); ++i)
            if (ms[i].desc->id == id) return int(i);
        registry_->find(id);  // throws, listing the known ids
        return 0;
    }
    void select(int index) {
        current_ = std::clamp(index, 0, int(registry_->modules().size()) - 1);
        sceneName_.clear();
        plotRow_ = module().probe.height / 2;
        lastStudentStamp_ = {};
        loadScene();
        handout_.clear();
        std::ifstream in(loaded().sourceDir / "README.md");
        std::stringstream s;
        s << in.rdbuf();
        handout_ = s.str();
    }
    fs::path studentFile() const {
        return submission_.empty() ? fs::path() : submission_ / (module().id + ".glsl");
    }
    StudentSource studentSource() const { return {submission_, false}; }

    // The chosen scene (default: the step's own), or a glTF model framed and lit like it.
    void loadScene() {
        if (registry_->modules().empty()) return;
        std::string name = sceneName_.empty() ? module().scene : sceneName_;
        try {
            Scene scene = pbrlab::loadScene(paths_.scene(name));
            if (!model_.empty()) scene = sceneForModel(scene, model_);
            noteModelWarnings(scene);  // a JSON scene may hold models too
            scene_ = std::move(scene);
            shownSceneName_ = sceneName_;
            shownModel_ = model_;
            sceneError_.clear();
        } catch (const Error& e) {
            // Keep the previous scene on screen, and the chooser (and the saved state) on it,
            // so a broken file is neither remembered nor half-shown.
            sceneError_ = e.what();
            sceneName_ = shownSceneName_;
            model_ = shownModel_;
            logLine("scene", sceneError_);
        }
        glm::dvec3 offset = scene_.camera.position - scene_.camera.target;
        distance_ = glm::length(offset);
        yaw_ = std::atan2(offset.x, offset.z);
        pitch_ = std::asin(std::clamp(offset.y / distance_, -1.0, 1.0));
        dirty_ = true;
    }

    // What the model loader read but does not render goes to the host log (the Log tab),
    // once per file.
    void noteModelWarnings(const Scene& scene) {
        for (const SceneModel& m : scene.models)
            if (warnedModels_.insert(m.data->file).second)
                for (const std::string& w : m.data->warnings)
                    logLine("model", m.data->file.string() + ": " + w);
    }

    Scene currentScene() const {
        Scene s = scene_;
        s.camera.position =
            s.camera.target + distance_ * glm::dvec3(std::cos(pitch_) * std::sin(yaw_),
                                                     std::sin(pitch_),
                                                     std::cos(pitch_) * std::cos(yaw_));
        return s;
    }

    // Restores the module and parameters; returns the remembered model (empty: none), which
    // the constructor loads unless the command line names a scene or model.
    fs::path loadState() {
        std::ifstream in(configFile());
        if (!in) return {};
        fs::path model;
        try {
            nlohmann::json j = nlohmann::json::parse(in);
            if (j.contains("model")) model = j["model"].get<std::string>();
            const nlohmann::json& all = j.contains("params") ? j["params"] : nlohmann::json();
            if (!all.is_object()) return model;
            for (auto& [id, params] : all.items()) {
                auto it = states_.find(id);
                if (it == states_.end()) continue;
                for (auto& [name, value] : params.items()) try {
                        applyAssignment(registry_->find(id).desc->params, it->second.params,
                                        name + "=" + value.get<std::string>());
                    } catch (const std::exception&) {
                        // A value from an older version of the module: keep the default.
                    }
            }
            if (j.contains("module") && options_.module.empty()) {
                std::string id = j["module"].get<std::string>();
                for (size_t i = 0; i < registry_->modules().size(); ++i)
                    if (registry_->modules()[i].desc->id == id) select(int(i));
            }
        } catch (const std::exception& e) {
            messages_ += configFile().string() + ": ignored (" + e.what() + ")\n";
        }
        return model;
    }

    void saveState() const {
        nlohmann::json j;
        j["module"] = module().id;
        if (!model_.empty()) j["model"] = model_.string();  // the model stays across steps
        for (const auto& m : registry_->modules())
            for (const auto& p : m.desc->params)
                j["params"][m.desc->id][p.name] =
                    p.format(states_.at(m.desc->id).params.vector(p.name));
        std::error_code ec;
        fs::create_directories(configFile().parent_path(), ec);
        fs::path tmp = configFile();
        tmp += ".tmp";
        std::ofstream(tmp) << j.dump(2);
        fs::rename(tmp, configFile(), ec);
    }

    // ---- work between frames ----------------------------------------------------------------
    void update() {
        // Hot reload: a saved student file marks the view dirty; the renderer recompiles it.
        if (!studentFile().empty()) {
            std::error_code ec;
            auto stamp = fs::last_write_time(studentFile(), ec);
            if (!ec && stamp != lastStudentStamp_) {
                lastStudentStamp_ = stamp;
                dirty_ = true;
            }
        }
        // The first render of an environment precomputes for seconds: show a frame that says so.
        if (dirty_ && (module().needs & NeedsEnvironment) &&
            !renderer_->hasEnvironmentMaps(currentScene(), iblFor(currentScene())) &&
            !precomputeNoticeShown_) {
            precomputeNoticeShown_ = true;
            return;
        }
        precomputeNoticeShown_ = false;
        if (module().needs & NeedsEnvironment) useBudgetSettings(currentScene());
        // While the input moves, only the picture is drawn (on the GPU, mapped for display
        // there, nothing read back): 30 frames a second at least. The evaluation against the
        // CPU reference, the probes and the statistics follow once it has been still for a
        // moment (dirty_ stays set until then).
        const bool moving = std::chrono::steady_clock::now() - lastMove_ < kSettleDelay;
        if (dirty_ && moving)
            drawLive();
        else if (dirty_)
            render();
        updateOneStatus();
    }

    // --error-budget: the settings chosen for this scene's environment (measured the first time
    // it is shown, as `pbrlab precompute --error-budget` measures them) go into its requests.
    void useBudgetSettings(const Scene& scene) {
        if (options_.errorBudget <= 0) return;
        if (!budgetSettings_.count(scene.environment)) {
            try {
                const Image equirect =
                    loadEnvironmentImage(scene.environment, renderer_->cacheRoot());
                IblTruth truth(equirect);
                IblPrecompute precompute(renderer_->programs(), paths_.shaders(), paths_.labs());
                const IblDiskCache cache(renderer_->cacheRoot());
                const IblChoice choice =
                    chooseIblSettings(precompute, equirect, truth, options_.errorBudget,
                                      renderer_->cacheRoot().empty() ? nullptr : &cache);
                const IblErrors& e = choice.run.errors;
                char line[256];
                std::snprintf(line, sizeof line,
                              "error budget %g on %s: %s; mean errors irradiance %.4f, prefilter "
                              "%.4f, LUT %.4f",
                              options_.errorBudget, scene.environment.c_str(),
                              choice.met ? "met" : "NOT met (the most accurate settings)",
                              e.irradiance.mean, e.prefilter.mean, e.lut.mean);
                logLine("gui", std::string(line) + "; " + choice.settings.describe());
                budgetSettings_.emplace(scene.environment, choice.settings);
            } catch (const Error& e) {
                logLine("gui", std::string("error budget: ") + e.what());
                budgetSettings_.emplace(scene.environment, IblSettings());
            }
        }
    }

    // The IBL settings of every request for this scene: --error-budget's choice for its
    // environment, else the defaults.
    IblSettings iblFor(const Scene& scene) const {
        const auto chosen = budgetSettings_.find(scene.environment);
        return chosen != budgetSettings_.end() ? chosen->second : IblSettings();
    }

    // An input changed what is drawn (camera, parameter, light): a live frame now, the full
    // evaluation when it stops.
    void moved() {
        dirty_ = true;
        lastMove_ = std::chrono::steady_clock::now();
    }

    // The picture the student is looking at (theirs when their file has compiled, else the
    // solution's), rendered at the live size (kLiveBudgetMs) and mapped for display on the GPU.
    void drawLive() {
        const auto start = std::chrono::steady_clock::now();
        const Scene scene = currentScene();
        const bool student = view_ != 1 && !studentValue_.pixels.empty();
        try {
            RenderRequest request{
                &loaded(), &state().params, &scene,   student ? studentSource() : StudentSource{},
                nullptr,   liveSize_,       liveSize_};
            request.seamlessCubes = false;  // as the settled picture: no jump when it lands
            request.readValue = false;
            request.ibl = iblFor(scene);
            const RenderResult r = renderer_->render(request);
            liveTexture_ = displayPass_->run(r.valueTexture, liveSize_, liveSize_, module().display,
                                             module().components);
            liveWho_ = student ? "your" : "the solution's";
        } catch (const Error& e) {
            render();  // a program that does not compile: the full path says why
            return;
        }
        renderMs_ =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        liveSizes_.push_back(liveSize_);
        // Resized at most every 4 frames, from the slowest of them (a new size reallocates
        // the targets; one slow frame is not a trend), with a gap between shrink and grow.
        liveWindow_.push_back(renderMs_);
        if (liveWindow_.size() < 4) return;
        const double slowest = *std::max_element(liveWindow_.begin(), liveWindow_.end());
        liveWindow_.clear();
        if (slowest > kLiveBudgetMs)
            liveSize_ = std::max(128, int(liveSize_ * 0.8) / 8 * 8);
        else if (slowest < 0.4 * kLiveBudgetMs)
            liveSize_ = std::min(kRenderSize, int(liveSize_ * 1.25) / 8 * 8);
    }

    void render() {
        dirty_ = false;
        liveTexture_ = 0;
        const LoadedModule& m = loaded();
        Scene scene = currentScene();
        ModuleState& st = state();
        auto start = std::chrono::steady_clock::now();
        // Views read cube maps as the CPU reference does (RenderRequest::seamlessCubes off),
        // so the statistics under the image are the ones `pbrlab check` grades with.
        try {
            EvalRequest request;
            request.render = {&m, &st.params, &scene, {}, nullptr, kRenderSize, kRenderSize};
            request.render.readSurfaces = true;
            request.render.seamlessCubes = false;
            request.render.ibl = iblFor(scene);
            Evaluation solution = evaluate(*renderer_, request);
            solutionValue_ = solution.render.value;
            surfaces_ = solution.render.surfaces;
            band_ = solution.band;
            solutionStats_ = solution.comparison;
            referenceValue_ = solution.render.value;
            for (size_t i = 0; i < band_.expected.size(); ++i)
                for (int c = 0; c < 3; ++c)
                    referenceValue_.pixels[i * 4 + size_t(c)] = float(band_.expected[i][c]);
            request.render.surfaces = nullptr;
            const std::vector<Surface> probe = probeSurfaces(module().probe);
            RenderRequest probeRequest{
                &m, &st.params, &scene, {}, &probe, module().probe.width, module().probe.height};
            probeRequest.seamlessCubes = false;
            probeRequest.ibl = iblFor(scene);
            probeSolution_ = renderer_->render(probeRequest).value;
            renderError_.clear();
        } catch (const Error& e) {
            renderError_ = e.what();
        }
        updatePermutation(applyParamBindings(scene, module(), st.params));
        hasStudent_ = !studentFile().empty() && fs::exists(studentFile());
        bool rendered = false;
        if (hasStudent_) {
            for (int attempt = 0; attempt < 2; ++attempt) {
                try {
                    RenderRequest request{&m,      &st.params,  &scene,     studentSource(),
                                          nullptr, kRenderSize, kRenderSize};
                    request.seamlessCubes = false;
                    request.ibl = iblFor(scene);
                    studentValue_ = renderer_->render(request).value;
                    studentStats_ =
                        compareWithBand(studentValue_, surfaces_, band_, module().components,
                                        module().nonNegative, module().tolerance.outlierFraction);
                    const std::vector<Surface> probe = probeSurfaces(module().probe);
                    RenderRequest probeRequest{&m,
                                               &st.params,
                                               &scene,
                                               studentSource(),
                                               &probe,
                                               module().probe.width,
                                               module().probe.height};
                    probeRequest.seamlessCubes = false;
                    probeRequest.ibl = iblFor(scene);
                    probeStudent_ = renderer_->render(probeRequest).value;
                    if (attempt == 0) compileLog_.clear();
                    rendered = true;
                    break;
                } catch (const ShaderError& e) {
                    // The new file does not compile: show the log, and render once more with
                    // the last good program (the cache kept it).
                    compileLog_ = e.what();
                    st.status = Status::CompileError;
                } catch (const Error& e) {
                    compileLog_ = e.what();
                    break;
                }
            }
        }
        // No version of the student's file has compiled yet: nothing of theirs to show.
        if (!rendered) studentValue_ = Image();
        renderMs_ =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        logLine("gui", "evaluated " + m.desc->id + " against the CPU reference in " +
                           std::to_string(int(renderMs_)) + " ms");
        compose();
    }

    // The programs this step needs for the scene on screen, as `pbrlab permutations` lists
    // them: one G-buffer define set per kind of material drawn (a map adds a HAS_*_MAP
    // define), and the view's (the student's file compiles with the same defines).
    void updatePermutation(const Scene& scene) {
        permutation_.clear();
        std::set<std::string> gbuffers;
        for (const DrawItem& item : drawItems(scene))
            gbuffers.insert(definesText(
                renderer_->gbufferRecipe(scene.materials.at(size_t(item.material)), module().needs)
                    .defines));
        for (const std::string& d : gbuffers) permutation_.insert({"G-buffer", d});
        ProgramRecipe view = renderer_->viewRecipe(loaded(), {}, false, int(scene.lights.size()));
        permutation_.insert({view.label, definesText(view.defines)});
    }

    // The badges are the grade: `pbrlab check ID --json`, the same gradeStep `pbrlab grade`
    // runs, in a process of its own (a step takes up to seconds to grade), one at a time; the
    // window polls it each frame and stays responsive.
    void updateOneStatus() {
        if (badgeJob_.pid > 0) {
            int status = 0;
            if (waitpid(badgeJob_.pid, &status, WNOHANG) == 0) return;  // still grading
            ModuleState& st = states_[badgeJob_.id];
            try {
                const nlohmann::json report = nlohmann::json::parse(std::ifstream(badgeJob_.json));
                const nlohmann::json& g = report.at("modules").at(0);
                const std::string result = g.at("status");
                st.status = result == "passed"          ? Status::Passes
                            : result == "compile_error" ? Status::CompileError
                                                        : Status::Fails;
                st.gradeMessage = g.value("message", "");
            } catch (const std::exception&) {
                st.status = Status::Fails;
                st.gradeMessage = "the grade did not finish";
            }
            std::error_code ec;
            fs::remove(badgeJob_.json, ec);
            dirty_ = dirty_ || badgeJob_.id == module().id;
            badgeJob_ = {};
        }
        const auto& ms = registry_->modules();
        for (size_t k = 0; k < ms.size(); ++k) {
            statusCursor_ = (statusCursor_ + 1) % ms.size();
            const LoadedModule& m = ms[statusCursor_];
            ModuleState& st = states_[m.desc->id];
            fs::path file = submission_.empty() ? fs::path() : submission_ / (m.desc->id + ".glsl");
            std::error_code ec;
            if (file.empty() || !fs::exists(file)) {
                st.status = Status::Missing;
                continue;
            }
            auto stamp = fs::last_write_time(file, ec);
            if (st.stampKnown && stamp == st.stamp) continue;
            st.stamp = stamp;
            st.stampKnown = true;
            st.status = Status::Unknown;
            startBadge(m.desc->id);
            return;
        }
    }

    void startBadge(const std::string& id) {
        badgeJob_.id = id;
        badgeJob_.json = fs::temp_directory_path() /
                         ("pbrlab-badge-" + std::to_string(getpid()) + "-" + id + ".json");
        const std::string exe = fs::read_symlink("/proc/self/exe").string();
        // The same step folders as this process (moduleDirs drops the ones given twice).
        std::vector<std::string> args = {exe};
        for (const fs::path& dir : options_.modulesDirs)
            args.insert(args.end(), {"--modules", dir.string()});
        args.insert(args.end(), {"check", id, "--submission", submission_.string(), "--json",
                                 badgeJob_.json.string()});
        std::vector<char*> argv;
        for (std::string& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t quiet;
        posix_spawn_file_actions_init(&quiet);
        posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&quiet, 2, "/dev/null", O_WRONLY, 0);
        pid_t pid = -1;
        if (posix_spawn(&pid, exe.c_str(), &quiet, nullptr, argv.data(), environ) != 0) pid = -1;
        posix_spawn_file_actions_destroy(&quiet);
        badgeJob_.pid = pid;
        if (pid < 0) {
            states_[id].status = Status::Fails;
            states_[id].gradeMessage = "could not start the grade (pbrlab check)";
            badgeJob_ = {};
        }
    }

    // ---- images -----------------------------------------------------------------------------
    Image termImage(int term) const {
        Image out = solutionValue_;
        for (size_t i = 0; i < surfaces_.size(); ++i) {
            const Surface& s = surfaces_[i];
            glm::dvec3 c(0);
            glm::dvec3 H = ref::halfwayVector(s.light, s.view);
            glm::dvec3 F0 = ref::baseReflectivity(s.albedo, s.metallic);
            glm::dvec3 F = ref::fresnelSchlick(std::max(glm::dot(H, s.view), 0.0), F0);
            glm::dvec3 radiance =
                ref::pointLightRadiance(s.lightColor, s.lightPosition, s.position);
            double NdotL = ref::lambertCosine(s.normal, s.light);
            glm::dvec3 kD = (1.0 - F) * (1.0 - s.metallic);
            switch (term) {
                case 0:
                    c = s.albedo;
                    break;
                case 1:
                    c = glm::dvec3(s.roughness);
                    break;
                case 2:
                    c = glm::dvec3(s.metallic);
                    break;
                case 3:
                    c = glm::dvec3(s.ao);
                    break;
                case 4:
                    c = 0.5 + 0.5 * s.normal;
                    break;
                case 5:
                    c = 0.5 + 0.5 * ref::normalFromMap(s.normal, s.tangent, s.normalTexel);
                    break;
                case 6:
                    c = glm::dvec3(NdotL);
                    break;
                case 7: {
                    double D = ref::distributionGGX(s.normal, H, s.roughness);
                    c = glm::dvec3(D / (1 + D));  // compresses the peak for display
                    break;
                }
                case 8:
                    c = glm::dvec3(ref::geometrySmith(s.normal, s.view, s.light, s.roughness));
                    break;
                case 9:
                case 10:
                    c = F;
                    break;
                case 11:
                    c = kD;
                    break;
                case 12:
                    c = kD * s.albedo / ref::kPi * radiance * NdotL;
                    break;
                case 13:
                    c = ref::cookTorranceSpecular(s.normal, s.view, s.light, F0, s.roughness) *
                        radiance * NdotL;
                    break;
            }
            if (term == 0 || term >= 12) {  // linear colours and radiance: encode for display
                Display hdr{term == 0 ? DisplayMode::LinearColor : DisplayMode::HdrColor};
                c = displayColor(glm::dvec4(c, 1), hdr, 3);
            }
            for (int k = 0; k < 3; ++k)
                out.pixels[i * 4 + size_t(k)] = s.covered ? float(c[k]) : 0.12f;
            out.pixels[i * 4 + 3] = 1;
        }
        return out;
    }

    void compose() {
        if (solutionValue_.pixels.empty()) return;
        const ModuleDesc& d = module();
        const Image& student = studentValue_.pixels.empty() ? solutionValue_ : studentValue_;
        Image shown;
        switch (view_) {
            case 0:
                shown = displayImage(student, d.display, d.components);
                break;
            case 1:
                shown = displayImage(solutionValue_, d.display, d.components);
                break;
            case 2:
                shown = displayImage(referenceValue_, d.display, d.components);
                break;
            case 3:
                shown = differenceImage(student, referenceValue_, d.components, diffRange_);
                break;
            case 4: {
                shown = displayImage(student, d.display, d.components);
                Image ref = displayImage(referenceValue_, d.display, d.components);
                int split = int(split_ * shown.width);
                for (int y = 0; y < shown.height; ++y)
                    for (int x = split; x < shown.width; ++x)
                        for (int c = 0; c < 4; ++c)
                            shown.at(x, y, c) = x == split ? 1.0f : ref.at(x, y, c);
                break;
            }
            default:
                shown = termImage(view_ - kFirstTermView);
                break;
        }
        // Count what cannot be shown honestly, for the warning line.
        nanCount_ = infCount_ = 0;
        for (size_t i = 0; i + 3 < student.pixels.size(); i += 4)
            for (int c = 0; c < d.components; ++c) {
                nanCount_ += std::isnan(student.pixels[i + size_t(c)]);
                infCount_ += std::isinf(student.pixels[i + size_t(c)]);
            }
        gl::BindTexture(GL_TEXTURE_2D, imageTexture_.id());
        gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        // Row 0 of the image is its top; ImGui draws uv (0,0) at the top-left: no flip.
        gl::TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, shown.width, shown.height, 0, GL_RGBA,
                       GL_FLOAT, shown.pixels.data());
        gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        imageWidth_ = shown.width;
        imageHeight_ = shown.height;
    }

    void saveScreenshot(const fs::path& file, int w, int h) {
        std::vector<unsigned char> rows(size_t(w) * h * 4);
        gl::BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        gl::ReadBuffer(GL_BACK);
        gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
        gl::ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
        Image image;
        image.width = w;
        image.height = h;
        image.channels = 3;
        image.pixels.resize(size_t(w) * h * 3);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int c = 0; c < 3; ++c)
                    image.at(x, y, c) = rows[(size_t(y) * w + x) * 4 + size_t(c)] / 255.0f;
        try {
            writeImage(file, flipRows(std::move(image)), FileDepth::Uint8, true);
            messages_ += "screenshot: " + file.string() + "\n";
            std::cout << "screenshot " << file.string() << " (" << w << "x" << h << ")\n";
        } catch (const Error& e) {
            messages_ += std::string(e.what()) + "\n";
        }
    }

    // ---- UI -------------------------------------------------------------------------------
    // The handouts use Greek letters and maths signs (α, θ, π, ≤, ≈, ·, ², −); ImGui's built-in
    // font has none of them. DejaVu Sans (Debian's fonts-dejavu-core) has all; without it the
    // built-in font is kept and those characters show as '?'.
    void loadFont() {
        static const ImWchar ranges[] = {0x0020, 0x00FF,  // Latin-1: ·, ², °, ×
                                         0x0370, 0x03FF,  // Greek
                                         0x2010, 0x205E,  // dashes, quotes, ′
                                         0x2070, 0x209F,  // super- and subscripts
                                         0x2190, 0x21FF,  // arrows
                                         0x2200, 0x22FF,  // maths operators
                                         0};
        const char* file = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
        if (fs::exists(file) &&
            ImGui::GetIO().Fonts->AddFontFromFileTTF(file, 15.0f, nullptr, ranges))
            return;
        messages_ += std::string("font ") + file + " not found: Greek letters show as '?'\n";
    }

    static void styleUi() {
        ImGui::StyleColorsDark();
        ImGuiStyle& s = ImGui::GetStyle();
        s.WindowRounding = 0;
        s.FrameRounding = 3;
        s.GrabRounding = 3;
        s.WindowBorderSize = 0;
        s.ItemSpacing = ImVec2(8, 6);
        s.Colors[ImGuiCol_WindowBg] = ImVec4(0.11f, 0.115f, 0.13f, 1);
        s.Colors[ImGuiCol_Header] = ImVec4(0.24f, 0.32f, 0.45f, 1);
        s.Colors[ImGuiCol_HeaderHovered] = ImVec4(0.30f, 0.40f, 0.56f, 1);
    }

    void drawUi() {
        ImVec2 size = ImGui::GetIO().DisplaySize;
        const float left = 250, right = 430;
        const ImGuiWindowFlags fixed =
            ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;
        ImGui::SetNextWindowPos(ImVec2(0, 0));
        ImGui::SetNextWindowSize(ImVec2(left, size.y));
        ImGui::Begin("Steps", nullptr, fixed);
        drawModuleList();
        ImGui::End();

        ImGui::SetNextWindowPos(ImVec2(left, 0));
        ImGui::SetNextWindowSize(ImVec2(size.x - left - right, size.y));
        ImGui::Begin("View", nullptr, fixed | ImGuiWindowFlags_NoScrollbar);
        drawViewport();
        ImGui::End();

        ImGui::SetNextWindowPos(ImVec2(size.x - right, 0));
        ImGui::SetNextWindowSize(ImVec2(right, size.y));
        ImGui::Begin("Module", nullptr, fixed);
        drawSidePanel();
        ImGui::End();
    }

    void drawModuleList() {
        ImGui::TextDisabled("workspace");
        ImGui::TextWrapped("%s", submission_.empty() ? "(no student folder: solutions only)"
                                                     : submission_.string().c_str());
        ImGui::Separator();
        std::string lab;
        const auto& ms = registry_->modules();
        for (size_t i = 0; i < ms.size(); ++i) {
            const ModuleDesc& d = *ms[i].desc;
            if (d.lab != lab) {
                lab = d.lab;
                ImGui::Spacing();
                ImGui::TextColored(ImVec4(1, 0.8f, 0.45f, 1), "lab: %s", lab.c_str());
            }
            ImGui::PushID(int(i));
            char label[128];
            std::snprintf(label, sizeof label, "%2d  %s", d.step, d.id.c_str());
            if (ImGui::Selectable(label, int(i) == current_, 0, ImVec2(130, 0))) select(int(i));
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("%s\n%s", d.title.c_str(), d.function.c_str());
            ImGui::SameLine(150);
            Status s = states_[d.id].status;
            ImGui::TextColored(statusColor(s), "%s", statusBadge(s));
            ImGui::PopID();
        }
        ImGui::Spacing();
        ImGui::Separator();
        if (ImGui::Button("< previous")) select(current_ - 1);
        ImGui::SameLine();
        if (ImGui::Button("next >")) select(current_ + 1);
        if (!messages_.empty()) {
            ImGui::Separator();
            ImGui::TextWrapped("%s", messages_.c_str());
        }
    }

    void drawViewport() {
        const ModuleDesc& d = module();
        ImGui::Text("%d. %s", d.step, d.title.c_str());
        ImGui::TextDisabled("%s", d.function.c_str());
        ImGui::SetNextItemWidth(170);
        if (ImGui::BeginCombo("view", kViews[size_t(view_)].c_str())) {
            for (size_t i = 0; i < kViews.size(); ++i) {
                if (i == size_t(kFirstTermView)) ImGui::Separator();
                if (ImGui::Selectable(kViews[i].c_str(), int(i) == view_)) {
                    view_ = int(i);
                    compose();
                }
            }
            ImGui::EndCombo();
        }
        if (view_ == 3) {
            ImGui::SameLine();
            ImGui::SetNextItemWidth(160);
            if (ImGui::SliderFloat("range", &diffRange_, 1e-6f, 1.0f, "%.1e",
                                   ImGuiSliderFlags_Logarithmic))
                compose();
        }
        if (view_ == 4) {
            ImGui::SameLine();
            ImGui::SetNextItemWidth(160);
            if (ImGui::SliderFloat("split", &split_, 0, 1)) compose();
        }
        ImGui::SameLine();
        if (ImGui::Button("screenshot")) screenshotRequested_ = true;
        ImGui::SameLine();
        ImGui::TextDisabled("frame %.1f ms, render %.0f ms", frameMs_, renderMs_);

        if (studentValue_.pixels.empty() && (view_ == 0 || view_ == 3 || view_ == 4))
            ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "%s",
                               hasStudent_ ? "your file has not compiled yet: showing the solution"
                                           : "no student file for this step: showing the solution");
        if (!renderError_.empty())
            ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "%s", renderError_.c_str());
        if (nanCount_ + infCount_ > 0)
            ImGui::TextColored(ImVec4(1, 0.3f, 1, 1),
                               "%d NaN pixels (magenta), %d Inf pixels (cyan) in the student image",
                               nanCount_, infCount_);

        ImVec2 avail = ImGui::GetContentRegionAvail();
        float legend = (view_ == 3 || d.display.mode == DisplayMode::FalseColor) ? 28 : 0;
        float side = std::max(64.0f, std::min(avail.x - legend, avail.y - 150));
        ImVec2 origin = ImGui::GetCursorScreenPos();
        const GLuint shownTexture = liveTexture_ ? liveTexture_ : imageTexture_.id();
        ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<intptr_t>(shownTexture)),
                     ImVec2(side, side));
        handleCamera(origin, side);
        if (liveTexture_ && view_ > 1)
            ImGui::TextDisabled("moving: %s picture; the %s view follows when you stop", liveWho_,
                                kViews[size_t(view_)].c_str());
        if (legend > 0) {
            ImGui::SameLine();
            drawLegend(view_ == 3 ? 0.0 : d.display.lo, view_ == 3 ? diffRange_ : d.display.hi,
                       view_ != 3 && d.display.logScale, side);
        }
        drawStats();
    }

    void handleCamera(ImVec2 origin, float side) {
        if (!ImGui::IsItemHovered()) return;
        ImGuiIO& io = ImGui::GetIO();
        if (ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
            yaw_ -= io.MouseDelta.x * 0.01;
            pitch_ = std::clamp(pitch_ + io.MouseDelta.y * 0.01, -1.5, 1.5);
            moved();
        }
        if (io.MouseWheel != 0) {
            distance_ = std::clamp(distance_ * std::pow(0.9, io.MouseWheel), 1.2, 200.0);
            moved();
        }
        // Pixel inspector.
        int x = int((io.MousePos.x - origin.x) / side * imageWidth_);
        int y = int((io.MousePos.y - origin.y) / side * imageHeight_);
        if (x < 0 || y < 0 || x >= imageWidth_ || y >= imageHeight_ ||
            solutionValue_.pixels.empty() || liveTexture_)
            return;
        size_t i = size_t(y) * solutionValue_.width + x;
        if (i >= surfaces_.size() || !surfaces_[i].covered) return;
        const Surface& s = surfaces_[i];
        auto value = [&](const Image& im) {
            char buf[96];
            std::snprintf(buf, sizeof buf, "%.6g %.6g %.6g", im.pixels[i * 4], im.pixels[i * 4 + 1],
                          im.pixels[i * 4 + 2]);
            return std::string(buf);
        };
        ImGui::BeginTooltip();
        ImGui::Text("pixel (%d, %d)", x, y);
        if (!studentValue_.pixels.empty())
            ImGui::Text("student   %s", value(studentValue_).c_str());
        ImGui::Text("solution  %s", value(solutionValue_).c_str());
        ImGui::Text("reference %s", value(referenceValue_).c_str());
        ImGui::Separator();
        ImGui::Text("N (%.3f %.3f %.3f)  N.V %.3f  N.L %.3f", s.normal.x, s.normal.y, s.normal.z,
                    glm::dot(s.normal, s.view), glm::dot(s.normal, s.light));
        ImGui::Text("roughness %.3f  metallic %.3f  ao %.3f", s.roughness, s.metallic, s.ao);
        ImGui::EndTooltip();
    }

    void drawLegend(double lo, double hi, bool logScale, float height) {
        ImVec2 p = ImGui::GetCursorScreenPos();
        ImDrawList* dl = ImGui::GetWindowDrawList();
        const int steps = 64;
        for (int i = 0; i < steps; ++i) {
            glm::dvec3 c = falseColor(1.0 - (i + 0.5) / steps);
            float y0 = p.y + height * i / steps, y1 = p.y + height * (i + 1) / steps;
            dl->AddRectFilled(ImVec2(p.x, y0), ImVec2(p.x + 14, y1),
                              IM_COL32(int(c.r * 255), int(c.g * 255), int(c.b * 255), 255));
        }
        char top[32], bottom[32];
        std::snprintf(top, sizeof top, "%.2g", hi);
        std::snprintf(bottom, sizeof bottom, "%.2g%s", lo, logScale ? " log" : "");
        dl->AddText(ImVec2(p.x - 2, p.y - 14), IM_COL32(220, 220, 220, 255), top);
        dl->AddText(ImVec2(p.x - 2, p.y + height + 1), IM_COL32(220, 220, 220, 255), bottom);
        ImGui::Dummy(ImVec2(28, height));
    }

    void drawStats() {
        auto row = [&](const char* who, const Comparison& s) {
            bool ok = s.passes(module().nonNegative, module().tolerance.outlierFraction);
            ImGui::TextColored(ok ? ImVec4(0.4f, 0.9f, 0.45f, 1) : ImVec4(1, 0.5f, 0.3f, 1),
                               "%-9s worst %.3g x the tolerance  outside %d  NaN %d  Inf %d  "
                               "neg %d  %s",
                               who, s.worstExcess, s.outside, s.nanCount, s.infCount,
                               s.negativeCount, ok ? "within the band" : "outside the band");
        };
        if (liveTexture_) {
            ImGui::TextDisabled("vs the CPU reference: follows when the input stops");
            return;
        }
        ImGui::TextDisabled(
            "vs the CPU reference's band on this picture (the badge is the grade):");
        if (!studentValue_.pixels.empty()) row("student", studentStats_);
        row("solution", solutionStats_);
        const ModuleState& st = states_.at(module().id);
        if (st.status == Status::Fails && !st.gradeMessage.empty())
            ImGui::TextWrapped("grade: %s", st.gradeMessage.c_str());
    }

    void drawSidePanel() {
        // Parameters stay in view; the handout, plot and log share the space below.
        ImGui::BeginChild("parameters", ImVec2(0, ImGui::GetContentRegionAvail().y * 0.42f), true);
        drawParams();
        ImGui::Separator();
        drawScenePanel();
        ImGui::EndChild();
        if (ImGui::BeginTabBar("tabs")) {
            // --tab opens one tab on the first frame; after that the student's clicks decide.
            auto opened = [&](const char* tab) {
                return openTab_ == tab ? ImGuiTabItemFlags_SetSelected : 0;
            };
            if (ImGui::BeginTabItem("Handout", nullptr, opened("handout"))) {
                ImGui::BeginChild("handout");
                drawHandout(handout_);
                ImGui::EndChild();
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Plot", nullptr, opened("plot"))) {
                drawPlot();
                ImGui::EndTabItem();
            }
            ImGuiTabItemFlags logFlags = compileLog_.empty() ? 0 : ImGuiTabItemFlags_SetSelected;
            if (compileLog_ != shownLog_)
                shownLog_ = compileLog_;
            else
                logFlags = 0;
            if (ImGui::BeginTabItem(compileLog_.empty() ? "Log###log" : "Log (error)###log",
                                    nullptr, logFlags | opened("log"))) {
                drawLog();
                ImGui::EndTabItem();
            }
            if (ImGui::BeginTabItem("Programs", nullptr, opened("programs"))) {
                ImGui::BeginChild("programs");
                drawPrograms();
                ImGui::EndChild();
                ImGui::EndTabItem();
            }
            ImGui::EndTabBar();
            openTab_.clear();
        }
    }

    void drawParams() {
        const ModuleDesc& d = module();
        ModuleState& st = state();
        if (d.params.empty()) ImGui::TextDisabled("this step has no parameters");
        for (const ParamDecl& p : d.params) {
            ImGui::PushID(p.name.c_str());
            glm::dvec3 v = st.params.vector(p.name);
            bool changed = false;
            switch (p.type) {
                case ParamType::Float: {
                    float f = float(v.x);
                    changed =
                        ImGui::SliderFloat(p.name.c_str(), &f, float(p.min), float(p.max), "%.4g",
                                           p.logScale ? ImGuiSliderFlags_Logarithmic : 0);
                    v.x = f;
                    break;
                }
                case ParamType::Int: {
                    int i = int(v.x);
                    changed = ImGui::SliderInt(p.name.c_str(), &i, int(p.min), int(p.max));
                    v.x = i;
                    break;
                }
                case ParamType::Bool: {
                    bool b = v.x != 0;
                    changed = ImGui::Checkbox(p.name.c_str(), &b);
                    v.x = b;
                    break;
                }
                case ParamType::Enum: {
                    int i = int(v.x);
                    if (ImGui::BeginCombo(p.name.c_str(), p.choices[size_t(i)].c_str())) {
                        for (size_t k = 0; k < p.choices.size(); ++k)
                            if (ImGui::Selectable(p.choices[k].c_str(), int(k) == i)) {
                                v.x = double(k);
                                changed = true;
                            }
                        ImGui::EndCombo();
                    }
                    break;
                }
                case ParamType::Color: {
                    float c[3] = {float(v.x), float(v.y), float(v.z)};
                    changed = ImGui::ColorEdit3(
                        p.name.c_str(), c,
                        p.max > 1 ? ImGuiColorEditFlags_HDR | ImGuiColorEditFlags_Float : 0);
                    v = glm::clamp(glm::dvec3(c[0], c[1], c[2]), 0.0, p.max);
                    break;
                }
                case ParamType::Direction: {
                    ImGui::TextUnformatted(p.name.c_str());
                    changed = directionPad("pad", v);
                    ImGui::SameLine();
                    ImGui::BeginGroup();
                    float f[3] = {float(v.x), float(v.y), float(v.z)};
                    ImGui::SetNextItemWidth(200);
                    if (ImGui::DragFloat3("##xyz", f, 0.01f, -1, 1) &&
                        glm::length(glm::dvec3(f[0], f[1], f[2])) > 1e-6) {
                        v = glm::dvec3(f[0], f[1], f[2]);
                        changed = true;
                    }
                    if (ImGui::Button(v.z < 0 ? "lower hemisphere" : "upper hemisphere")) {
                        v.z = -v.z;
                        changed = true;
                    }
                    ImGui::EndGroup();
                    if (changed) v = glm::normalize(v);
                    break;
                }
            }
            if (ImGui::IsItemHovered() && !p.description.empty())
                ImGui::SetTooltip("%s", p.description.c_str());
            ImGui::SameLine();
            if (ImGui::SmallButton("reset")) {
                v = p.defaultValue;
                changed = true;
            }
            if (changed) {
                st.params.set(p.name, v);
                moved();
            }
            ImGui::TextDisabled("  %s", p.description.c_str());
            ImGui::PopID();
        }
    }

    // The glTF models the chooser offers: the project's own (assets/models), the --model file,
    // and the one chosen (it may come from the saved state).
    std::vector<fs::path> modelChoices() const {
        std::vector<fs::path> files;
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(paths_.assets() / "models", ec))
            if (e.path().extension() == ".glb" || e.path().extension() == ".gltf")
                files.push_back(canonicalFile(e.path()));
        std::sort(files.begin(), files.end());
        fs::path given = options_.model.empty() ? fs::path() : canonicalFile(options_.model);
        for (const fs::path& f : {given, model_})
            if (!f.empty() && std::find(files.begin(), files.end(), f) == files.end())
                files.push_back(f);
        return files;
    }

    void drawScenePanel() {
        ImGui::TextDisabled("scene");
        std::string sceneShown = sceneName_.empty() ? module().scene : sceneName_;
        std::string current = model_.empty() ? sceneShown : model_.filename().string();
        ImGui::SetNextItemWidth(220);
        if (ImGui::BeginCombo("scene", current.c_str())) {
            std::vector<std::string> names;
            for (const auto& e : fs::directory_iterator(paths_.assets() / "scenes"))
                if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
            std::sort(names.begin(), names.end());
            for (const auto& n : names)
                if (ImGui::Selectable(n.c_str(), model_.empty() && n == sceneShown)) {
                    sceneName_ = n;
                    model_.clear();
                    loadScene();
                }
            // A model is lit like the step's own scene, so any model works with any step.
            ImGui::Separator();
            ImGui::TextDisabled("glTF models");
            std::vector<fs::path> models = modelChoices();
            for (size_t i = 0; i < models.size(); ++i) {
                ImGui::PushID(int(i));  // two folders may hold the same file name
                if (ImGui::Selectable(models[i].filename().string().c_str(), models[i] == model_)) {
                    model_ = models[i];
                    sceneName_.clear();
                    loadScene();
                }
                if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", models[i].string().c_str());
                ImGui::PopID();
            }
            ImGui::EndCombo();
        }
        if (!model_.empty()) ImGui::TextDisabled("glTF model, lit like %s", sceneShown.c_str());
        if (!sceneError_.empty()) {  // wrapped: a model's error names its full path
            ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1, 0.3f, 0.3f, 1));
            ImGui::TextWrapped("%s", sceneError_.c_str());
            ImGui::PopStyleColor();
        }
        if (!scene_.lights.empty()) {
            float pos[3] = {float(scene_.lights[0].position.x), float(scene_.lights[0].position.y),
                            float(scene_.lights[0].position.z)};
            if (ImGui::DragFloat3("light 0 position", pos, 0.05f)) {
                scene_.lights[0].position = glm::dvec3(pos[0], pos[1], pos[2]);
                moved();
            }
            // Colour and intensity apart: light colours are in the hundreds (thousands for a
            // large model), which neither fits nor edits well in a colour widget.
            const glm::dvec3 color = scene_.lights[0].color;
            float intensity = float(std::max({color.x, color.y, color.z}));
            const glm::dvec3 hue = intensity > 0 ? color / double(intensity) : glm::dvec3(1);
            float col[3] = {float(hue.x), float(hue.y), float(hue.z)};
            bool edited = ImGui::ColorEdit3("light 0 colour", col, ImGuiColorEditFlags_Float);
            edited |= ImGui::DragFloat("light 0 intensity", &intensity, intensity * 0.01f + 0.01f,
                                       0.0f, 1e7f, "%.1f", ImGuiSliderFlags_AlwaysClamp);
            if (edited) {
                scene_.lights[0].color =
                    glm::max(glm::dvec3(col[0], col[1], col[2]), 0.0) * double(intensity);
                moved();
            }
        }
        if (module().needs & NeedsEnvironment) {
            if (environmentInput_[0] == 0)
                std::snprintf(environmentInput_, sizeof environmentInput_, "%s",
                              scene_.environment.c_str());
            ImGui::SetNextItemWidth(220);
            ImGui::InputText("environment", environmentInput_, sizeof environmentInput_);
            ImGui::SameLine();
            if (ImGui::Button("load")) {
                std::string env = environmentInput_;
                if (env != "sky" && !fs::exists(env)) {
                    sceneError_ = env + ": no such file (use \"sky\" or an .hdr/.exr path)";
                } else {
                    scene_.environment = env;
                    sceneError_.clear();
                    dirty_ = true;
                }
            }
            if (ImGui::IsItemHovered())
                ImGui::SetTooltip("\"sky\" (the project's own) or an equirectangular .hdr/.exr");
        }
        if (ImGui::Button("reset camera")) loadScene();
        ImGui::SameLine();
        ImGui::TextDisabled("drag: orbit, wheel: zoom");
    }

    void drawPlot() {
        const ModuleDesc& d = module();
        const Probe& probe = d.probe;
        if (probeSolution_.pixels.empty()) return;
        ImGui::TextWrapped("The function along one row of the probe: x = %s; the row picks y = %s.",
                           probe.xAxis.c_str(), probe.yAxis.c_str());
        ImGui::SliderInt("row", &plotRow_, 0, probe.height - 1);
        plotRow_ = std::clamp(plotRow_, 0, probe.height - 1);
        ImGui::TextDisabled("y = %.3f (of 0..1)", 1.0 - double(plotRow_) / (probe.height - 1));
        if (probe.xIsLightAngle) {
            ImGui::SameLine();
            ImGui::Checkbox("polar", &polarPlot_);
            if (polarPlot_) {
                ImGui::SameLine();
                // The BRDF alone grows towards grazing; times the cosine it is the light
                // actually reflected, the lobe textbooks draw.
                ImGui::Checkbox("× N·L", &polarTimesCosine_);
            }
        }
        ImVec2 p = ImGui::GetCursorScreenPos();
        ImVec2 size(ImGui::GetContentRegionAvail().x, 260);
        ImGui::InvisibleButton("plot", size);
        ImDrawList* dl = ImGui::GetWindowDrawList();
        dl->AddRectFilled(p, ImVec2(p.x + size.x, p.y + size.y), IM_COL32(25, 27, 32, 255));
        bool haveStudent =
            !studentValue_.pixels.empty() && probeStudent_.width == probeSolution_.width;
        if (probe.xIsLightAngle && polarPlot_) {
            drawPolarLobe(dl, p, size, haveStudent);
            return;
        }
        double lo = 1e300, hi = -1e300;
        auto valueAt = [&](const Image& im, int x, int c) { return double(im.at(x, plotRow_, c)); };
        for (int x = 0; x < probe.width; ++x)
            for (int c = 0; c < d.components; ++c)
                for (const Image* im :
                     {&probeSolution_, haveStudent ? &probeStudent_ : &probeSolution_}) {
                    double v = valueAt(*im, x, c);
                    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
                }
        if (!(hi > lo)) hi = lo + 1;
        auto point = [&](int x, double v) {
            return ImVec2(p.x + size.x * float(x) / float(probe.width - 1),
                          p.y + size.y - size.y * float((v - lo) / (hi - lo)));
        };
        const ImU32 colors[3] = {IM_COL32(255, 110, 90, 255), IM_COL32(110, 230, 120, 255),
                                 IM_COL32(110, 160, 255, 255)};
        for (int c = 0; c < d.components; ++c) {
            std::vector<ImVec2> solution, student;
            for (int x = 0; x < probe.width; ++x) {
                solution.push_back(point(x, valueAt(probeSolution_, x, c)));
                if (haveStudent) student.push_back(point(x, valueAt(probeStudent_, x, c)));
            }
            ImU32 col = d.components == 1 ? IM_COL32(255, 210, 90, 255) : colors[c];
            dl->AddPolyline(solution.data(), int(solution.size()), col, 0, 3.0f);
            if (haveStudent)
                dl->AddPolyline(student.data(), int(student.size()), IM_COL32(255, 255, 255, 200),
                                0, 1.2f);
        }
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.3g", hi);
        dl->AddText(ImVec2(p.x + 4, p.y + 2), IM_COL32(200, 200, 200, 255), buf);
        std::snprintf(buf, sizeof buf, "%.3g", lo);
        dl->AddText(ImVec2(p.x + 4, p.y + size.y - 16), IM_COL32(200, 200, 200, 255), buf);
        ImGui::TextDisabled("thick: solution%s", haveStudent ? ", thin white: your function" : "");
    }

    // The probe row as a lobe in the plane of incidence: the light's direction at each angle
    // from N, its length the value (scaled to the row's largest). N points up, V and the
    // mirror direction R are drawn, so students see the lobe lean towards R and widen with
    // roughness.
    void drawPolarLobe(ImDrawList* dl, ImVec2 p, ImVec2 size, bool haveStudent) {
        const ModuleDesc& d = module();
        const Probe& probe = d.probe;
        const ImVec2 centre(p.x + size.x * 0.5f, p.y + size.y - 18);
        const float radius = std::min(size.x * 0.5f, size.y - 26) - 6;
        auto at = [&](double degrees, double length) {
            const double a = glm::radians(degrees);
            return ImVec2(centre.x + float(std::sin(a) * length) * radius,
                          centre.y - float(std::cos(a) * length) * radius);
        };
        const ImU32 grid = IM_COL32(70, 74, 84, 255), label = IM_COL32(200, 200, 200, 255);
        for (double ring : {0.5, 1.0}) {
            std::vector<ImVec2> arc;
            for (int i = 0; i <= 64; ++i) arc.push_back(at(-90 + 180.0 * i / 64, ring));
            dl->AddPolyline(arc.data(), int(arc.size()), grid, 0, 1.0f);
        }
        dl->AddLine(at(-90, 1), at(90, 1), grid);  // the surface
        const struct {
            double degrees;
            const char* name;
        } rays[] = {{0, "N"}, {probe.viewAngle, "V"}, {-probe.viewAngle, "R"}};
        for (const auto& r : rays) {
            dl->AddLine(centre, at(r.degrees, 1.0), grid, 1.5f);
            dl->AddText(at(r.degrees, 1.06), label, r.name);
        }
        auto degreesAt = [&](int x) { return -90 + 180.0 * x / (probe.width - 1); };
        auto valueAt = [&](const Image& im, int x, int c) {
            double v = im.at(x, plotRow_, c);
            return polarTimesCosine_ ? v * std::cos(glm::radians(degreesAt(x))) : v;
        };
        double hi = 0;
        for (int x = 0; x < probe.width; ++x)
            for (int c = 0; c < d.components; ++c)
                for (const Image* im :
                     {&probeSolution_, haveStudent ? &probeStudent_ : &probeSolution_}) {
                    double v = valueAt(*im, x, c);
                    if (std::isfinite(v)) hi = std::max(hi, v);
                }
        if (!(hi > 0)) hi = 1;
        const ImU32 colors[3] = {IM_COL32(255, 110, 90, 255), IM_COL32(110, 230, 120, 255),
                                 IM_COL32(110, 160, 255, 255)};
        auto lobe = [&](const Image& im, int c) {
            std::vector<ImVec2> points;
            for (int x = 0; x < probe.width; ++x) {
                double v = valueAt(im, x, c);
                points.push_back(at(degreesAt(x), std::isfinite(v) ? std::max(v, 0.0) / hi : 0));
            }
            return points;
        };
        for (int c = 0; c < d.components; ++c) {
            auto solution = lobe(probeSolution_, c);
            ImU32 col = d.components == 1 ? IM_COL32(255, 210, 90, 255) : colors[c];
            dl->AddPolyline(solution.data(), int(solution.size()), col, 0, 3.0f);
            if (haveStudent) {
                auto student = lobe(probeStudent_, c);
                dl->AddPolyline(student.data(), int(student.size()), IM_COL32(255, 255, 255, 200),
                                0, 1.2f);
            }
        }
        char buf[64];
        std::snprintf(buf, sizeof buf, "outer ring: %.3g", hi);
        dl->AddText(ImVec2(p.x + 4, p.y + 2), label, buf);
        ImGui::TextDisabled("thick: solution%s; length: value at that light direction",
                            haveStudent ? ", thin white: your function" : "");
    }

    // Every program compiled so far (the cache compiles each recipe once per define set, so a
    // scene with texture maps or more lights adds programs), with the ones the step uses for
    // the scene on screen listed on top and highlighted; then what else the GPU had to do.
    void drawPrograms() {
        const ImVec4 used(1, 0.8f, 0.45f, 1);
        ImGui::TextDisabled("this step on this scene uses (highlighted below):");
        for (const auto& [label, defines] : permutation_) {
            ImGui::TextColored(used, "%s", label.c_str());
            ImGui::SameLine();
            ImGui::TextWrapped("%s", defines.empty() ? "(no defines)" : defines.c_str());
        }
        ImGui::Spacing();
        const auto& compiled = renderer_->programs().compiled();
        ImGui::TextDisabled("%zu programs compiled, in order (a hot reload compiles again):",
                            compiled.size());
        const ImGuiTableFlags flags =
            ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerH | ImGuiTableFlags_SizingFixedFit;
        if (ImGui::BeginTable("compiled", 2, flags)) {
            // Two columns, the compile time under the label: the side panel is narrow, and a
            // third column would break the longest define (HAS_METALLIC_ROUGHNESS_MAP=1) or
            // label word (equirect_to_cube) in the middle.
            ImGui::TableSetupColumn("program, compile", ImGuiTableColumnFlags_WidthFixed, 132);
            ImGui::TableSetupColumn("defines", ImGuiTableColumnFlags_WidthStretch);
            ImGui::TableHeadersRow();
            for (const CompiledProgram& p : compiled) {
                ImGui::TableNextRow();
                bool isUsed = permutation_.count({p.label, p.defines}) > 0;
                if (isUsed)
                    ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg0, IM_COL32(60, 52, 30, 255));
                ImGui::TableNextColumn();
                ImGui::PushStyleColor(ImGuiCol_Text,
                                      isUsed ? used : ImGui::GetStyleColorVec4(ImGuiCol_Text));
                ImGui::TextWrapped("%s", p.label.c_str());
                ImGui::PopStyleColor();
                ImGui::TextDisabled("%.1f ms", p.milliseconds);
                ImGui::TableNextColumn();
                ImGui::TextWrapped("%s", p.defines.empty() ? "-" : p.defines.c_str());
            }
            ImGui::EndTable();
        }
        ImGui::Spacing();
        ImGui::Text("textures loaded: %d   precompute passes: %d",
                    eventCount(Counter::TextureLoads), eventCount(Counter::PrecomputePasses));
        // The journal's lines for that work, with sizes and times.
        std::istringstream in(journal());
        std::string line;
        while (std::getline(in, line))
            if (line.rfind("[texture]", 0) == 0 || line.rfind("[precompute]", 0) == 0)
                ImGui::TextWrapped("%s", line.c_str());
    }

    void drawLog() {
        if (compileLog_.empty()) {
            ImGui::TextDisabled("no errors");
        } else {
            ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1),
                               "%s does not compile; the image shows the last version that did.",
                               studentFile().filename().string().c_str());
            ImGui::TextDisabled("click a line to copy it");
            std::istringstream in(compileLog_);
            std::string line;
            int n = 0;
            while (std::getline(in, line)) {
                ImGui::PushID(n++);
                if (ImGui::Selectable(line.c_str())) ImGui::SetClipboardText(line.c_str());
                ImGui::PopID();
            }
        }
        ImGui::Separator();
        ImGui::TextDisabled("host log");
        ImGui::TextWrapped("%s", journal().c_str());
    }

    GuiOptions options_;
    std::unique_ptr<GlContext> context_;
    DataPaths paths_;
    std::unique_ptr<ModuleRegistry> registry_;
    std::unique_ptr<LabRenderer> renderer_;
    fs::path submission_;
    std::map<std::string, ModuleState> states_;
    int current_ = 0;
    int view_ = 0;
    std::string sceneName_, sceneError_, renderError_, compileLog_, shownLog_, messages_, handout_;
    std::string openTab_;    // --tab, for the first frame
    bool polarPlot_ = true;  // probes over the light's angle: the row as a lobe
    bool polarTimesCosine_ = true;
    fs::path model_;  // the glTF model shown, lit like the scene (empty: the scene itself)
    // What is on screen, for the chooser to return to when a file does not load.
    std::string shownSceneName_;
    fs::path shownModel_;
    std::set<fs::path> warnedModels_;
    // The step's programs for the scene on screen: (label, defines) as compiled() lists them.
    std::set<std::pair<std::string, std::string>> permutation_;
    Scene scene_;
    double yaw_ = 0, pitch_ = 0, distance_ = 3;
    bool dirty_ = true, hasStudent_ = false, screenshotRequested_ = false;
    // The live view (drawLive): its texture while the input moves (0: the settled image).
    std::unique_ptr<DisplayPass> displayPass_;
    GLuint liveTexture_ = 0;
    int liveSize_ = kRenderSize;                         // the live picture's side (kLiveBudgetMs)
    std::map<std::string, IblSettings> budgetSettings_;  // --error-budget, per environment
    std::vector<int> liveSizes_;      // of every live frame, for --orbit's report
    std::vector<double> liveWindow_;  // the live frames' times since the last resize
    const char* liveWho_ = "";
    std::chrono::steady_clock::time_point lastMove_{};
    bool precomputeNoticeShown_ = false;
    char environmentInput_[512] = "";
    fs::file_time_type lastStudentStamp_{};
    Image studentValue_, solutionValue_, referenceValue_, probeSolution_, probeStudent_;
    std::vector<Surface> surfaces_;
    struct BadgeJob {
        pid_t pid = -1;
        std::string id;
        fs::path json;
    } badgeJob_;  // the badge being graded (a `pbrlab check` process)
    Comparison studentStats_, solutionStats_;
    Band band_;  // the reference's band on the current picture
    gl::Handle imageTexture_;
    int imageWidth_ = 1, imageHeight_ = 1, nanCount_ = 0, infCount_ = 0, plotRow_ = 0;
    float diffRange_ = 1e-3f, split_ = 0.5f;
    double frameMs_ = 0, renderMs_ = 0;
    size_t statusCursor_ = 0;
};

}  // namespace

int runGui(const GuiOptions& options) {
    GuiApp app(options);
    return app.run();
}

}  // namespace pbrlab
