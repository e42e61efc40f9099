// Error against run time: the brute-force estimator converges towards the CPU truth as N
// grows, and every approximation reports finite numbers.
#include <gtest/gtest.h>

#include <iostream>

#include "converge.h"
#include "gl/context.h"
#include "test_support.h"

using namespace pbrlab;

TEST(Converge, BruteForceErrorFallsWithSamplesAndTheReportIsWritten) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    LabRenderer renderer{paths};
    IblSettings small;  // keep the precomputes of the test short on 2 cores
    small.prefilterSize = 32;
    small.environmentSize = 128;
    renderer.setIblSettings(small);
    ConvergeOptions o;
    o.size = 24;
    o.truthSamples = 4096;
    o.quick = true;
    test::TempDir dir;
    o.out = dir.path;
    std::vector<ConvergeRow> rows = runConverge(renderer, paths, o);
    writeConvergeReport(rows, o.out);
    std::vector<double> bruteForce;
    double splitSum = -1;
    for (const auto& r : rows) {
        EXPECT_TRUE(std::isfinite(r.rmse) && std::isfinite(r.maxError) && r.ms > 0) << r.setting;
        std::cout << r.method << " " << r.setting << " display rmse " << r.displayRmse << "\n";
        if (r.method == "brute_force") bruteForce.push_back(r.displayRmse);
        if (r.setting == "prefilter=256 fis=on") splitSum = r.displayRmse;
    }
    // Quick runs N = 1, 16, 256. In display units (linear RMSE is ruled by the few pixels
    // whose samples hit the 20000-bright sun) the error falls with N, slowly and not
    // monotonically at this tiny size: BRDF sampling rarely finds the sun in wide lobes
    // (measured 0.140, 0.116, 0.120 at 24x24; 0.128, 0.114, 0.106 at 48x48). So the test
    // asks for N = 256 below N = 1, and the split sum with filtered sampling below N = 256
    // (measured 0.066 and 0.045).
    ASSERT_EQ(bruteForce.size(), 3u);
    EXPECT_LT(bruteForce[2], bruteForce[0]);
    EXPECT_LT(splitSum, bruteForce[2]);
    EXPECT_TRUE(std::filesystem::exists(dir.path / "converge.csv"));
    EXPECT_TRUE(std::filesystem::exists(dir.path / "converge.gp"));
}
