// Promises of the grader that no other test held it to: each was found by breaking the
// grader's code and seeing the whole suite stay green (scripts/sabotage.sh, docs/grading.md
// "The suite checked by sabotage").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "course/assignment.h"
#include "course/autograder.h"
#include "gl/context.h"
#include "grading/grade_step.h"
#include "test_support.h"

namespace fs = std::filesystem;
using namespace pbrlab;

namespace {

std::string readText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

// An estimator's values are compared with the converged integral within a noise-aware band;
// its other checks (the error's fall, no systematic error per region, finite values) can fail
// too, and did for every planted mistake, so a band that let everything through went unseen.
// Here irradiance's reference solution, off by a factor 1 + 0.1 N.y: not a constant factor
// (the scale check takes the median ratio, near 1 over normals spread on the sphere, and
// divides it out before the band), so the error left is up to 10% of E near the poles, 6 x the
// band's 1.5% (labs/irradiance/module.cpp): values checks against the converged integral fail.
TEST(EstimatorBand, AnEstimatorOffByTenPercentAtTheZenithFailsItsValuesChecks) {
    auto context = createHeadlessContext();
    const DataPaths paths{PBRLAB_SOURCE_DIR};
    const ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};
    test::TempDir kit;
    std::string code = readText(paths.labs() / "irradiance/solution.glsl");
    const std::regex signature(R"(vec3 irradianceAt\(vec3 N\))");
    ASSERT_TRUE(std::regex_search(code, signature));
    code = std::regex_replace(code, signature, "vec3 exactIrradianceAt(vec3 N)") +
           "\nvec3 irradianceAt(vec3 N)\n{\n    return exactIrradianceAt(N) * (1.0 + 0.1 * N.y);"
           "\n}\n";
    kit.write("irradiance.glsl", code);
    StudentSource source;
    source.dir = kit.path;
    // Every check, no feedback and no extreme-input sweep: 4 s where the whole grade takes 15.
    GradeSettings settings;
    settings.feedback = false;
    settings.robustness = false;
    const StepResult r = gradeStep(renderer, modules.find("irradiance"), paths, source, settings);
    int failedValues = 0;
    for (const CheckReport& c : r.checks)
        failedValues +=
            c.kind == CheckKind::Values && c.category == CheckCategory::Estimator && !c.passed;
    EXPECT_FALSE(r.passed);
    EXPECT_GT(failedValues, 0) << "no values check against the converged integral failed";
}

// A step that reads where it may not (a failed contract check) scores 0 under partial credit,
// whatever its other checks passed: its values mean nothing (docs/assignment.md). The same
// checks with the contract kept earn their share, so the 0 is the contract's doing.
TEST(Assignment, AFailedContractCheckScoresTheStepZero) {
    const Assignment a = parseAssignment(nlohmann::json::parse(R"({"steps": ["ndf"],
                                                                  "points": {"ndf": 2}})"),
                                         "a.json", {"ndf"});
    ModuleGrade g;
    g.id = "ndf";
    g.status = GradeStatus::Failed;
    g.checks = nlohmann::json::parse(R"([
        {"category": "contract", "kind": "contract", "passed": false},
        {"category": "probe", "kind": "values", "passed": true, "shows_work": true},
        {"category": "invariants", "kind": "invariant", "passed": true}])");
    scoreGrade(g, a);
    EXPECT_EQ(g.maxScore, 2);
    EXPECT_EQ(g.score, 0);
    g.checks[0]["passed"] = true;
    scoreGrade(g, a);
    EXPECT_EQ(g.score, 2);  // every check passed: the step's points
}
