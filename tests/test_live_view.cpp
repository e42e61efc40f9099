// The GUI's live view while the input moves (core/host/gui/frame.cpp), without a window: the
// picture at a reduced side that follows a time budget (LiveSize), with coarse spheres, and
// once the input is still the full-size picture, exactly what the headless renderer draws.
// The mechanism, not its speed: docs/speed-history.md has the frame times.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iterator>
#include <thread>

#include "gl/context.h"
#include "gui/evaluation_worker.h"
#include "gui/frame_economies.h"
#include "gui/lab.h"
#include "gui/live_size.h"
#include "ibl/map_error.h"
#include "render/converge.h"
#include "render/renderer.h"
#include "test_support.h"

using namespace pbrlab;

TEST(LiveView, TheLiveSideFollowsTheTimeBudget) {
    const double budget = LiveSize::kBudgetMs;
    LiveSize live(512);
    for (int i = 0; i < 8; ++i) live.frameTook(0.5 * budget);
    EXPECT_EQ(live.side(), 512);  // within the budget: full size, never more
    // One frame far over the budget is not a trend (another process had the cores) ...
    live.frameTook(20 * budget);
    live.frameTook(0.5 * budget);
    live.frameTook(0.5 * budget);
    live.frameTook(0.5 * budget);
    EXPECT_EQ(live.side(), 512);
    // ... two in a row are: at once, to the side that would have fitted (cost per pixel).
    live.frameTook(4 * budget);
    live.frameTook(4 * budget);
    EXPECT_EQ(live.side(), 256);
    // A little over the budget for 4 frames: a fifth smaller.
    for (int i = 0; i < 4; ++i) live.frameTook(1.1 * budget);
    EXPECT_EQ(live.side(), 200);
    // Much under it: a quarter larger every 4 frames, back to full size.
    for (int i = 0; i < 4; ++i) live.frameTook(0.1 * budget);
    EXPECT_EQ(live.side(), 248);
    for (int i = 0; i < 40; ++i) live.frameTook(0.1 * budget);
    EXPECT_EQ(live.side(), 512);
    // A view that costs seconds at full size (the settled frame measured it): the next drag
    // starts small, and no side goes below the smallest.
    live.fullSizeTook(5000);
    EXPECT_EQ(live.side(), 24);
    for (int i = 0; i < 8; ++i) live.frameTook(100 * budget);
    EXPECT_EQ(live.side(), LiveSize::kMinSide);
    // From the smallest side it grows too.
    for (int i = 0; i < 4; ++i) live.frameTook(0.1 * budget);
    EXPECT_EQ(live.side(), 24);
    live.reset();  // another step
    EXPECT_EQ(live.side(), 512);
}

// Without the frame economies (--no-frame-economies) the live picture stays at full size
// whatever its frames or the settled frame took.
TEST(LiveView, WithoutEconomiesTheLiveSideStaysFull) {
    for (const bool timed : {true, false}) {
        LiveSize live(512, timed, false);
        live.fullSizeTook(5000);
        for (int i = 0; i < 8; ++i) live.frameTook(100 * LiveSize::kBudgetMs);
        EXPECT_EQ(live.side(), 512) << "frames timed: " << timed;
    }
}

// In a browser a live frame's time is not its picture's (kLiveFramesTimed): the settled
// picture's cost, timed by its read-back, sets the side, and the frames move it only between
// half of that side and all of it.
TEST(LiveView, UntimedFramesKeepTheSideTheSettledPicturesCostAllows) {
    const double budget = LiveSize::kBudgetMs;
    LiveSize live(512, false);
    live.fullSizeTook(4 * budget);  // the budget fits a picture of half the side
    EXPECT_EQ(live.side(), 256);
    // Every frame far over the budget (the GPU process's queue): no smaller than half of it.
    for (int i = 0; i < 40; ++i) live.frameTook(3 * budget);
    EXPECT_EQ(live.side(), 128);
    // Frames that look cheap (a GPU that queues the work): no larger than the side allowed.
    for (int i = 0; i < 40; ++i) live.frameTook(0.1 * budget);
    EXPECT_EQ(live.side(), 256);
    // The next settled picture measures again, cheaper: that side, whatever the frames did.
    for (int i = 0; i < 40; ++i) live.frameTook(3 * budget);
    live.fullSizeTook(budget);
    EXPECT_EQ(live.side(), 512);
    // The costliest views keep the smallest side as their floor.
    live.fullSizeTook(5000);
    EXPECT_EQ(live.side(), 24);
    for (int i = 0; i < 8; ++i) live.frameTook(100 * budget);
    EXPECT_EQ(live.side(), LiveSize::kMinSide);
    live.reset();  // another step: full size, the whole range again
    EXPECT_EQ(live.side(), 512);
    for (int i = 0; i < 40; ++i) live.frameTook(3 * budget);
    EXPECT_EQ(live.side(), LiveSize::kMinSide);
}

