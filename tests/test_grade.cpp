// The autograder end to end: kits with and without solutions, typical mistakes named at their
// own step, compile errors with file and line, refused files, time limits, and the reports.
#include <gtest/gtest.h>

#include <fstream>

#include "grade.h"
#include "kit.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

struct Grader {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR, paths.labs()};
    test::TempDir dir;

    fs::path kit(bool solutions) {
        fs::path out = dir.path / (solutions ? "solutions" : "stubs");
        writeKit(modules, {out, solutions, "", false});
        return out;
    }
    GradeReport grade(const fs::path& submission, std::vector<std::string> ids = {},
                      double timeout = 120) {
        GradeOptions o;
        o.submission = fs::canonical(submission);
        o.modules = std::move(ids);
        o.timeoutSeconds = timeout;
        return gradeSubmission(modules, paths, o);
    }
    static const ModuleGrade& find(const GradeReport& r, const std::string& id) {
        for (const auto& g : r.modules)
            if (g.id == id) return g;
        throw std::runtime_error("no grade for " + id);
    }
};

}  // namespace

TEST(Grade, ReferenceSolutionsScoreTheMaximum) {
    Grader g;
    GradeReport r = g.grade(g.kit(true));
    ASSERT_EQ(r.modules.size(), g.modules.modules().size());
    for (const auto& m : r.modules) EXPECT_EQ(m.status, "passed") << m.id << ": " << m.message;
    EXPECT_EQ(r.score, r.maxScore);
}

TEST(Grade, UntouchedStubsScoreZeroAndNeverCrash) {
    Grader g;
    GradeReport r = g.grade(g.kit(false));
    for (const auto& m : r.modules) EXPECT_EQ(m.status, "failed") << m.id << ": " << m.message;
    EXPECT_EQ(r.score, 0);
}

TEST(Grade, EachProblemCostsOnlyItsOwnStep) {
    Grader g;
    fs::path kit = g.kit(true);
    fs::copy_file(g.paths.labs() / "05-ndf/mistakes/alpha_is_roughness.glsl", kit / "ndf.glsl",
                  fs::copy_options::overwrite_existing);
    std::ofstream(kit / "halfway.glsl") << "vec3 halfwayVector(vec3 L, vec3 V)\n{\n"
                                           "    return normalize(L + V)\n}\n";
    fs::remove(kit / "albedo.glsl");
    fs::create_symlink("/etc/hostname", kit / "albedo.glsl");
    std::ofstream(kit / "f0.glsl", std::ios::binary) << std::string("vec3 x\0y;\n", 10);
    fs::remove(kit / "smith.glsl");
    GradeReport r = g.grade(kit, {"albedo", "halfway", "ndotl", "ndf", "g1", "smith", "f0"});
    EXPECT_EQ(Grader::find(r, "ndf").status, "failed");
    EXPECT_NE(Grader::find(r, "ndf").message.find("looks like: alpha = roughness"),
              std::string::npos)
        << Grader::find(r, "ndf").message;
    EXPECT_EQ(Grader::find(r, "halfway").status, "compile_error");
    EXPECT_NE(Grader::find(r, "halfway").message.find((kit / "halfway.glsl").string() + ":4"),
              std::string::npos)
        << Grader::find(r, "halfway").message;
    EXPECT_NE(Grader::find(r, "albedo").message.find("outside the submission"), std::string::npos);
    EXPECT_NE(Grader::find(r, "f0").message.find("NUL bytes"), std::string::npos);
    EXPECT_EQ(Grader::find(r, "smith").status, "missing");
    EXPECT_EQ(Grader::find(r, "ndotl").status, "passed");
    EXPECT_EQ(Grader::find(r, "g1").status, "passed");
    EXPECT_EQ(r.score, 2);
}

TEST(Grade, ATimeLimitKillsTheModuleAndTheReportStillComesOut) {
    // llvmpipe caps loop iterations, so a shader cannot hang it; a limit shorter than any
    // grading exercises the same path a hung GPU driver would: kill, "timeout", carry on.
    Grader g;
    fs::path kit = g.kit(true);
    GradeReport r = g.grade(kit, {"ndotl", "g1"}, 0.05);
    ASSERT_EQ(r.modules.size(), 2u);
    for (const auto& m : r.modules) EXPECT_EQ(m.status, "timeout") << m.id;
    nlohmann::json gs = toGradescope(r);
    EXPECT_EQ(gs["tests"].size(), 2u);
}

TEST(Grade, ReportsHaveTheFieldsGradescopeReads) {
    Grader g;
    GradeReport r = g.grade(g.kit(true), {"ndotl"});
    nlohmann::json gs = toGradescope(r);
    for (const char* key : {"score", "execution_time", "output", "tests"})
        EXPECT_TRUE(gs.contains(key)) << key;
    for (const char* key : {"name", "score", "max_score", "status", "output"})
        EXPECT_TRUE(gs["tests"][0].contains(key)) << key;
    nlohmann::json ours = toJson(r);
    for (const char* key : {"id", "status", "score", "max_score", "metrics", "message"})
        EXPECT_TRUE(ours["modules"][0].contains(key)) << key;
    fs::path file = g.dir.path / "out" / "results.json";
    writeFileAtomically(file, gs.dump());
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(file))["score"], 1);
}

TEST(Grade, InvariantsAreMeasuredOnTheStudentsFunction) {
    Grader g;
    fs::path kit = g.kit(true);
    GradeReport good = g.grade(kit, {"ndf", "smith", "fresnel", "brdf"});
    for (const auto& m : good.modules) {
        ASSERT_TRUE(m.metrics.contains("invariants")) << m.id;
        for (const auto& inv : m.metrics["invariants"]) EXPECT_TRUE(inv["holds"]) << m.id << inv;
    }
    // Without PI, D integrates to PI instead of 1.
    fs::copy_file(g.paths.labs() / "05-ndf/mistakes/missing_pi.glsl", kit / "ndf.glsl",
                  fs::copy_options::overwrite_existing);
    GradeReport bad = g.grade(kit, {"ndf"});
    const auto& invariants = bad.modules[0].metrics["invariants"];
    ASSERT_FALSE(invariants.empty());
    EXPECT_FALSE(invariants[0]["holds"]);
    EXPECT_NEAR(double(invariants[0]["measured"]), 3.14159, 0.01);
    EXPECT_NE(bad.modules[0].message.find("invariant integral of D"), std::string::npos)
        << bad.modules[0].message;
}
