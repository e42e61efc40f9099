// The GUI for real: a window under Xvfb, scripted with --frames and --screenshot.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "assets/image_io.h"
#include "test_support.h"

using namespace pbrlab;

namespace {

bool haveXvfb() {
    return std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
}

// Runs `pbrlab --verbose gui ARGS --window 1200x760 --frames FRAMES --screenshot SHOT` from
// dir/kit with HOME=dir (so the remembered state is the test's own); stdout and stderr go to
// dir/log.txt. Returns the exit status.
int runGui(const test::TempDir& dir, const std::string& args, const std::filesystem::path& shot,
           int frames = 4) {
    std::filesystem::create_directories(dir.path / "kit");
    std::string cmd =
        "cd " + (dir.path / "kit").string() + " && HOME=" + dir.path.string() +
        " xvfb-run -a -s '-screen 0 1280x800x24' " PBRLAB_EXECUTABLE " --verbose gui " + args +
        " --window 1200x760 --frames " + std::to_string(frames) + " --screenshot " + shot.string() +
        " > " + (dir.path / "log.txt").string() + " 2>&1";
    return std::system(cmd.c_str());
}

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Not blank: a lit object, the dark panels and the text give many distinct values.
void expectWindowShot(const std::filesystem::path& shot) {
    Image image = readImage(shot);
    EXPECT_EQ(image.width, 1200);
    EXPECT_EQ(image.height, 760);
    double lo = 1, hi = 0;
    for (float v : image.pixels) lo = std::min<double>(lo, v), hi = std::max<double>(hi, v);
    EXPECT_GT(hi - lo, 0.5);
}

}  // namespace

TEST(Gui, ScriptedRunUnderXvfbWritesTheWindow) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    dir.write("kit/ndotl.glsl", "float lambertCosine(vec3 N, vec3 L) { return dot(N, L); }\n");
    auto shot = dir.path / "s.png";
    ASSERT_EQ(runGui(dir, "ndotl", shot), 0) << readText(dir.path / "log.txt");
    expectWindowShot(shot);
    // Still input: the picture was evaluated against the CPU reference (the statistics).
    EXPECT_NE(readText(dir.path / "log.txt").find("evaluated ndotl against the CPU reference"),
              std::string::npos);
    // The parameters were remembered under the test's own HOME.
    EXPECT_TRUE(std::filesystem::exists(dir.path / ".config/pbrlab/gui.json"));
}

TEST(Gui, ShowsAGltfModelWithTheProgramsTabAndRemembersIt) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    const std::string model = PBRLAB_SOURCE_DIR "/assets/models/textured-sphere.glb";
    auto shot = dir.path / "model.png";
    ASSERT_EQ(runGui(dir, "--model " + model + " --module reflectance --tab programs", shot), 0)
        << readText(dir.path / "log.txt");
    expectWindowShot(shot);
    // The model, not the step's sphere, was drawn: its embedded maps were read (the verbose
    // journal) and the G-buffer compiled with them.
    std::string log = readText(dir.path / "log.txt");
    EXPECT_NE(log.find("textured-sphere.glb#image"), std::string::npos) << log;
    EXPECT_NE(log.find("HAS_METALLIC_ROUGHNESS_MAP=1"), std::string::npos) << log;
    // The choice is remembered, and the next start shows the model again without --model.
    EXPECT_NE(readText(dir.path / ".config/pbrlab/gui.json").find("textured-sphere.glb"),
              std::string::npos);
    ASSERT_EQ(runGui(dir, "reflectance", shot), 0) << readText(dir.path / "log.txt");
    log = readText(dir.path / "log.txt");
    EXPECT_NE(log.find("textured-sphere.glb#image"), std::string::npos) << log;
}

