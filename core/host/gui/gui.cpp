// The window: GLFW and Dear ImGui around the Lab (lab.h). Each frame runs the frame function,
// draws the three windows (panels.h), and saves a screenshot when asked.
#include "gui.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <thread>

#include "gl/context.h"
#include "lab.h"
#include "panels.h"
#include "platform.h"
#include "redraw.h"
#include "render/display.h"
#include "util/error.h"
#include "view_status.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// The first frames compile programs (llvmpipe compiles at first draw): left out.
void printFrameTimes(const char* what, std::vector<double> ms, int w, int h) {
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
        "%s: %zu frames at %dx%d (after %zu warm-up): median %.1f ms, 95th percentile %.1f ms\n",
        what, ms.size(), w, h, warmup, median, p95);
}

// The handouts use Greek letters and maths signs (α, θ, π, ≤, ≈, ·, ², −); ImGui's built-in
// font has none of them. DejaVu Sans (Debian's fonts-dejavu-core) has all; without it the
// built-in font is kept and those characters show as '?'.
void loadFont(std::string& messages) {
    static const ImWchar ranges[] = {0x0020, 0x00FF,  // Latin-1: ·, ², °, ×
                                     0x0370, 0x03FF,  // Greek
                                     0x2010, 0x205E,  // dashes, quotes, ′
                                     0x2070, 0x209F,  // super- and subscripts
                                     0x2190, 0x21FF,  // arrows
                                     0x2200, 0x22FF,  // maths operators
                                     0};
    const char* file = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    if (fs::exists(file) && ImGui::GetIO().Fonts->AddFontFromFileTTF(file, 15.0f, nullptr, ranges))
        return;
    messages += std::string("font ") + file + " not found: Greek letters show as '?'\n";
}

// The evaluation thread's context (evaluation_worker.h), on the desktop: a hidden window's, made
// here on the main thread (GLFW creates windows on it only; creating one leaves the current context
// as it was), current on the worker. Not shared with the window's: the worker returns images in
// memory, and no GL object crosses threads.
class GlfwWorkerContext final : public WorkerContext {
public:
    GlfwWorkerContext() {
        // The context's own threads (llvmpipe's rasterizers) start here, on the main thread:
        // they yield to the window's as the evaluation thread does.
        platform::backgroundPriorityForThreadsStartedBy([this] {
            glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
            glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
            glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
            glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
            glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
            window_ = glfwCreateWindow(16, 16, "pbrlab evaluation", nullptr, nullptr);
            glfwDefaultWindowHints();
        });
    }
    ~GlfwWorkerContext() override {
        if (window_) glfwDestroyWindow(window_);
    }
    void makeCurrent() override {
        if (!window_) throw Error("cannot create a second OpenGL 4.5 core context");
        glfwMakeContextCurrent(window_);
    }
    void release() override { glfwMakeContextCurrent(nullptr); }

private:
    GLFWwindow* window_ = nullptr;
};

std::unique_ptr<WorkerContext> evaluationContext() {
    if (!kEvaluationThread) return windowsOwnContext();  // a page: one thread, one context
    return std::make_unique<GlfwWorkerContext>();
}

// The windows' background.
const ImVec4 kBackground(0.11f, 0.115f, 0.13f, 1);

void styleUi() {
    ImGui::StyleColorsDark();
    ImGuiStyle& s = ImGui::GetStyle();
    s.WindowRounding = 0;
    s.FrameRounding = 3;
    s.GrabRounding = 3;
    s.WindowBorderSize = 0;
    s.ItemSpacing = ImVec2(8, 6);
    // The windows tile the screen: their background is the screen's clear colour (kBackground),
    // not a filled rectangle each, which llvmpipe would shade and blend pixel by pixel (a third
    // of a frame at 1600x960).
    s.Colors[ImGuiCol_WindowBg] = ImVec4(0, 0, 0, 0);
    s.Colors[ImGuiCol_Header] = ImVec4(0.24f, 0.32f, 0.45f, 1);
    s.Colors[ImGuiCol_HeaderHovered] = ImVec4(0.30f, 0.40f, 0.56f, 1);
}

