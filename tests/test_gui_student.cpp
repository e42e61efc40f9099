// The GUI with the student's files as they are the night before a deadline: edited while the
// window is open, broken, graded from the console. Under Xvfb; the run is scripted with the
// console's own lines (--command: `wait`, `status`, `screenshot`), and the test edits the
// files while the window is open, between the run's `wait --file` lines.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

#include "assets/image_io.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

bool haveXvfb() {
    return std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
}

std::string readText(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// `pbrlab --verbose gui ARGS --window 1200x760 --frames 2`, run from dir/kit with HOME=dir (the
// remembered state is the test's own) in the background; stdout and stderr go to dir/log.txt.
// Stopped after 5 minutes (a window that hangs fails the test).
class BackgroundGui {
public:
    BackgroundGui(const test::TempDir& dir, const std::string& args) : log_(dir.path / "log.txt") {
        fs::create_directories(dir.path / "kit");
        const std::string cmd =
            "cd " + (dir.path / "kit").string() + " && HOME=" + dir.path.string() +
            " timeout 300 xvfb-run -a -s '-screen 0 1280x800x24' " PBRLAB_EXECUTABLE
            " --verbose gui " +
            args + " --window 1200x760 --frames 2 > " + log_.string() + " 2>&1";
        thread_ = std::thread([this, cmd] {
            status_ = std::system(cmd.c_str());
            finished_ = true;
        });
    }
    ~BackgroundGui() {
        if (thread_.joinable()) thread_.join();
    }
    // Until the log holds `text` (true), or the window has closed or `seconds` have passed.
    bool waitFor(const std::string& text, double seconds = 240) {
        const auto until =
            std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (std::chrono::steady_clock::now() < until) {
            if (readText(log_).find(text) != std::string::npos) return true;
            if (finished_) return false;
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        }
        return false;
    }
    int finish() {
        thread_.join();
        return status_;
    }
    std::string log() const { return readText(log_); }

private:
    fs::path log_;
    std::thread thread_;
    int status_ = -1;
    std::atomic<bool> finished_ = false;
};

// What the console's `status` printed, the n-th time (0: the first): up to the next line typed.
std::string statusReport(const std::string& log, int n) {
    size_t at = 0;
    for (int i = 0; i <= n; ++i) {
        at = log.find("> status\n", at);
        if (at == std::string::npos) return {};
        at += 9;
    }
    return log.substr(at, log.find("\n> ", at) - at);
}

// The pixels of the compile error's box above the picture (its background colour).
int errorBoxPixels(const fs::path& shot) {
    const Image image = readImage(shot);
    int n = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            n += std::abs(image.at(x, y, 0) - 0.25f) < 0.01f &&
                 std::abs(image.at(x, y, 1) - 0.08f) < 0.01f &&
                 std::abs(image.at(x, y, 2) - 0.08f) < 0.01f;
    return n;
}

// ndf's reference solution, as a student who got it right would write it.
const char* const kGoodNdf = R"(float distributionGGX(vec3 N, vec3 H, float roughness)
{
    float a = roughness * roughness;
    float a2 = max(a * a, 1e-7);
    float NdotH = max(dot(N, H), 0.0);
    float NdotH2 = NdotH * NdotH;
    float d = (1.0 - NdotH2) + NdotH2 * a2;
    return a2 / (PI * d * d);
}
)";

}  // namespace

// The student saves a file that does not compile while the window is open: the error (file,
// line and the compiler's text) stays above the picture through the evaluations that follow
// (the badge's grade, an input moved), which show the last program that compiled and say so,
// until the file compiles again.
TEST(GuiStudent, ACompileErrorStaysOnScreenUntilTheFileCompilesAgain) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    const fs::path kit = dir.path / "kit", ndf = dir.write("kit/ndf.glsl", kGoodNdf);
    const fs::path broken = dir.path / "broken.png", fixed = dir.path / "fixed.png";
    BackgroundGui gui(dir, "ndf --submission " + kit.string() +
                               " --command wait"  // evaluated and graded as saved
                               " --command 'wait --timeout 200 --file " +
                               (dir.path / "go1").string() +
                               "'"
                               " --command wait"  // the broken file: evaluated, graded
                               " --command 'set light_dir=0,1,1' --command wait"  // again
                               " --command status --command 'screenshot " +
                               broken.string() + "' --command 'wait --timeout 200 --file " +
                               (dir.path / "go2").string() +
                               "'"
                               " --command wait --command status --screenshot " +
                               fixed.string());
    const bool started = gui.waitFor("> wait --timeout 200 --file " + (dir.path / "go1").string());
    std::string bad = kGoodNdf;
    bad.replace(bad.find("(PI * d * d);"), 13, "(PI * d * d) +;");  // line 8
    dir.write("kit/ndf.glsl", bad);
    dir.write("go1", "");
    const bool brokenShown =
        gui.waitFor("> wait --timeout 200 --file " + (dir.path / "go2").string());
    dir.write("kit/ndf.glsl", kGoodNdf);
    dir.write("go2", "");
    ASSERT_EQ(gui.finish(), 0) << gui.log();
    ASSERT_TRUE(started && brokenShown) << gui.log();
    const std::string log = gui.log();

    // Broken, after the grade and an evaluation with the light moved: the error is on screen,
    // file:line and the compiler's words, and the statistics say whose they are.
    const std::string whileBroken = statusReport(log, 0);
    EXPECT_NE(whileBroken.find("badge: compile error"), std::string::npos) << log;
    EXPECT_NE(whileBroken.find("ndf.glsl does not compile: the picture and the statistics are of "
                               "the last program that compiled, "),
              std::string::npos)
        << log;
    EXPECT_NE(whileBroken.find(ndf.string() + ":8"), std::string::npos) << log;
    EXPECT_NE(whileBroken.find("syntax error"), std::string::npos) << log;
    EXPECT_NE(whileBroken.find("showing the last program that compiled, "), std::string::npos)
        << log;
    EXPECT_NE(whileBroken.find("last good worst"), std::string::npos) << log;
    // Evaluated more than once while broken (the grade's arrival, the light), error kept.
    const size_t brokeAt = log.find("[gui] ndf.glsl does not compile");
    ASSERT_NE(brokeAt, std::string::npos) << log;
    size_t evaluations = 0;
    for (size_t at = log.find("evaluated ndf", brokeAt);
         at != std::string::npos && at < log.find("> status");
         at = log.find("evaluated ndf", at + 1))
        ++evaluations;
    EXPECT_GE(evaluations, 2u) << log;

    // Fixed: the error is gone, the statistics are the student's again.
    const std::string afterFix = statusReport(log, 1);
    EXPECT_NE(log.find("[gui] ndf.glsl compiles again"), std::string::npos) << log;
    EXPECT_EQ(afterFix.find("does not compile"), std::string::npos) << afterFix;
    EXPECT_NE(afterFix.find("student   worst"), std::string::npos) << afterFix;
    EXPECT_EQ(afterFix.find("last program that compiled"), std::string::npos) << afterFix;

    // And in the window: the error's box above the picture, then none.
    EXPECT_GT(errorBoxPixels(broken), 5000);
    EXPECT_EQ(errorBoxPixels(fixed), 0);
}

