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
// the families whose file name holds TEXT (to share the work among processes),
// PBRLAB_SEEDS_CHECKS=sun,picture only those parts of the statistics (convergence, sun,
// picture).
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
#include "ibl/precompute.h"
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
            // Correct estimators only: a mistake may have a seed too (one correct without a sun).
            if (f.path().filename().string().rfind("correct_", 0) == 0 &&
                std::regex_search(text.str(), kSeedLine))
                out.push_back({id, f.path(), text.str()});
        }
    }
    std::sort(out.begin(), out.end(),
              [](const Family& a, const Family& b) { return a.file < b.file; });
    return out;
}

// The statistic a check is judged by, as "larger is worse" where it has one.
double statistic(const CheckReport& c) {
    if (c.kind == CheckKind::Values) return c.worstExcess;  // x the tolerance
    if (c.name.rfind("no systematic error", 0) == 0) return std::abs(c.measured);  // |z|
    if (c.name.rfind("the error falls", 0) == 0) return -c.measured;  // the fall, negated
    return c.measured;  // points with the same value; the overall scale
}

}  // namespace

TEST(EstimatorSeeds, NoCorrectEstimatorFailsAtAnySeed) {
    const char* seedsEnv = std::getenv("PBRLAB_SEEDS");
    const int seeds = seedsEnv ? std::max(1, std::atoi(seedsEnv)) : 1;
    const std::vector<Family> families = seededFamilies();
    ASSERT_GE(families.size(), std::getenv("PBRLAB_SEEDS_STEPS") ? 1u : 3u);
    auto context = createHeadlessContext();
    DataPaths paths(PBRLAB_SOURCE_DIR);
    ModuleRegistry modules(PBRLAB_MODULE_DIR);
    LabRenderer renderer(paths);
    std::ofstream csv;
    if (const char* file = std::getenv("PBRLAB_SEEDS_CSV")) {
        csv.open(file);
        csv << "family,seed,check,passed,statistic,outside,points\n";
    }
    unsigned parts = 0;
    const std::string checks = std::getenv("PBRLAB_SEEDS_CHECKS")
                                   ? std::getenv("PBRLAB_SEEDS_CHECKS")
                                   : "convergence,sun,picture";
    using Grader = step_grading::StepGrader;
    if (checks.find("convergence") != std::string::npos) parts |= Grader::Convergence;
    if (checks.find("sun") != std::string::npos) parts |= Grader::Sun;
    if (checks.find("picture") != std::string::npos) parts |= Grader::Picture;
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
                                     .runEstimatorStatistics(parts);
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

// sky-sun (envgen.h): in the cube the estimators read (256 a face), a sun well under a degree
// (every texel above 1% of the brightest within 0.6 degrees of it: the disc's 0.27 degrees
// plus a texel's 0.35) and 1e4 times the median or more, the dynamic range of a real outdoor
// sky; its bright texels (brightTexels, what the sun check resolves) are the sun and nothing
// else: the rest is no brighter than sky-soft, whose brightest feature is about 8.
TEST(EstimatorEnvironments, SkySunHoldsASubDegreeSunOfRealDynamicRange) {
    const Image sky = generateEnvironment("sky-sun"), sun = brightTexels(sky);
    ASSERT_EQ(sky.pixels.size(), sun.pixels.size());
    float skyAlone = 0;
    for (size_t i = 0; i < sky.pixels.size(); ++i)
        skyAlone = std::max(skyAlone, sky.pixels[i] - sun.pixels[i]);
    EXPECT_LT(skyAlone, 10.0f);
    const auto cube = equirectToCube(sky, 256, 1);
    std::vector<double> luminance;
    double brightest = 0;
    glm::dvec3 at(0);
    for (int face = 0; face < 6; ++face)
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) {
                const Image& im = cube[0][size_t(face)];
                const double l =
                    0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
                luminance.push_back(l);
                if (l > brightest) brightest = l, at = cubeTexelDirection(face, x, y, 256);
            }
    std::vector<double> sorted = luminance;
    std::nth_element(sorted.begin(), sorted.begin() + long(sorted.size() / 2), sorted.end());
    const double median = sorted[sorted.size() / 2];
    EXPECT_GE(brightest / median, 1e4) << "brightest " << brightest << ", median " << median;
    EXPECT_NEAR(glm::dot(at, skySunDirection()), 1.0, 1e-4);
    double widest = 0;
    for (int face = 0, k = 0; face < 6; ++face)
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x, ++k)
                if (luminance[size_t(k)] > 0.01 * brightest)
                    widest = std::max(widest, std::acos(std::min(
                                                  1.0, glm::dot(cubeTexelDirection(face, x, y, 256),
                                                                skySunDirection()))));
    EXPECT_LT(widest * 180 / 3.141592653589793, 0.6);
    std::printf("[ sky-sun  ] brightest %.4g, median %.4g (%.3g x), sun's texels within %.3g deg\n",
                brightest, median, brightest / median, widest * 180 / 3.141592653589793);
}