// n >= pi sqrt(r) keeps a chord within half a pixel of a circle of radius r pixels.
TEST(LiveView, CoarseSpheresHaveTheSegmentsTheirSizeOnScreenNeeds) {
    EXPECT_EQ(sphereSegments(1), 16);
    EXPECT_EQ(sphereSegments(56), 24);   // the lesson's grid at 512: 28 pixels, doubled
    EXPECT_EQ(sphereSegments(100), 32);  // pi * 10 = 31.4
    EXPECT_EQ(sphereSegments(400), 64);
    EXPECT_EQ(sphereSegments(1000), 96);  // the full sphere
}

// The lesson's grid, drawn with coarse spheres (the live frames') and with the full ones: the
// same picture, moved by under a pixel. The outline moves only onto its neighbours, and every
// other value is one the full picture has within a pixel (a fraction of a pixel is a change
// of N.L of a few hundredths where the normal turns quickly, but not a new value).
// The first drag's side comes from the settled picture's cost: the view pass and its value's
// read-back, since a browser's glFinish returns before the GPU has drawn (the view pass alone
// measured 0.0-0.4 ms at 512 in headless Chromium, and the first drag began at full size).
TEST(LiveView, ThePicturesCostCountsTheReadBackThatWaitsForTheGpu) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths, RendererOptions{{}, {}}};
    const LoadedModule& ndf = modules.find("ndf");
    const ParamValues params(ndf.desc->params);
    const Scene scene = loadScene(paths.scene("sphere-grid"));
    RenderRequest request{&ndf, &params, &scene, {}, nullptr, kRenderSize, kRenderSize};
    request.readValue = false;
    renderer.render(request);  // compiled: not part of what is timed below
    const RenderResult drawn = renderer.render(request);
    EXPECT_EQ(drawn.pictureMilliseconds, drawn.milliseconds);  // nothing read back
    request.readValue = true;
    const RenderResult read = renderer.render(request);
    ASSERT_EQ(read.value.width, kRenderSize);
    EXPECT_GT(read.milliseconds, 0);
    EXPECT_GT(read.pictureMilliseconds, read.milliseconds);  // 4 MB of floats came back
}

TEST(LiveView, CoarseSpheresMoveThePictureByUnderAPixel) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths, RendererOptions{{}, {}}};
    const LoadedModule& ndotl = modules.find("ndotl");
    const ParamValues params(ndotl.desc->params);
    const Scene scene = loadScene(paths.scene("sphere-grid"));
    const int side = 256;
    RenderRequest request{&ndotl, &params, &scene, {}, nullptr, side, side};
    const Image full = renderer.render(request).value;
    request.coarseSpheres = true;
    const Image coarse = renderer.render(request).value;
    request.coarseSpheres = false;
    EXPECT_EQ(renderer.render(request).value.pixels, full.pixels);  // nothing left behind
    auto covered = [&](const Image& im, int x, int y) {
        return x >= 0 && y >= 0 && x < side && y < side && im.at(x, y, 3) > 0.5f;
    };
    int coveredPixels = 0, changedCoverage = 0, changedValue = 0;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            coveredPixels += covered(full, x, y);
            bool outline = false;         // a neighbour in the full picture is on the other side
            float lo = 1e9f, hi = -1e9f;  // the full picture's values within a pixel
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    outline = outline || covered(full, x + dx, y + dy) != covered(full, x, y);
                    if (!covered(full, x + dx, y + dy)) continue;
                    lo = std::min(lo, full.at(x + dx, y + dy, 0));
                    hi = std::max(hi, full.at(x + dx, y + dy, 0));
                }
            if (covered(full, x, y) != covered(coarse, x, y)) {
                ++changedCoverage;
                EXPECT_TRUE(outline) << "pixel " << x << ", " << y;
            } else if (covered(full, x, y)) {
                const float v = coarse.at(x, y, 0);
                changedValue += v != full.at(x, y, 0);
                if (!outline) {
                    EXPECT_GE(v, lo - 1e-3f) << "pixel " << x << ", " << y;
                    EXPECT_LE(v, hi + 1e-3f) << "pixel " << x << ", " << y;
                }
            }
        }
    EXPECT_GT(coveredPixels, side * side / 4);
    EXPECT_GT(changedValue, coveredPixels / 2);  // coarse they were
    EXPECT_LT(changedCoverage, coveredPixels / 20);
}