// The window's back buffer as an sRGB PNG (rows top first).
void saveScreenshot(const fs::path& file, int w, int h, std::string& messages) {
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
        messages += "screenshot: " + file.string() + "\n";
        std::cout << "screenshot " << file.string() << " (" << w << "x" << h << ")\n";
    } catch (const Error& e) {
        messages += std::string(e.what()) + "\n";
    }
}

class GuiApp;
GuiApp* runningApp = nullptr;  // for the page's hooks (gui.h)

class GuiApp {
public:
    explicit GuiApp(const GuiOptions& options)
        : options_(options),
          context_(createWindowContext(options.width, options.height, "pbrlab")),
          lab_(options, state_, evaluationContext()),
          console_(options.globalArguments, options.frames > 0) {
        for (const std::string& line : options.commands) console_.submit(line);
        if (!options.commands.empty() && options.tab.empty()) state_.openTab = "console";
        IMGUI_CHECKVERSION();
        ImGui::CreateContext();
        ImGui::GetIO().IniFilename = nullptr;  // the layout is computed, not saved
        loadFont(lab_.shown().messages);
        styleUi();
        ImGui_ImplGlfw_InitForOpenGL(context_->window(), true);
        ImGui_ImplOpenGL3_Init(gl::kWebGl2 ? "#version 300 es" : "#version 450 core");
        redraw_.setChecking(options.checkRedraw);
        runningApp = this;
    }

    std::string stepOnScreen() const { return lab_.module(state_).id; }
    void resize(int width, int height) {
        glfwSetWindowSize(context_->window(), width, height);
        redraw_.invalidate();  // a canvas given a size, even its own, is blank
    }
    void checkRedraw(bool on) { redraw_.setChecking(on); }
    std::string statusJson() const {
        const ViewStatus status = viewStatus(lab_, state_);
        nlohmann::json rows = nlohmann::json::array();
        for (const ViewStatus::Row& row : status.rows)
            rows.push_back({{"text", row.text}, {"ok", row.ok}});
        const std::string id = lab_.module(state_).id;
        return nlohmann::json{{"step", id},
                              {"settled", lab_.settled(state_)},
                              {"error", status.error},
                              {"errorLog", status.errorLog},
                              {"notice", status.notice},
                              {"renderError", lab_.shown().renderError},
                              {"sceneError", lab_.shown().sceneError},
                              {"rows", rows},
                              {"liveSide", lab_.shown().liveSide},
                              {"liveMs", lab_.shown().renderMs},
                              {"yaw", state_.camera.yaw},
                              {"evaluations", lab_.evaluationsDone()},
                              {"evaluationsYielded", lab_.evaluationsYielded()},
                              {"redraw", redrawJson()},
                              {"badge", badgeText(lab_.badges().of(id).status)},
                              {"gradeMessage", lab_.badges().of(id).gradeMessage},
                              {"bandNote", status.bandNote},
                              {"grade", status.grade},
                              {"gradeDetails", status.gradeDetails},
                              {"view", viewName(state_.view, state_.term, lab_.termViews())},
                              {"layout", layoutJson()}}
            .dump();
    }
    nlohmann::json layoutJson() const {
        const WindowLayout& l = state_.layout;
        return {{"compact", l.compact},
                {"steps", l.steps},
                {"view", l.view},
                {"module", l.module},
                {"pictureSide", l.pictureSide},
                {"pictureOrigin", l.pictureOrigin},
                {"viewToggle", l.viewToggle}};
    }
    nlohmann::json redrawJson() const {
        const RedrawStats& r = redraw_.stats();
        return {{"framesDrawn", r.framesDrawn},         {"framesInPart", r.framesInPart},
                {"framesUnchanged", r.framesUnchanged}, {"lastFraction", r.lastFraction},
                {"framesChecked", r.framesChecked},     {"pixelsDiffering", r.pixelsDiffering}};
    }
    void saveSolutionPicture(const fs::path& file) const {
        const ModuleDesc& m = lab_.module(state_);
        writeImage(file, displayImage(lab_.shown().solutionValue, m.display, m.components),
                   FileDepth::Uint8, true);
    }
    void submit(const std::string& line) { console_.submit(line); }

    ~GuiApp() {
        runningApp = nullptr;
        saveState(lab_.registry(), state_);
        ImGui_ImplOpenGL3_Shutdown();
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext();
    }

