// False failures of the estimator checks: every correct estimator of tests/variants/<id>/
// that has a seed (a line `const uint SEED = 0u;`) graded at many seeds, with the
// estimator's statistical checks alone (StepGrader::runEstimatorStatistics: the converged
// integrals come from the disk cache after the first seed). No check may fail at any seed.
//
//   PBRLAB_SEEDS=200 PBRLAB_SEEDS_CSV=seeds.csv build/tests/pbrlab_tests
//       --gtest_filter='EstimatorSeeds.*'   (one line)
//
// measures seeds 1..200 (seed 0 is the file as it is, graded by test_variants.cpp) and prints,
// per family and check, the failures and the worst statistic (docs/grading.md, "Estimators:
// dynamic range, linearity, false failures"). Without PBRLAB_SEEDS: seed 1 only.
// PBRLAB_SEEDS_STEPS=mc_specular,brdf_lut: those steps' families only, PBRLAB_SEEDS_FAMILY=TEXT
// the families whose file name holds TEXT (to share the work among processes).
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "assets/envgen.h"
#include "course/autograder.h"
#include "gl/context.h"
#include "grading/step_grader.h"
#include "render/renderer.h"
#include "steps/contract.h"
#include "test_support.h"
#include "util/error.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

struct Family {
    std::string module;
    fs::path file;
    std::string text;
};

const std::regex kSeedLine(R"(const uint SEED = [0-9]+u;)");

std::vector<Family> seededFamilies() {
    std::vector<Family> out;
    const char* only = std::getenv("PBRLAB_SEEDS_STEPS");
    for (const std::string id : {"mc_specular", "irradiance", "prefilter", "brdf_lut"}) {
        if (only && ("," + std::string(only) + ",").find("," + id + ",") == std::string::npos)
            continue;
        const fs::path dir = fs::path(PBRLAB_SOURCE_DIR) / "tests" / "variants" / id;
        for (const auto& f : fs::directory_iterator(dir)) {
            std::ifstream in(f.path());
            std::stringstream text;
            text << in.rdbuf();
            const char* family = std::getenv("PBRLAB_SEEDS_FAMILY");
            if (family && f.path().filename().string().find(family) == std::string::npos) continue;
            if (std::regex_search(text.str(), kSeedLine)) out.push_back({id, f.path(), text.str()});
        }
    }
    std::sort(out.begin(), out.end(),
              [](const Family& a, const Family& b) { return a.file < b.file; });
    return out;
}

// The statistic a check is judged by, as "larger is worse" where it has one.
double statistic(const CheckReport& c) {
    if (c.kind == "values") return c.worstExcess;  // x the tolerance
    if (c.name.rfind("no systematic error", 0) == 0) return std::abs(c.measured);  // |z|
    if (c.name.rfind("the error falls", 0) == 0) return -c.measured;  // the fall, negated
    return c.measured;  // points with the same value; the overall scale
}

}  // namespace

TEST(EstimatorSeeds, NoCorrectEstimatorFailsAtAnySeed) {
    const char* seedsEnv = std::getenv("PBRLAB_SEEDS");
    const int seeds = seedsEnv ? std::max(1, std::atoi(seedsEnv)) : 1;
    const std::vector<Family> families = seededFamilies();
    ASSERT_GE(families.size(), std::getenv("PBRLAB_SEEDS_STEPS") ? 1u : 4u);
    auto context = createHeadlessContext();
    DataPaths paths(PBRLAB_SOURCE_DIR);
    ModuleRegistry modules(PBRLAB_MODULE_DIR);
    LabRenderer renderer(paths);
    std::ofstream csv;
    if (const char* file = std::getenv("PBRLAB_SEEDS_CSV")) {
        csv.open(file);
        csv << "family,seed,check,passed,statistic,outside,points\n";
    }
    struct Summary {
        int runs = 0, failures = 0;
        double worst = -1e300;
    };
    for (const Family& f : families) {
        const LoadedModule& m = modules.find(f.module);
        const std::string family = f.module + "/" + f.file.filename().string();
        std::map<std::string, Summary> summary;
        for (int seed = 1; seed <= seeds; ++seed) {
            test::TempDir kit;
            kit.write(f.module + ".glsl",
                      std::regex_replace(f.text, kSeedLine,
                                         "const uint SEED = " + std::to_string(seed) + "u;"));
            GradeSettings settings;
            settings.feedback = false;
            settings.robustness = false;
            const StepResult r = step_grading::StepGrader(renderer, m, paths, {kit.path}, settings)
                                     .runEstimatorStatistics();
            for (const CheckReport& c : r.checks) {
                // One row per check, the counts and environments in its name.
                Summary& s = summary[c.name];
                ++s.runs;
                s.failures += !c.passed;
                s.worst = std::max(s.worst, statistic(c));
                if (csv.is_open())
                    csv << family << "," << seed << ",\"" << c.name << "\"," << c.passed << ","
                        << statistic(c) << "," << c.outside << "," << c.points << "\n";
                EXPECT_TRUE(c.passed)
                    << family << " seed " << seed << ": " << c.name << ": " << c.detail;
            }
        }
        for (const auto& [name, s] : summary)
            std::printf("[ seeds    ] %s: %s: %d of %d failed, worst statistic %.4g\n",
                        family.c_str(), name.c_str(), s.failures, s.runs, s.worst);
    }
}

// The environments of the estimator checks (envgen.h): sky-hdr is the soft sky plus the lobe,
// texel by texel; a factor scales every texel; the lobe spans 1e4 to 1e5 (in the sun's colour).
TEST(EstimatorEnvironments, SkyHdrIsTheSoftSkyPlusTheLobeAndScalesExactly) {
    const Image soft = generateEnvironment("sky-soft"), lobe = generateEnvironment("hdr-lobe");
    const Image sum = generateEnvironment("sky-hdr");
    const Image scaled = generateEnvironment("sky-hdr*1024");
    ASSERT_EQ(sum.pixels.size(), soft.pixels.size());
    ASSERT_EQ(lobe.pixels.size(), soft.pixels.size());
    float lo = 1e30f, hi = 0;
    for (size_t i = 0; i < sum.pixels.size(); ++i) {
        ASSERT_EQ(sum.pixels[i], float(double(soft.pixels[i]) + double(lobe.pixels[i]))) << i;
        ASSERT_EQ(scaled.pixels[i], 1024.0f * sum.pixels[i]) << i;
        if (i % 3 == 0) lo = std::min(lo, lobe.pixels[i]), hi = std::max(hi, lobe.pixels[i]);
    }
    // Red is the sun colour's largest channel (1.0): the lobe's own range, sampled at texel
    // centres (within a texel of either end).
    EXPECT_NEAR(lo, 1e4, 1e4 * 1e-3);
    EXPECT_NEAR(hi, 1e5, 1e5 * 1e-3);
    EXPECT_TRUE(isGeneratedEnvironment("sky-hdr*0.0009765625"));
    EXPECT_FALSE(isGeneratedEnvironment("sky-hdr*x"));
    EXPECT_THROW(generateEnvironment("nothing"), Error);
}