// An empty XDG_CONFIG_HOME for one test, so that no remembered step, scene or model (gui.json)
// is read; the old value comes back at the end of the test.
class EmptyConfigHome {
public:
    EmptyConfigHome() {
        const char* old = std::getenv("XDG_CONFIG_HOME");
        old_ = old ? old : "";
        setenv("XDG_CONFIG_HOME", dir_.path.c_str(), 1);
    }
    ~EmptyConfigHome() {
        if (old_.empty())
            unsetenv("XDG_CONFIG_HOME");
        else
            setenv("XDG_CONFIG_HOME", old_.c_str(), 1);
    }

private:
    test::TempDir dir_;
    std::string old_;
};

// The window's frames while the evaluation thread works, until its result has arrived (each
// frame returns at once: the evaluation is not waited for).
void framesUntilEvaluated(Lab& lab, GuiState& state, Requests& requests) {
    const auto start = std::chrono::steady_clock::now();
    while (lab.evaluating() && std::chrono::steady_clock::now() - start < std::chrono::minutes(2)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        lab.update(state, requests);
    }
    ASSERT_FALSE(lab.evaluating()) << "no evaluation in 2 minutes";
}

// Dragging, then still, as the window's frames do it (Lab::update): every moving frame is a
// live picture at the controller's side, nothing evaluated; once the input is still the
// evaluation runs on its thread while frames go on, and its picture is full size and exactly
// what the headless renderer (`pbrlab render`) draws for that camera.
TEST(LiveView, MovingFramesAreReducedAndTheStillFrameIsTheHeadlessRender) {
    auto context = createHeadlessContext();
    const EmptyConfigHome config;  // no remembered step, scene or model (gui.json)
    GuiOptions options;
    options.modulesDirs = {PBRLAB_MODULE_DIR};
    options.module = "ndf";
    options.scene = "sphere-grid";
    GuiState state;
    Lab lab(options, state);
    Requests requests;
    lab.update(state, requests);  // still from the start: the evaluation starts
    // The frame did not wait for it: a 512x512 evaluation of the grid takes a second or more
    // on llvmpipe (docs/speed-history.md), this frame returned with it still running.
    EXPECT_TRUE(lab.evaluating());
    EXPECT_TRUE(lab.shown().solutionValue.pixels.empty());
    framesUntilEvaluated(lab, state, requests);
    ASSERT_EQ(lab.shown().liveTexture, 0u);
    const Image first = lab.shown().solutionValue;
    ASSERT_EQ(first.width, kRenderSize);

    // Reduced, as after a view that cost 4 budgets at full size (reset first: the settled frame
    // above measured this machine's cost). The frames below may shrink it further, by their
    // times; they cannot grow it back within 3 frames.
    lab.liveSize().reset();
    lab.liveSize().fullSizeTook(4 * LiveSize::kBudgetMs);
    ASSERT_EQ(lab.liveSize().side(), kRenderSize / 2);
    for (int frame = 0; frame < 3; ++frame) {
        state.camera.yaw += 0.02;  // a step of a mouse drag
        requests.moved = true;
        lab.update(state, requests);
        const Shown& shown = lab.shown();
        ASSERT_NE(shown.liveTexture, 0u);
        if (frame == 0) {
            EXPECT_EQ(shown.liveSide, kRenderSize / 2);
        }
        EXPECT_LE(shown.liveSide, kRenderSize / 2);         // what the line under the picture says
        EXPECT_EQ(lab.liveSizes().back(), shown.liveSide);  // what it was drawn at
        EXPECT_EQ(shown.solutionValue.pixels, first.pixels);  // not evaluated while moving
    }

    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // past the settle delay
    lab.update(state, requests);
    EXPECT_TRUE(lab.evaluating());
    framesUntilEvaluated(lab, state, requests);
    const Shown& shown = lab.shown();
    EXPECT_EQ(shown.liveTexture, 0u);
    ASSERT_EQ(shown.solutionValue.width, kRenderSize);
    EXPECT_NE(shown.solutionValue.pixels, first.pixels);  // the camera turned
    LabRenderer headless{lab.paths(), RendererOptions{{}, {}}};
    const Scene scene = lab.currentScene(state);
    const RenderResult r = headless.renderScene(lab.loaded(state), state.params.at("ndf"), scene,
                                                {}, kRenderSize, kRenderSize, false);
    EXPECT_EQ(r.value.pixels, shown.solutionValue.pixels);
}