    // The frames until the window closes or a scripted run is done, then the reports asked
    // for. False: the platform calls the frames after this returns (a page), and the app must
    // stay for as long as they come.
    bool run() {
        const bool ended = platform::runFrames(
            [this] { return !glfwWindowShouldClose(context_->window()) && frame(); },
            [this](const std::exception& e) {
                lab_.shown().messages += std::string(e.what()) + "\n";
            });
        if (!ended) return false;
        if (options_.orbit) printOrbitReport(frameTimes_, renderTimes_, width_, height_);
        if (options_.orbit || options_.checkRedraw) printRedrawReport();
        if (options_.frameTimes) printEvaluationFrames(frameTimes_, whileEvaluating_);
        return true;
    }

private:
    // One frame; false once a scripted run (--frames) is done.
    bool frame() {
        GLFWwindow* window = context_->window();
        int& w = width_;
        int& h = height_;
        glfwPollEvents();
        auto start = std::chrono::steady_clock::now();
        const bool evaluatingBefore = lab_.evaluating();
        const int evaluationsBefore = lab_.evaluationsDone();
        if (options_.orbit) {  // a step of a mouse drag
            state_.camera.yaw += 0.02;
            requests_.moved = true;
        }
        console_.poll({&lab_, &state_, &requests_});
        // A press since the last frame: ImGui takes it in this frame's NewFrame, after
        // update(), which in a page would first run an evaluation posted before it, in the
        // page's one thread, with the button down (orbit_probe's back-to-back drags: one frame
        // of 1.1-1.5 s in 3 of 12). GLFW has the button's state from the press's event.
        if (glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS)
            requests_.holding = true;
        lab_.update(state_, requests_);
        if (quietFrame()) return true;
        ImGui_ImplOpenGL3_NewFrame();
        ImGui_ImplGlfw_NewFrame();
        // GLFW's clock may not advance between two frames (a page's timer is coarse), and
        // ImGui needs time to pass.
        ImGui::GetIO().DeltaTime = std::max(ImGui::GetIO().DeltaTime, 1e-4f);
        ImGui::NewFrame();
        drawWindows();
        requests_.holding = ImGui::IsAnyItemActive() && ImGui::IsMouseDown(ImGuiMouseButton_Left);
        ImGui::Render();
        glfwGetFramebufferSize(window, &w, &h);
        redraw_.draw(*ImGui::GetDrawData(), ImGui::GetIO().Fonts->TexID, kBackground);
        ++frameCount_;
        // Scripted: the frames asked for, the console's lines and the evaluation have
        // finished, the evaluation before this frame (ImGui hides a window, such as the
        // pixel inspector's tooltip, on the first frame it appears in).
        bool last = options_.frames > 0 && frameCount_ >= options_.frames && console_.idle() &&
                    !evaluatingBefore && !lab_.evaluating();
        if (requests_.screenshot) {  // the button, or the console's `screenshot`
            saveScreenshot(requests_.screenshotFile.empty() ? fs::path("pbrlab-screenshot.png")
                                                            : requests_.screenshotFile,
                           w, h, lab_.shown().messages);
            requests_.screenshot = false;
            requests_.screenshotFile.clear();
        }
        if (last && !options_.screenshot.empty())
            saveScreenshot(options_.screenshot, w, h, lab_.shown().messages);
        glfwSwapBuffers(window);
        platform::frameDrawn();
        lab_.shown().frameMs = millisecondsSince(start);
        frameTimes_.push_back(lab_.shown().frameMs);
        renderTimes_.push_back(lab_.shown().renderMs);
        const bool evaluated =
            evaluatingBefore || lab_.evaluating() || lab_.evaluationsDone() != evaluationsBefore;
        whileEvaluating_.push_back(evaluated ? evaluationsBefore : -1);
        // While the evaluation thread works, 60 frames a second are enough: the rest of
        // the time is its (without vsync, as under Xvfb, the loop would draw hundreds).
        if (lab_.evaluating() && kEvaluationThread)
            std::this_thread::sleep_until(start + std::chrono::microseconds(16667));
        return !last;
    }