TEST(Gui, ABrokenModelShowsItsErrorInsteadOfCrashing) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    auto broken = dir.write("broken.glb", "0123456789");
    auto shot = dir.path / "broken.png";
    ASSERT_EQ(runGui(dir, "--model " + broken.string() + " reflectance", shot), 0)
        << readText(dir.path / "log.txt");
    // The step's own scene stays on screen; the error names the file (in the window, and in
    // the host log that --verbose prints).
    expectWindowShot(shot);
    std::string log = readText(dir.path / "log.txt");
    size_t error = log.find("[scene] ");
    ASSERT_NE(error, std::string::npos) << log;
    EXPECT_NE(log.find("broken.glb: ", error), std::string::npos) << log;
    // A file that did not load is not remembered.
    EXPECT_EQ(readText(dir.path / ".config/pbrlab/gui.json").find("broken.glb"), std::string::npos);
}

TEST(Gui, RejectsAnUnknownTab) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    EXPECT_NE(runGui(dir, "--tab nonsense", dir.path / "none.png"), 0);
    EXPECT_NE(readText(dir.path / "log.txt").find("--tab nonsense: unknown tab"),
              std::string::npos);
}

// Dragging, scripted: every frame turns the camera, so every frame is a live one (the picture
// drawn and mapped for display on the GPU, nothing read back), and the frame times are printed.
TEST(Gui, OrbitDrawsLiveFramesAndPrintsTheirTimes) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    auto shot = dir.path / "orbit.png";
    ASSERT_EQ(runGui(dir, "ndf --orbit", shot), 0) << readText(dir.path / "log.txt");
    expectWindowShot(shot);
    const std::string log = readText(dir.path / "log.txt");
    EXPECT_NE(log.find("frame: 1 frames at 1200x760"), std::string::npos) << log;
    // Its side follows the time budget (tests/test_live_view.cpp): only that it is printed.
    EXPECT_NE(log.find("of which the picture (median side): 1 frames at "), std::string::npos)
        << log;
    // The evaluation against the CPU reference ran once, after the frames (the input never
    // stopped during them): the settled frame, --orbit's baseline.
    const size_t frames = log.find("frame: 1 frames"), evaluated = log.find("evaluated ndf");
    ASSERT_NE(evaluated, std::string::npos) << log;
    EXPECT_GT(evaluated, frames) << log;
    EXPECT_EQ(log.find("evaluated ndf", evaluated + 1), std::string::npos) << log;
    EXPECT_NE(log.find("settled frame (512x512, evaluated against the CPU reference)"),
              std::string::npos)
        << log;
}

// While the camera turns, each frame is drawn over the last only where it changed (the picture,
// the frame's time): --check-redraw draws each also whole, through the same ImGui backend, and
// counts the pixels where the two differ. A picture left stale, or a scissor a pixel off, makes
// thousands (measured: 2.8 million over 30 frames with the picture's tiles not redrawn, 15479
// with the scissors' left edges a pixel to the left).
TEST(Gui, OrbitRedrawsOnlyWhatChanged) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    auto shot = dir.path / "orbit.png";
    ASSERT_EQ(runGui(dir, "ndf --orbit --check-redraw", shot, 20), 0)
        << readText(dir.path / "log.txt");
    expectWindowShot(shot);
    const std::string log = readText(dir.path / "log.txt");
    EXPECT_NE(log.find("redraw check: 20 frames also drawn whole, 0 pixels differ"),
              std::string::npos)
        << log;
    // The first frame is drawn whole; ImGui lays the windows out over the next; then the
    // picture (at most 512x512 of 1200x760, 29%) and a few lines of text: 31% measured.
    int drawn = 0, inPart = 0, unchanged = 0;
    double median = 100;
    const size_t at = log.find("window redrawn: ");
    ASSERT_NE(at, std::string::npos) << log;
    ASSERT_EQ(std::sscanf(log.c_str() + at,
                          "window redrawn: %d frames drawn, %d of them only where they changed, "
                          "%d unchanged; median %lf%%",
                          &drawn, &inPart, &unchanged, &median),
              4)
        << log;
    EXPECT_GE(inPart, 15) << log;
    EXPECT_LT(median, 40) << log;
}