// A newer edit supersedes the evaluation running: it is never shown (the evaluation thread
// drops it at its next stage), and the one shown is the newer state's.
TEST(LiveView, ANewerEditSupersedesTheEvaluationRunning) {
    auto context = createHeadlessContext();
    const EmptyConfigHome config;
    GuiOptions options;
    options.modulesDirs = {PBRLAB_MODULE_DIR};
    options.module = "ndotl";
    GuiState state;
    Lab lab(options, state);
    Requests requests;
    lab.update(state, requests);  // still: the evaluation starts
    ASSERT_TRUE(lab.evaluating());
    state.camera.yaw += 0.5;  // the student drags before it arrives
    requests.moved = true;
    lab.update(state, requests);
    EXPECT_FALSE(lab.evaluating());  // cancelled
    EXPECT_NE(lab.shown().liveTexture, 0u);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // past the settle delay
    lab.update(state, requests);
    framesUntilEvaluated(lab, state, requests);
    EXPECT_EQ(lab.evaluationsDone(), 1);  // the first one never arrived
    LabRenderer headless{lab.paths(), RendererOptions{{}, {}}};
    const RenderResult r =
        headless.renderScene(lab.loaded(state), state.params.at("ndotl"), lab.currentScene(state),
                             {}, kRenderSize, kRenderSize, false);
    EXPECT_EQ(r.value.pixels, lab.shown().solutionValue.pixels);
}