    // True: this frame is not drawn. In a page the browser calls frame() at the display's
    // rate, and drawing the window is most of what an idle page costs: SwiftShader draws on
    // the CPU, on the cores the page's grader (a worker) and the picture's evaluation need,
    // and a grade took 3x as long beside a window drawn 25 times a second. So while nothing
    // on screen moves (no input in the page, no console line, nothing evaluated, no grade
    // arrived), the window is drawn 4 times a second, which still shows a tooltip as it
    // comes. After a change the next frames are drawn (ImGui lays a new window out over two).
    // The desktop draws every frame (platform::skipsQuietFrames): its GPU draws, with vsync.
    bool quietFrame() {
        if (!platform::skipsQuietFrames() || !options_.economies.quietFrames()) return false;
        constexpr int kFramesAfterChange = 4;
        constexpr auto kQuietFramePeriod = std::chrono::milliseconds(250);
        const auto now = std::chrono::steady_clock::now();
        const bool input = platform::inputArrived();
        if (input || !console_.quiet() || lab_.changing() || requests_.screenshot ||
            lab_.gradesArrived() != gradesShown_)
            framesToDraw_ = kFramesAfterChange;
        gradesShown_ = lab_.gradesArrived();
        if (framesToDraw_ == 0 && now - lastDrawn_ < kQuietFramePeriod) return true;
        framesToDraw_ = std::max(framesToDraw_ - 1, 0);
        lastDrawn_ = now;
        return false;
    }

    // --frame-times: every frame's times, then, for each evaluation against the CPU reference,
    // the frames drawn while it ran (or the frame that ran it, when it runs in the frame).
    void printEvaluationFrames(std::vector<double> frameTimes,
                               const std::vector<int>& whileEvaluating) const {
        for (int k = 0; k < lab_.evaluationsDone(); ++k) {
            std::vector<double> during;
            for (size_t i = 0; i < frameTimes.size(); ++i)
                if (whileEvaluating[i] == k) during.push_back(frameTimes[i]);
            std::sort(during.begin(), during.end());
            if (!during.empty())
                std::printf(
                    "evaluation %d against the CPU reference: %zu frames while it ran, "
                    "median %.1f ms, longest %.1f ms\n",
                    k + 1, during.size(), during[during.size() / 2], during.back());
        }
        // The baseline in the same run: the frames while none ran, the first 3 left out
        // (compiles), as long as the machine's load alone makes them.
        std::vector<double> idle;
        for (size_t i = 3; i < frameTimes.size(); ++i)
            if (whileEvaluating[i] < 0) idle.push_back(frameTimes[i]);
        std::sort(idle.begin(), idle.end());
        if (!idle.empty())
            std::printf("while no evaluation ran: %zu frames, median %.1f ms, longest %.1f ms\n",
                        idle.size(), idle[idle.size() / 2], idle.back());
        std::sort(frameTimes.begin(), frameTimes.end());
        if (!frameTimes.empty())
            std::printf("frames: %zu, median %.1f ms, longest %.1f ms\n", frameTimes.size(),
                        frameTimes[frameTimes.size() / 2], frameTimes.back());
    }