// --no-frame-economies: what a GPU would draw, by the same path. Every frame is drawn whole,
// the live picture at full size (with the economies, the test above: 15 or more of 20 frames
// drawn in part).
TEST(Gui, WithoutFrameEconomiesEveryFrameIsDrawnWholeAtFullSize) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    auto shot = dir.path / "orbit.png";
    ASSERT_EQ(runGui(dir, "ndf --orbit --no-frame-economies --check-redraw", shot, 8), 0)
        << readText(dir.path / "log.txt");
    expectWindowShot(shot);
    const std::string log = readText(dir.path / "log.txt");
    EXPECT_NE(log.find("of which the picture (median side): 5 frames at 512x512"),
              std::string::npos)
        << log;
    EXPECT_NE(log.find("window redrawn: 8 frames drawn, 0 of them only where they changed"),
              std::string::npos)
        << log;
    EXPECT_NE(log.find("redraw check: 8 frames also drawn whole, 0 pixels differ"),
              std::string::npos)
        << log;
}

TEST(Gui, AnErrorBudgetChoosesTheEnvironmentsSettingsAsPrecomputeDoes) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    auto shot = dir.path / "budget.png";
    ASSERT_EQ(runGui(dir, "split_sum --error-budget 0.05", shot), 0)
        << readText(dir.path / "log.txt");
    expectWindowShot(shot);
    const std::string log = readText(dir.path / "log.txt");
    // Measured (docs/ibl.md): on the sky, 0.05 is met by 8 bins per face side, where the
    // default uses 16 (mean errors 0.0055 / 0.038 / 0.0008).
    EXPECT_NE(log.find("error budget 0.05 on sky: met"), std::string::npos) << log;
    EXPECT_NE(log.find("by bins 8"), std::string::npos) << log;
    EXPECT_NE(log.find("[environment] sky (env256_src64_irr16 bins 8"), std::string::npos) << log;
}

// The console, scripted: a GUI-local line changes the state as the parameter's widget does, a
// shell command runs as on the shell (its file written, its output in the console), and a
// wrong one gets the shell's message. The run waits for the commands before its last frame.
TEST(Gui, ConsoleLinesChangeTheStateAndRunTheShellsCommands) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    auto shot = dir.path / "console.png", picture = dir.path / "ndf.png";
    ASSERT_EQ(runGui(dir,
                     "hammersley --command 'set samples=32' --command 'render ndf --size 40x24 "
                     "--out " +
                         picture.string() + "' --command 'render ndf --bogus'",
                     shot),
              0)
        << readText(dir.path / "log.txt");
    expectWindowShot(shot);
    // hammersley's samples (default 64) as `set` left them, saved with the state on exit.
    const std::string saved = readText(dir.path / ".config/pbrlab/gui.json");
    EXPECT_NE(saved.find("\"samples\": \"32\""), std::string::npos) << saved;
    const Image image = readImage(picture);
    EXPECT_EQ(image.width, 40);
    EXPECT_EQ(image.height, 24);
    const std::string log = readText(dir.path / "log.txt");
    EXPECT_NE(log.find("wrote " + picture.string() + " (40x24"), std::string::npos) << log;
    EXPECT_NE(log.find("(exit status 0)"), std::string::npos) << log;
    EXPECT_NE(log.find("> render ndf --bogus\n--out is required"), std::string::npos) << log;
}

// Scripts written for earlier versions: gui --module ID and gui --size WxH (the window) still
// work; --size says that it is deprecated.
TEST(Gui, TheOlderSpellingsStillWork) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    const auto shot = dir.path / "old.png";
    const std::string cmd = "cd " + dir.path.string() + " && HOME=" + dir.path.string() +
                            " xvfb-run -a -s '-screen 0 1280x800x24' " PBRLAB_EXECUTABLE
                            " gui --module ndf --size 640x480 --frames 2 --screenshot " +
                            shot.string() + " > log.txt 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << readText(dir.path / "log.txt");
    EXPECT_EQ(readImage(shot).width, 640);
    EXPECT_EQ(readImage(shot).height, 480);
    EXPECT_NE(readText(dir.path / "log.txt").find("gui --size is deprecated"), std::string::npos);
    EXPECT_NE(readText(dir.path / ".config/pbrlab/gui.json").find("\"module\": \"ndf\""),
              std::string::npos);
}
