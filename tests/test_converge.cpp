// Error against run time: the brute-force estimator converges towards the CPU truth as N
// grows, and every approximation reports finite numbers.
#include <gtest/gtest.h>

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
    double first = -1, last = -1;
    for (const auto& r : rows) {
        EXPECT_TRUE(std::isfinite(r.rmse) && std::isfinite(r.maxError) && r.ms > 0) << r.setting;
        if (r.method == "brute_force") (first < 0 ? first : last) = r.displayRmse;
    }
    // N = 1 against N = 256 (quick runs 1, 16, 256), in display units (linear RMSE is ruled
    // by the few pixels whose samples hit the sun). Half is a loose, noise-proof bound.
    EXPECT_LT(last, 0.5 * first);
    EXPECT_TRUE(std::filesystem::exists(dir.path / "converge.csv"));
    EXPECT_TRUE(std::filesystem::exists(dir.path / "converge.gp"));
}