// An environment's maps are built on the evaluation thread and handed to the window's
// renderer with its result: a drag before they arrive draws no live picture (which would build
// them in the frame) and says why; after, the window's renderer holds the same texels as a
// headless renderer builds, and a drag draws at once.
TEST(LiveView, AnEnvironmentsMapsAreBuiltOnTheEvaluationThreadNotInAFrame) {
    auto context = createHeadlessContext();
    const EmptyConfigHome config;
    GuiOptions options;
    options.modulesDirs = {PBRLAB_MODULE_DIR};
    options.module = "split_sum";  // reads the environment cube and every derived map
    GuiState state;
    Lab lab(options, state);
    Requests requests;
    const Scene scene = lab.currentScene(state);
    const IblSettings ibl = lab.iblFor(scene);
    lab.update(state, requests);  // still: the evaluation starts, and builds the maps
    ASSERT_TRUE(lab.evaluating());
    state.camera.yaw += 0.5;  // the student drags before it arrives
    requests.moved = true;
    lab.update(state, requests);
    EXPECT_TRUE(lab.shown().liveWaitsForMaps);
    EXPECT_EQ(lab.shown().liveTexture, 0u);
    EXPECT_EQ(lab.renderer().environmentMapsBuilt(scene.environment, ibl), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // past the settle delay
    lab.update(state, requests);
    framesUntilEvaluated(lab, state, requests);
    ASSERT_EQ(lab.renderer().environmentMapsBuilt(scene.environment, ibl), 2);

    LabRenderer headless{lab.paths(), RendererOptions{{}, {}}};
    headless.environmentMaps(scene, ibl);
    const auto built = headless.environmentMapImages(scene.environment, ibl);
    const auto taken = lab.renderer().environmentMapImages(scene.environment, ibl);
    ASSERT_TRUE(built && taken);
    auto same = [](const std::vector<std::vector<Image>>& a,
                   const std::vector<std::vector<Image>>& b) {
        if (a.size() != b.size()) return false;
        for (size_t level = 0; level < a.size(); ++level)
            for (size_t face = 0; face < a[level].size(); ++face)
                if (a[level][face].pixels != b[level][face].pixels) return false;
        return true;
    };
    EXPECT_TRUE(same(built->environment, taken->environment));
    EXPECT_TRUE(same(built->irradiance, taken->irradiance));
    EXPECT_TRUE(same(built->prefilter, taken->prefilter));
    EXPECT_EQ(built->lut.pixels, taken->lut.pixels);
    EXPECT_EQ(built->prefilterMaxLod, taken->prefilterMaxLod);

    state.camera.yaw += 0.02;  // a drag now draws at once
    requests.moved = true;
    lab.update(state, requests);
    EXPECT_FALSE(lab.shown().liveWaitsForMaps);
    EXPECT_NE(lab.shown().liveTexture, 0u);
}

// --error-budget's search (precomputes measured against the exact sums: 0.6-0.8 s) runs on
// the evaluation thread too: the window's renderer never compiles a precompute pass, a drag
// before the choice arrives waits for it, and the settings the window then uses are the ones
// `pbrlab precompute --error-budget` chooses, with their maps.
TEST(LiveView, TheErrorBudgetsSettingsAreChosenOnTheEvaluationThread) {
    auto context = createHeadlessContext();
    const EmptyConfigHome config;
    GuiOptions options;
    options.modulesDirs = {PBRLAB_MODULE_DIR};
    options.module = "split_sum";
    options.errorBudget = 0.05;
    GuiState state;
    Lab lab(options, state);
    Requests requests;
    const Scene scene = lab.currentScene(state);
    lab.update(state, requests);  // still: the evaluation starts with the search
    ASSERT_TRUE(lab.evaluating());
    state.camera.yaw += 0.5;
    requests.moved = true;
    lab.update(state, requests);
    EXPECT_TRUE(lab.shown().liveWaitsForMaps);
    EXPECT_EQ(lab.shown().liveTexture, 0u);
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    lab.update(state, requests);
    framesUntilEvaluated(lab, state, requests);

    LabRenderer headless{lab.paths(), RendererOptions{{}, {}}};
    const Image equirect = loadEnvironmentImage(scene.environment);
    IblTruth truth(equirect);
    IblPrecompute precompute(headless.programs(), lab.paths().shaders());
    const IblChoice choice = chooseIblSettings(precompute, equirect, truth, 0.05, nullptr);
    EXPECT_EQ(lab.iblFor(scene).key(), choice.settings.key());
    EXPECT_NE(choice.settings.key(), IblSettings().key());  // not vacuous: the budget changes them
    EXPECT_EQ(lab.renderer().environmentMapsBuilt(scene.environment, choice.settings), 2);
    for (const CompiledProgram& p : lab.renderer().programs().compiled())
        EXPECT_EQ(p.label.find("precompute"), std::string::npos) << p.label;
}

// A newer edit stops the CPU reference of the evaluation running between two points, not at
// the end of its stage (brdf_lut's band at 1024 samples: 7-9 s): the band asks `stop` before
// each point and throws Cancelled once it says so; asked never, it is the same band.
TEST(LiveView, AReferenceBandStopsBetweenPointsWhenAsked) {
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    const ModuleDesc& d = *modules.find("ndf").desc;
    const std::vector<Surface> surfaces = probeSurfaces(d.probe);
    ASSERT_GT(surfaces.size(), 1000u);
    const ParamValues params(d.params);
    const ReferenceContext context{
        params, {{glm::dvec3(2, 3, 4), glm::dvec3(1)}}, glm::dvec3(0, 0, 3)};
    std::atomic<int> asked{0};
    EXPECT_THROW(referenceBand(d, surfaces, context, [&] { return ++asked > 10; }), Cancelled);
    // Each worker thread asks once more at most after the first yes.
    EXPECT_LE(asked.load(), 10 + 8);
    const Band whole = referenceBand(d, surfaces, context);
    const Band askedNever = referenceBand(d, surfaces, context, [] { return false; });
    EXPECT_EQ(whole.expected, askedNever.expected);
    EXPECT_EQ(whole.lo, askedNever.lo);
    EXPECT_EQ(whole.hi, askedNever.hi);
}

// After a student's edit only their file has changed: the evaluation takes the solution's
// picture, band and probe from the last one instead of drawing and reading back the picture
// again (in the page, 0.25-0.5 s of each evaluation after an edit), and grades the new file
// exactly as a fresh evaluation does. Any other input draws the solution anew.
TEST(LiveView, AnEditReusesTheSolutionsStageAndOtherInputsDoNot) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    const test::TempDir work;
    auto text = [](const std::filesystem::path& file) {
        std::ifstream in(file);
        return std::string(std::istreambuf_iterator<char>(in), {});
    };
    const std::string correct = text(PBRLAB_SOURCE_DIR "/labs/ndf/solution.glsl");
    const std::string wrong = text(PBRLAB_SOURCE_DIR "/labs/ndf/mistakes/alpha_is_roughness.glsl");
    EvaluationJob job;
    job.module = &modules.find("ndf");
    job.params = ParamValues(job.module->desc->params);
    job.scene = loadScene(paths.scene("sphere-grid"));
    job.submission = work.path;
    job.student = true;
    job.side = 128;
    auto evaluate = [&](EvaluationWorker& worker) {
        worker.post(job);
        return worker.wait();
    };
    EvaluationWorker worker(paths, headlessWorkerContext(), FrameEconomies{}.evaluationDrawMs());
    work.write("ndf.glsl", correct);
    const EvaluationResult first = evaluate(worker);
    ASSERT_TRUE(first.renderError.empty()) << first.renderError;
    EXPECT_FALSE(first.solutionKept);
    ASSERT_TRUE(first.studentRendered);
    EXPECT_TRUE(first.studentStats.passes(false, 0));

    work.write("ndf.glsl", wrong);
    const EvaluationResult edited = evaluate(worker);
    EXPECT_TRUE(edited.solutionKept);
    EXPECT_EQ(edited.solutionValue.pixels, first.solutionValue.pixels);
    EXPECT_EQ(edited.referenceValue.pixels, first.referenceValue.pixels);
    EXPECT_EQ(edited.probeSolution.pixels, first.probeSolution.pixels);
    EXPECT_EQ(edited.surfaces, first.surfaces);  // shared, not copied
    // The wrong file's statistics, as a worker that kept nothing computes them.
    EvaluationWorker fresh(paths, headlessWorkerContext(), FrameEconomies{}.evaluationDrawMs());
    const EvaluationResult alone = evaluate(fresh);
    EXPECT_FALSE(alone.solutionKept);
    ASSERT_TRUE(edited.studentRendered);
    EXPECT_FALSE(edited.studentStats.passes(false, 0));
    EXPECT_EQ(edited.studentStats.outside, alone.studentStats.outside);
    EXPECT_EQ(edited.studentStats.worstExcess, alone.studentStats.worstExcess);
    EXPECT_EQ(edited.studentStats.worstIndex, alone.studentStats.worstIndex);
    EXPECT_EQ(edited.studentValue.pixels, alone.studentValue.pixels);
    EXPECT_EQ(edited.solutionValue.pixels, alone.solutionValue.pixels);

    // Each of the solution's inputs draws it anew: a parameter, the camera, a light, a material,
    // the picture's side.
    const std::vector<std::function<void()>> changes = {
        [&] { job.params.set("light_dir", glm::dvec3(0.6, 0.6, 0.52)); },
        [&] { job.scene.camera.position.x += 0.1; },
        [&] { job.scene.lights[0].color *= 2.0; },
        [&] { job.scene.materials[0].albedo *= 0.5; },
        [&] { job.side = 96; },
    };
    for (size_t i = 0; i < changes.size(); ++i) {
        changes[i]();
        EXPECT_FALSE(evaluate(worker).solutionKept) << "change " << i;
        EXPECT_TRUE(evaluate(worker).solutionKept) << "change " << i << ", again";
    }
}