// The console's `check ndf` grades the open workspace (here found in the folder the lab was
// started in), as the badge does, not the reference solution; --submission '' still asks
// for the reference solution, and the console's help says so.
TEST(GuiStudent, TheConsolesCheckGradesTheOpenWorkspace) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    const fs::path kit = dir.path / "kit";
    dir.write("kit/ndf.glsl",
              "float distributionGGX(vec3 N, vec3 H, float roughness) { return 0.5; }\n");
    BackgroundGui gui(dir,
                      "ndf --command 'check ndf' --command \"check ndf --submission ''\" "
                      "--command help --command wait --command status");
    ASSERT_EQ(gui.finish(), 0) << gui.log();
    const std::string log = gui.log();
    const size_t inKit = log.find("> check ndf\n(on the workspace: --submission " +
                                  fs::canonical(kit).string() + ")\n");
    const size_t solution = log.find("> check ndf --submission ''\n");
    ASSERT_NE(inKit, std::string::npos) << log;
    ASSERT_NE(solution, std::string::npos) << log;
    const size_t fail = log.find("ndf: FAIL", inKit), pass = log.find("ndf: PASS", solution);
    EXPECT_LT(fail, solution) << log;
    EXPECT_NE(pass, std::string::npos) << log;
    EXPECT_NE(log.find("work on the open workspace unless the line gives one"), std::string::npos)
        << log;
    // The badge says what the console's check said.
    EXPECT_NE(statusReport(log, 0).find("badge: fails"), std::string::npos) << log;
}

// A FIFO (a student's `mkfifo ndotl.glsl`) when the window opens, and a good ndf.glsl replaced
// by a file over 10 MB while it is open: the window does not hang opening them, and says why
// they are not used, in the place of the compile error, with the solution's picture, through
// the evaluations that follow (the renderer refuses a file once per change, then would draw
// its last good program).
TEST(GuiStudent, AFifoOrAHugeFileIsRefusedOnScreenWithoutBlocking) {
    if (!haveXvfb()) GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    const fs::path kit = dir.path / "kit", go = dir.path / "go";
    fs::create_directories(kit);
    ASSERT_EQ(mkfifo((kit / "ndotl.glsl").c_str(), 0644), 0);
    dir.write("kit/ndf.glsl", kGoodNdf);
    const fs::path shot = dir.path / "fifo.png";
    BackgroundGui gui(dir, "ndotl --submission " + kit.string() +
                               " --command wait --command status --command 'screenshot " +
                               shot.string() +
                               "' --command 'step ndf' --command wait --command 'wait --timeout "
                               "200 --file " +
                               go.string() + "' --command wait --command status");
    const bool started = gui.waitFor("> wait --timeout 200 --file " + go.string());
    dir.write("huge.glsl", std::string(11 * 1024 * 1024, ' ') + kGoodNdf);
    fs::rename(dir.path / "huge.glsl", kit / "ndf.glsl");  // as an editor saves: at once
    dir.write("go", "");
    ASSERT_EQ(gui.finish(), 0) << gui.log();
    ASSERT_TRUE(started) << gui.log();
    const std::string log = gui.log();
    const std::string fifo = statusReport(log, 0), huge = statusReport(log, 1);
    EXPECT_NE(fifo.find("ndotl.glsl cannot be used, so the picture is the solution's"),
              std::string::npos)
        << log;
    EXPECT_NE(fifo.find((kit / "ndotl.glsl").string() + ": refused: not a regular file (a FIFO)"),
              std::string::npos)
        << log;
    EXPECT_EQ(fifo.find("student   worst"), std::string::npos) << log;
    EXPECT_NE(huge.find("ndf.glsl cannot be used, so the picture is the solution's"),
              std::string::npos)
        << log;
    EXPECT_NE(huge.find((kit / "ndf.glsl").string() + ": refused: larger than 10 MB"),
              std::string::npos)
        << log;
    EXPECT_EQ(huge.find("student   worst"), std::string::npos) << log;
    EXPECT_EQ(huge.find("last good"), std::string::npos) << log;
    EXPECT_GT(errorBoxPixels(shot), 5000);
}
