// Assignment files (docs/assignment.md): each broken field named with its file and JSON path,
// partial credit on real grades (a planted mistake that fails some categories and passes
// others, the reference solutions at full points), Gradescope's rows, the release schedule.
#include <gtest/gtest.h>

#include "assignment.h"
#include "grade.h"
#include "gradescope.h"
#include "kit.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kSteps = {"ndotl", "ndf", "smith", "fresnel", "specular"};

std::string errorOf(const test::TempDir& dir, const std::string& text) {
    const fs::path file = dir.write("a.json", text);
    try {
        loadAssignment(file, kSteps);
    } catch (const std::exception& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace

TEST(Assignment, EachBrokenFieldIsNamedWithTheFileAndItsPath) {
    test::TempDir dir;
    const std::string file = (dir.path / "a.json").string();
    const std::vector<std::pair<std::string, std::string>> cases = {
        {R"({"steps": ["ndf"], "pionts": {}})", "pionts: unknown field"},
        {R"({"steps": ["ndf"], "points": {"ndf": -1}})", "points.ndf: must be a number >= 0"},
        {R"({"steps": ["ndf"], "points": {"ndf": "3"}})", "points.ndf: must be a number >= 0"},
        {R"({"steps": ["ndf"], "points": {"smith": 2}})",
         "points.smith: 'smith' is not one of the assignment's steps"},
        {R"({"steps": ["ndotl", "nfd"]})", "steps[1]: 'nfd' is not a step id"},
        {R"({"steps": ["ndf", "ndf"]})", "steps[1]: 'ndf' is listed twice"},
        {R"({"points": {}})", "steps: missing"},
        {R"({"steps": ["ndf"], "checks": {"colour": 1}})", "checks.colour: not a check category"},
        {R"({"steps": ["ndf"], "checks": {"probe": true}})", "checks.probe: must be a number"},
        {R"({"steps": ["ndf"], "visibility": {"ndf": "later"}})",
         "visibility.ndf: 'later' is not visible, hidden, after_due_date or after_published"},
        {R"({"steps": ["ndf"], "visibility": {"ndf.colour": "hidden"}})",
         "visibility.ndf.colour: not \"default\", a step id, a check category"},
        {R"({"steps": ["ndf"], "release": [{"date": "2026-02-30", "through": "ndf"}]})",
         "release[0].date: '2026-02-30' is not a date YYYY-MM-DD"},
        {R"({"steps": ["ndf"], "release": [{"date": "2026-02-03"}]})",
         "release[0].through: missing"},
        {R"({"steps": ["ndf", "smith"], "release": [{"date": "2026-02-03", "through": "smith"},
             {"date": "2026-02-01", "through": "ndf"}]})",
         "release[1].date: must come after 2026-02-03"},
        {R"({"steps": ["ndf"], "solutions": [{"date": "2026-02-03", "through": "smith"}]})",
         "solutions[0].through: 'smith' is not one of the assignment's steps"},
        {R"({"steps": ["ndf"], "due": "tomorrow"})", "due: 'tomorrow' is not a date"},
        {R"({"steps": ["ndf"], "due": "2026-10-01T25:00Z"})", "due: '2026-10-01T25:00Z' is not"},
        {R"({"steps": ["ndf"], "time_limit_seconds": 0})",
         "time_limit_seconds: must be a number >= 1"},
        {R"({"steps": ["ndf"], "partial_credit": "yes"})", "partial_credit: must be true or false"},
        {R"({"steps": ["ndf"],)", "not valid JSON"},
    };
    for (const auto& [text, expected] : cases) {
        const std::string error = errorOf(dir, text);
        EXPECT_EQ(error.rfind(file + ": ", 0), 0u) << text << "\n" << error;
        EXPECT_NE(error.find(expected), std::string::npos) << text << "\n" << error;
    }
}

