// The sun check on a real HDR (docs/grading.md, "A real sun"): with an outdoor panorama made
// by others as the sky with a sun (GradeSettings::sunEnvironment), the reference solutions of
// the steps that read the environment pass every check facing its sun, and a rule that limits
// bright light relative to the rest fails one, named for what it does. Skipped when
// ../shared/data (beside the repository, not part of it) is absent. And the command line that
// chooses such a sky.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "gl/context.h"
#include "grading/grade_step.h"
#include "render/renderer.h"
#include "steps/contract.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

TEST(Sun, ARealHdrsSunIsGradedAsTheGeneratedOne) {
    const fs::path hdr = fs::path(PBRLAB_SOURCE_DIR) / "../shared/data/hdr/venice_sunset_1k.hdr";
    if (!fs::exists(hdr)) GTEST_SKIP() << "shared data absent: " << hdr;
    auto context = createHeadlessContext();
    DataPaths paths(PBRLAB_SOURCE_DIR);
    ModuleRegistry modules(PBRLAB_MODULE_DIR);
    LabRenderer renderer(paths);
    const fs::path source(PBRLAB_SOURCE_DIR);
    struct Case {
        std::string step;
        fs::path file;
        bool correct;
    };
    const std::vector<Case> cases = {
        {"mc_specular", source / "labs/mc_specular/solution.glsl", true},
        {"mc_specular", source / "tests/exploits/mc_specular/firefly_rejection_relative.glsl",
         false},
        {"prefilter", source / "labs/prefilter/solution.glsl", true},
        {"prefilter", source / "tests/exploits/prefilter/firefly_clamp_relative.glsl", false},
        {"irradiance", source / "labs/irradiance/solution.glsl", true},
        {"irradiance", source / "tests/exploits/irradiance/hot_texels_clamped_relative.glsl",
         false},
        {"split_sum", source / "labs/split_sum/solution.glsl", true},
        {"split_sum", source / "tests/exploits/split_sum/highlight_clamped_relative.glsl", false},
    };
    for (const Case& c : cases) {
        test::TempDir kit;
        fs::copy(c.file, kit.path / (c.step + ".glsl"));
        GradeSettings settings;
        settings.robustness = false;
        settings.sunEnvironment = fs::canonical(hdr).string();
        const StepResult r = gradeStep(renderer, modules.find(c.step), paths, {kit.path}, settings);
        int sunChecks = 0, sunFailed = 0;
        for (const CheckReport& check : r.checks)
            if (check.name.find("facing the sun") != std::string::npos ||
                (check.name.find("no systematic error") != std::string::npos &&
                 check.name.find(settings.sunEnvironment) != std::string::npos)) {
                ++sunChecks;
                sunFailed += !check.passed;
                std::printf("[ real sun ] %s %s: %s %s\n", c.step.c_str(),
                            c.file.filename().c_str(), check.passed ? "ok  " : "FAIL",
                            check.detail.substr(0, 160).c_str());
            }
        EXPECT_GT(sunChecks, 0) << c.step;
        if (c.correct) {
            EXPECT_EQ(sunFailed, 0) << c.step << ": " << r.message;
        } else {
            EXPECT_GT(sunFailed, 0) << c.step << ": " << r.message;
            EXPECT_NE(r.message.find("bright light"), std::string::npos) << r.message;
        }
    }
}

// An instructor's sky reaches the grade from the command line: `check --sun-environment` grades
// the sun check on it (here the shipped sky, whose sun is a 1.2 degree disc) instead of
// sky-sun, and the reference solution passes there.
TEST(Sun, TheCommandLineChoosesTheSkyWithASun) {
    test::TempDir dir;
    const fs::path report = dir.path / "report.json";
    const test::CommandRun check =
        test::run(dir, std::string(PBRLAB_EXECUTABLE) +
                           " check split_sum --sun-environment sky --json " + report.string());
    ASSERT_EQ(check.status, 0) << check.output;
    std::ifstream in(report);
    const nlohmann::json grade = nlohmann::json::parse(in);
    bool graded = false;
    for (const nlohmann::json& c : grade.at("modules").at(0).at("checks"))
        if (c.value("name", "") == "random inputs facing the sun (sky)") {
            graded = true;
            EXPECT_TRUE(c.value("passed", false)) << c.dump();
        }
    EXPECT_TRUE(graded) << check.output;
}