    void printOrbitReport(const std::vector<double>& frameTimes,
                          const std::vector<double>& renderTimes, int w, int h) {
        printFrameTimes("frame", frameTimes, w, h);
        std::vector<int> sizes = lab_.liveSizes();
        std::sort(sizes.begin(), sizes.end());
        const int side = sizes.empty() ? 0 : sizes[sizes.size() / 2];
        printFrameTimes("  of which the picture (median side)", renderTimes, side, side);
        // The baseline, in the same run: the settled frame, what every frame cost before the
        // live view (the picture at full size, read back and evaluated on the CPU).
        const auto start = std::chrono::steady_clock::now();
        lab_.render(state_);
        const double settledMs = millisecondsSince(start);
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

    // How much of the window the frames drew (WindowRedraw), and with --check-redraw whether
    // each, drawn over the last, was the frame drawn whole.
    void printRedrawReport() const {
        const RedrawStats& r = redraw_.stats();
        std::vector<double> fractions = r.fractions;
        std::sort(fractions.begin(), fractions.end());
        std::printf(
            "window redrawn: %lld frames drawn, %lld of them only where they changed, %lld "
            "unchanged; median %.1f%% of the window's pixels a frame\n",
            r.framesDrawn, r.framesInPart, r.framesUnchanged,
            fractions.empty() ? 100.0 : 100 * fractions[fractions.size() / 2]);
        if (r.framesChecked > 0)
            std::printf("redraw check: %lld frames also drawn whole, %lld pixels differ\n",
                        r.framesChecked, r.pixelsDiffering);
    }

    // Steps | picture | module, side by side, filling the window; in a narrow window
    // (kCompactLayoutWidth) the steps are a line at the top of the picture's.
    void drawWindows() {
        ImVec2 size = ImGui::GetIO().DisplaySize;
        WindowLayout& layout = state_.layout;
        layout.compact = size.x < kCompactLayoutWidth;
        // Narrower than the layout's widths need (a page beside its editor, a small window),
        // the side windows give up width first, down to what their controls need.
        const float left =
            layout.compact ? 0 : std::min(layout.stepsWidth, std::max(225.0f, 0.2f * size.x));
        // (Folded, the steps leave the parameters' window the width its controls need.)
        const float right =
            std::min(layout.moduleWidth, layout.compact ? std::max(340.0f, 0.38f * size.x)
                                                        : std::max(300.0f, 0.34f * size.x));
        const ImGuiWindowFlags fixed =
            ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;
        if (!layout.compact) {
            ImGui::SetNextWindowPos(ImVec2(0, 0));
            ImGui::SetNextWindowSize(ImVec2(left, size.y));
            ImGui::Begin("Steps", nullptr, fixed);
            drawStepsPanel(lab_, state_, requests_);
            ImGui::End();
        }
        layout.steps = left;
        layout.view = size.x - left - right;
        layout.module = right;

        ImGui::SetNextWindowPos(ImVec2(left, 0));
        ImGui::SetNextWindowSize(ImVec2(size.x - left - right, size.y));
        ImGui::Begin("View", nullptr, fixed | ImGuiWindowFlags_NoScrollbar);
        if (layout.compact) drawStepsLine(lab_, state_, requests_);
        drawViewPanel(lab_, state_, requests_);
        ImGui::End();

        ImGui::SetNextWindowPos(ImVec2(size.x - right, 0));
        ImGui::SetNextWindowSize(ImVec2(right, size.y));
        ImGui::Begin("Module", nullptr, fixed);
        // Parameters stay in view; the handout, plot and log share the space below.
        ImGui::BeginChild("parameters", ImVec2(0, ImGui::GetContentRegionAvail().y * 0.42f), true);
        drawModulePanel(lab_, state_, requests_);
        ImGui::EndChild();
        drawSideTabs(lab_, state_, tabs_, console_);
        ImGui::End();
    }

    GuiOptions options_;
    std::unique_ptr<GlContext> context_;
    // After context_ (a page asks the canvas's) and options_.
    WindowRedraw redraw_{platform::windowKeepsItsPixels(), options_.economies.partialRedraw()};
    GuiState state_;
    Lab lab_;  // after context_ (it needs GL) and state_ (it fills it)
    Requests requests_;
    SideTabsMemory tabs_;
    Console console_;
    int frameCount_ = 0, width_ = 0, height_ = 0;
    std::chrono::steady_clock::time_point lastDrawn_{};  // quietFrame's
    int framesToDraw_ = 0, gradesShown_ = 0;
    std::vector<double> frameTimes_, renderTimes_;
    // Per frame, the evaluation against the CPU reference it overlapped or ran (the number
    // finished before it), or -1.
    std::vector<int> whileEvaluating_;
};

}  // namespace

std::string guiStepOnScreen() {
    return runningApp ? runningApp->stepOnScreen() : std::string();
}

void guiSubmitConsoleLine(const std::string& line) {
    if (runningApp) runningApp->submit(line);
}

std::string guiStatusJson() {
    return runningApp ? runningApp->statusJson() : "{}";
}

void guiResize(int width, int height) {
    if (runningApp) runningApp->resize(width, height);
}

void guiCheckRedraw(bool on) {
    if (runningApp) runningApp->checkRedraw(on);
}

void guiSaveSolutionPicture(const fs::path& file) {
    if (!runningApp) throw Error("the GUI is not running");
    runningApp->saveSolutionPicture(file);
}

int runGui(const GuiOptions& options) {
    static std::unique_ptr<GuiApp> kept;  // a page's app, for as long as its frames come
    auto app = std::make_unique<GuiApp>(options);
    if (!app->run()) kept = std::move(app);
    return 0;
}

}  // namespace pbrlab