TEST(Assignment, DefaultsCommentsAndVisibilityPrecedence) {
    test::TempDir dir;
    const Assignment a = loadAssignment(dir.write("a.json", R"({
        // steps in any order: kept in the steps' order
        "steps": ["specular", "ndotl"],
        "points": {"default": 2, "specular": 4},
        "visibility": {"default": "after_published", "specular": "after_due_date",
                       "robustness": "hidden", "specular.probe": "visible"}
    })"),
                                        kSteps);
    EXPECT_EQ(a.steps, (std::vector<std::string>{"ndotl", "specular"}));
    EXPECT_EQ(a.points.at("ndotl"), 2);
    EXPECT_EQ(a.points.at("specular"), 4);
    EXPECT_TRUE(a.partialCredit);
    EXPECT_EQ(a.weights.at("robustness"), 0);  // reported, not deducted, unless weighted
    EXPECT_EQ(a.weights.at("probe"), 1);
    EXPECT_EQ(a.timeLimitSeconds, 60);
    EXPECT_EQ(a.visibilityOf("specular", "probe"), "visible");
    EXPECT_EQ(a.visibilityOf("specular", "scenes"), "after_due_date");
    EXPECT_EQ(a.visibilityOf("ndotl", "robustness"), "hidden");
    EXPECT_EQ(a.visibilityOf("ndotl", "probe"), "after_published");
}

namespace {

struct Graded {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    test::TempDir dir;
};

}  // namespace

// The planted mistake alpha = roughness in ndf fails every values check (probe, scenes, random
// inputs, the sphere grid) and passes the contract and the invariants (D's integrals do not
// see how alpha was made): its score is the weights' share of those two.
TEST(Assignment, PartialCreditIsTheWeightsShareOfTheCategoriesPassed) {
    Graded g;
    const fs::path kit = g.dir.path / "kit";
    writeKit(g.modules, {kit, true, "", false});
    fs::copy_file(g.paths.labs() / "ndf/mistakes/alpha_is_roughness.glsl", kit / "ndf.glsl",
                  fs::copy_options::overwrite_existing);
    const Assignment a = loadAssignment(g.dir.write("a.json", R"({
        "steps": ["ndotl", "ndf"], "points": {"ndotl": 2, "ndf": 3},
        "checks": {"contract": 1, "probe": 2, "scenes": 2, "random": 2, "sphere_grid": 1,
                   "invariants": 2, "robustness": 0},
        "visibility": {"ndf": "after_due_date", "ndf.invariants": "hidden"}
    })"),
                                        stepIds(g.modules));
    GradeOptions o;
    o.submission = fs::canonical(kit);
    applyAssignment(a, o);
    const GradeReport r = gradeSubmission(g.modules, g.paths, o);
    ASSERT_EQ(r.modules.size(), 2u);
    const ModuleGrade& ndotl = r.modules[0];
    const ModuleGrade& ndf = r.modules[1];
    EXPECT_EQ(ndotl.status, "passed");
    EXPECT_EQ(ndotl.score, 2);  // exactly
    EXPECT_EQ(ndotl.maxScore, 2);
    EXPECT_EQ(ndf.status, "failed");
    EXPECT_EQ(ndf.maxScore, 3);
    // contract 1 + invariants 2 of the weights 1 + 2 + 2 + 2 + 1 + 2 (robustness 0) = 10.
    EXPECT_NEAR(ndf.score, 3.0 * 3 / 10, 1e-12);
    EXPECT_NEAR(r.score, 2 + 0.9, 1e-12);

    const nlohmann::json gs = toGradescope(r, a);
    double sum = 0, ndfMax = 0;
    std::map<std::string, nlohmann::json> rows;
    for (const auto& t : gs["tests"]) {
        sum += t["score"].get<double>();
        rows[t["name"]] = t;
        EXPECT_EQ(t["output_format"], "md");
        if (t["extra_data"]["step"] == "ndf") ndfMax += t["max_score"].get<double>();
    }
    EXPECT_EQ(gs["score"].get<double>(), sum);
    EXPECT_NEAR(sum, 2.9, 1e-12);
    EXPECT_NEAR(ndfMax, 3, 1e-12);
    ASSERT_TRUE(rows.count("ndf: probe"));
    EXPECT_EQ(rows["ndf: probe"]["status"], "failed");
    EXPECT_EQ(rows["ndf: probe"]["score"], 0);
    EXPECT_NEAR(rows["ndf: probe"]["max_score"].get<double>(), 0.6, 1e-12);
    EXPECT_EQ(rows["ndf: probe"]["visibility"], "after_due_date");
    // The feedback names the mistake in the first failed row.
    EXPECT_NE(rows["ndf: probe"]["output"].get<std::string>().find("alpha = roughness"),
              std::string::npos);
    EXPECT_EQ(rows["ndf: invariants"]["status"], "passed");
    EXPECT_EQ(rows["ndf: invariants"]["visibility"], "hidden");
    EXPECT_FALSE(rows["ndf: invariants"]["extra_data"]["checks"].empty());
    // Robustness has weight 0: no row.
    EXPECT_FALSE(rows.count("ndf: robustness"));
    EXPECT_EQ(rows["ndotl: sphere_grid"]["visibility"], "visible");

    // Without partial credit: all or nothing, the step's points.
    Assignment whole = a;
    whole.partialCredit = false;
    GradeOptions w;
    w.submission = o.submission;
    applyAssignment(whole, w);
    const GradeReport rw = gradeSubmission(g.modules, g.paths, w);
    EXPECT_EQ(rw.modules[0].score, 2);
    EXPECT_EQ(rw.modules[1].score, 0);
    EXPECT_EQ(toGradescope(rw, whole)["tests"].size(), 2u);
}

