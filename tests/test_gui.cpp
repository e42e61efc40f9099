// The GUI for real: a window under Xvfb, scripted with --frames and --screenshot.
#include <gtest/gtest.h>

#include <cstdlib>

#include "pbrlab/image.h"
#include "test_support.h"

using namespace pbrlab;

TEST(Gui, ScriptedRunUnderXvfbWritesTheWindow) {
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0)
        GTEST_SKIP() << "xvfb-run is not installed";
    test::TempDir dir;
    dir.write("kit/ndotl.glsl", "float lambertCosine(vec3 N, vec3 L) { return dot(N, L); }\n");
    auto shot = dir.path / "s.png";
    std::string cmd = "cd " + (dir.path / "kit").string() + " && HOME=" + dir.path.string() +
                      " xvfb-run -a -s '-screen 0 1280x800x24' " PBRLAB_EXECUTABLE
                      " gui --module ndotl --size 1200x760 --frames 4 --screenshot " +
                      shot.string() + " > " + (dir.path / "log.txt").string() + " 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
    Image image = readImage(shot);
    EXPECT_EQ(image.width, 1200);
    EXPECT_EQ(image.height, 760);
    // Not blank: the lit sphere, the dark panels and the text give many distinct values.
    double lo = 1, hi = 0;
    for (float v : image.pixels) lo = std::min<double>(lo, v), hi = std::max<double>(hi, v);
    EXPECT_GT(hi - lo, 0.5);
    // The parameters were remembered under the test's own HOME.
    EXPECT_TRUE(std::filesystem::exists(dir.path / ".config/pbrlab/gui.json"));
}