TEST(Assignment, TheReleaseScheduleDecidesWhatTheKitHandsOut) {
    Graded g;
    const Assignment a = loadAssignment(g.dir.write("a.json", R"({
        "steps": ["ndotl", "ndf", "smith", "fresnel", "specular"],
        "release": [{"date": "2026-09-07", "through": "smith"},
                    {"date": "2026-09-21", "through": "specular"}],
        "solutions": [{"date": "2026-09-21", "through": "ndf"}],
        "due": "2026-10-01T23:59:00Z"
    })"),
                                        stepIds(g.modules));
    auto kitOn = [&](const std::string& date) {
        KitOptions k;
        k.out = g.dir.path / ("kit-" + date);
        applyAssignment(a, date, k);
        writeKit(g.modules, k);
        return k.out;
    };
    try {
        kitOn("2026-09-06");
        ADD_FAILURE() << "a kit before the first release";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("nothing is out by 2026-09-06"), std::string::npos)
            << e.what();
    }
    const fs::path first = kitOn("2026-09-07");
    for (const char* id : {"ndotl", "ndf", "smith"})
        EXPECT_TRUE(fs::exists(first / (std::string(id) + ".glsl"))) << id;
    for (const char* id : {"fresnel", "specular", "brdf", "albedo"})
        EXPECT_FALSE(fs::exists(first / (std::string(id) + ".glsl"))) << id;
    const fs::path second = kitOn("2026-09-30");
    for (const char* id : {"ndotl", "ndf", "smith", "fresnel", "specular"})
        EXPECT_TRUE(fs::exists(second / (std::string(id) + ".glsl"))) << id;
    EXPECT_FALSE(fs::exists(second / "brdf.glsl"));
    std::ifstream readme(second / "README.md");
    const std::string text((std::istreambuf_iterator<char>(readme)), {});
    EXPECT_NE(text.find("Due: 2026-10-01T23:59:00Z"), std::string::npos);
    EXPECT_NE(text.find("`ndf.glsl` | `float distributionGGX(vec3 N, vec3 H, float roughness)` "
                        "| solution given"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("`smith.glsl` | `float geometrySmith(vec3 N, vec3 V, vec3 L, float "
                        "roughness)` | to write"),
              std::string::npos)
        << text;
}
