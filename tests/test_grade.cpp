// The autograder end to end: kits with and without solutions, every problem costing its own
// step only, hostile files (symlink loops, NUL bytes in includes, bytes that are not UTF-8, a
// compiler-crashing macro), time limits, invariants that deduct, the contract's promise that
// every contract function of an earlier step is callable from a step (and no later one), and
// the GUI's badge agreeing with the grade.
#include <gtest/gtest.h>

#include <fstream>

#include "course/autograder.h"
#include "course/kit.h"
#include "gl/context.h"
#include "steps/contract.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

struct Grader {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    test::TempDir dir;

    fs::path kit(bool solutions) {
        fs::path out = dir.path / (solutions ? "solutions" : "stubs");
        writeKit(modules, {out, solutions, "", false});
        return out;
    }
    GradeReport grade(const fs::path& submission, std::vector<std::string> ids = {},
                      double timeout = 300) {
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
    static const nlohmann::json* check(const ModuleGrade& g, const std::string& prefix) {
        for (const auto& c : g.checks)
            if (c.value("name", "").rfind(prefix, 0) == 0) return &c;
        return nullptr;
    }
};

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

}  // namespace

TEST(Grade, ReferenceSolutionsScoreTheMaximum) {
    Grader g;
    ASSERT_EQ(g.modules.modules().size(), contractSteps().size()) << "not all 21 modules load";
    GradeReport r = g.grade(g.kit(true));
    ASSERT_EQ(r.modules.size(), contractSteps().size());
    for (const auto& m : r.modules)
        EXPECT_EQ(m.status, GradeStatus::Passed) << m.id << ": " << m.message;
    EXPECT_EQ(r.score, r.maxScore);
    std::printf("[ measured ] a correct 21-step submission graded in %.1f s\n", r.seconds);
}

// One child at a time makes the start order visible in the order grades come in: an estimator
// (irradiance) starts before an analytic step (ndotl), so that on several cores the longest
// step does not run alone at the end. The report keeps the lab's order.
TEST(Grade, EstimatorsStartFirstAndTheReportKeepsTheLabOrder) {
    Grader g;
    GradeOptions o;
    o.submission = fs::canonical(g.kit(false));
    o.modules = {"ndotl", "irradiance"};
    o.jobs = 1;
    std::vector<std::string> started;
    o.progress = [&](const ModuleGrade& grade) { started.push_back(grade.id); };
    const GradeReport r = gradeSubmission(g.modules, g.paths, o);
    EXPECT_EQ(started, (std::vector<std::string>{"irradiance", "ndotl"}));
    ASSERT_EQ(r.modules.size(), 2u);
    EXPECT_EQ(r.modules[0].id, "ndotl");
    EXPECT_EQ(r.modules[1].id, "irradiance");
}

TEST(Grade, UntouchedStubsScoreZeroAndNeverCrash) {
    Grader g;
    GradeReport r = g.grade(g.kit(false));
    int named = 0;
    for (const auto& m : r.modules) {
        EXPECT_EQ(m.status, GradeStatus::Failed) << m.id << ": " << m.message;
        named += contains(m.mistake, "still the kit's stub");
    }
    EXPECT_EQ(r.score, 0);
    // Every stub returns 0; only hammersley's view turns that into something else than a
    // constant (box counts), so the feedback says "stub" for the other twenty.
    EXPECT_GE(named, 20);
}

TEST(Grade, AnEndlessLoopIsNamedAsSuchNotAsTheStub) {
    Grader g;
    fs::path kit = g.kit(true);
    std::ofstream(kit / "ndotl.glsl") << "float lambertCosine(vec3 N, vec3 L) {\n"
                                         "    float x = 0.0;\n"
                                         "    while (true) { x += 1.0; }\n"
                                         "    return max(dot(N, L), 0.0);\n"
                                         "}\n";
    const GradeReport r = g.grade(kit, {"ndotl"});
    const ModuleGrade& m = Grader::find(r, "ndotl");
    // Refused at the loop: in a program of steps 1..4 Mesa keeps the return after the loop and
    // the values are right, so no value check can see it (it gave 0 in a program of all 21).
    EXPECT_EQ(m.status, GradeStatus::CompileError) << m.message;
    EXPECT_TRUE(contains(m.message, "ndotl.glsl:3: error: a loop that never ends")) << m.message;
    EXPECT_FALSE(contains(m.message, "stub")) << m.message;
}

TEST(Grade, EachProblemCostsOnlyItsOwnStep) {
    Grader g;
    fs::path kit = g.kit(true);
    fs::copy_file(g.paths.labs() / "ndf/mistakes/alpha_is_roughness.glsl", kit / "ndf.glsl",
                  fs::copy_options::overwrite_existing);
    std::ofstream(kit / "halfway.glsl") << "vec3 halfwayVector(vec3 L, vec3 V)\n{\n"
                                           "    return normalize(L + V)\n}\n";
    fs::remove(kit / "albedo.glsl");
    fs::create_symlink("/etc/hostname", kit / "albedo.glsl");
    std::ofstream(kit / "f0.glsl", std::ios::binary) << std::string("vec3 x\0y;\n", 10);
    fs::remove(kit / "smith.glsl");
    GradeReport r = g.grade(kit, {"albedo", "halfway", "ndotl", "ndf", "g1", "smith", "f0"});
    EXPECT_EQ(Grader::find(r, "ndf").status, GradeStatus::Failed);
    // The typical mistake is named, as a whole sentence.
    EXPECT_TRUE(contains(Grader::find(r, "ndf").message,
                         "typical mistake: alpha = roughness (perceptual roughness not squared)."))
        << Grader::find(r, "ndf").message;
    EXPECT_EQ(Grader::find(r, "halfway").status, GradeStatus::CompileError);
    EXPECT_TRUE(
        contains(Grader::find(r, "halfway").message, (kit / "halfway.glsl").string() + ":4"))
        << Grader::find(r, "halfway").message;
    EXPECT_TRUE(contains(Grader::find(r, "albedo").message, "outside the submission"));
    EXPECT_TRUE(contains(Grader::find(r, "f0").message, "NUL bytes"));
    EXPECT_EQ(Grader::find(r, "smith").status, GradeStatus::Missing);
    EXPECT_EQ(Grader::find(r, "ndotl").status, GradeStatus::Passed);
    EXPECT_EQ(Grader::find(r, "g1").status, GradeStatus::Passed);
    EXPECT_EQ(r.score, 2);
}

TEST(Grade, ASymlinkLoopIsRefusedAndEveryOtherStepIsGraded) {
    Grader g;
    fs::path kit = g.kit(true);
    fs::remove(kit / "ndotl.glsl");
    fs::create_symlink("loop-b", kit / "loop-a");
    fs::create_symlink("loop-a", kit / "loop-b");
    fs::create_symlink("loop-a", kit / "ndotl.glsl");
    // A file that includes the loop: its own step fails with the reason, nothing else.
    std::ofstream(kit / "f0.glsl") << "#include \"loop-a\"\n"
                                      "vec3 baseReflectivity(vec3 albedo, float metallic)\n"
                                      "{\n    return mix(vec3(0.04), albedo, metallic);\n}\n";
    GradeReport r = g.grade(kit, {"halfway", "ndotl", "f0", "fresnel"});
    ASSERT_EQ(r.modules.size(), 4u);
    EXPECT_EQ(Grader::find(r, "ndotl").status, GradeStatus::Failed);
    EXPECT_TRUE(contains(Grader::find(r, "ndotl").message, "cannot be resolved"))
        << Grader::find(r, "ndotl").message;
    EXPECT_NE(Grader::find(r, "f0").status, GradeStatus::Passed);
    EXPECT_TRUE(contains(Grader::find(r, "f0").message, "loop-a")) << Grader::find(r, "f0").message;
    EXPECT_EQ(Grader::find(r, "halfway").status, GradeStatus::Passed);
    EXPECT_EQ(Grader::find(r, "fresnel").status, GradeStatus::Passed);
    EXPECT_EQ(r.score, 2);
    // The report is written.
    const fs::path report = g.dir.path / "report.json";
    writeFileAtomically(report, jsonText(toJson(r)));
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(report))["modules"].size(), 4u);
}

TEST(Grade, ANulByteInAnIncludedFileIsRefusedNamingTheFile) {
    Grader g;
    fs::path kit = g.kit(true);
    std::ofstream(kit / "helpers.glsl", std::ios::binary)
        << std::string("float half(float x) { return 0.5 * x; }\n\0 trailing", 51);
    std::ofstream(kit / "f0.glsl") << "#include \"helpers.glsl\"\n"
                                      "vec3 baseReflectivity(vec3 albedo, float metallic)\n"
                                      "{\n    return mix(vec3(0.04), albedo, metallic);\n}\n";
    GradeReport r = g.grade(kit, {"f0"});
    const ModuleGrade& m = Grader::find(r, "f0");
    EXPECT_NE(m.status, GradeStatus::Passed);
    EXPECT_TRUE(contains(m.message, (kit / "helpers.glsl").string()) && contains(m.message, "NUL"))
        << m.message;
}

TEST(Grade, BytesThatAreNotUtf8InAMessageStillGiveAReport) {
    Grader g;
    fs::path kit = g.kit(true);
    // The compiler quotes the bad token in its log, and the log goes into the message.
    std::ofstream(kit / "ndotl.glsl", std::ios::binary)
        << "float lambertCosine(vec3 N, vec3 L)\n{\n    return \xff\xfe(N, L);\n}\n";
    GradeReport r = g.grade(kit, {"ndotl", "g1"});
    EXPECT_EQ(Grader::find(r, "ndotl").status, GradeStatus::CompileError)
        << Grader::find(r, "ndotl").message;
    EXPECT_EQ(Grader::find(r, "g1").status, GradeStatus::Passed);
    // Valid JSON, every byte of it.
    const std::string text = jsonText(toJson(r));
    EXPECT_EQ(validUtf8(text), text);
    EXPECT_NO_THROW(nlohmann::json::parse(text));
}

TEST(Grade, AMacroThatBlowsUpTheCompilerIsReportedAsSuch) {
    Grader g;
    fs::path kit = g.kit(true);
    std::string bomb = "#define A0 x x\n";
    for (int i = 1; i <= 40; ++i)
        bomb += "#define A" + std::to_string(i) + " A" + std::to_string(i - 1) + " A" +
                std::to_string(i - 1) + "\n";
    bomb += "float lambertCosine(vec3 N, vec3 L)\n{\n    float A40 = 0.0;\n    return A40;\n}\n";
    std::ofstream(kit / "ndotl.glsl") << bomb;
    GradeReport r = g.grade(kit, {"ndotl", "g1"}, 30);
    const ModuleGrade& m = Grader::find(r, "ndotl");
    EXPECT_NE(m.status, GradeStatus::Passed);
    // Whatever the compiler does with it (a crash, an endless expansion, an error), the
    // message says it happened while compiling, and the next step is graded.
    EXPECT_TRUE(contains(m.message, "compil")) << m.status << ": " << m.message;
    EXPECT_EQ(Grader::find(r, "g1").status, GradeStatus::Passed);
}

TEST(Grade, ATimeLimitKillsTheModuleAndTheReportStillComesOut) {
    // llvmpipe caps loop iterations, so a shader cannot hang it; a limit shorter than any
    // grading exercises the same path a hung GPU driver would: kill, "timeout", carry on.
    Grader g;
    fs::path kit = g.kit(true);
    GradeReport r = g.grade(kit, {"ndotl", "g1"}, 0.05);
    ASSERT_EQ(r.modules.size(), 2u);
    for (const auto& m : r.modules) {
        EXPECT_EQ(m.status, GradeStatus::Timeout) << m.id;
        EXPECT_EQ(m.score, 0) << m.id;
    }
    nlohmann::json gs = toGradescope(r);
    EXPECT_EQ(gs["tests"].size(), 2u);
}

TEST(Grade, ATimeBudgetForTheWholeSubmissionEndsItAndSaysWhichStepsItCut) {
    // run_autograder's budget (Gradescope's timeout less a margin): the step grading when it
    // runs out is killed, the steps after it are not started, and the report still comes out
    // with each of them at 0, saying why; the steps before it keep their grades.
    Grader g;
    fs::path kit = g.kit(true);
    GradeOptions o;
    o.submission = fs::canonical(kit);
    o.modules = {"ndotl", "g1", "smith"};
    o.timeoutSeconds = 300;
    o.jobs = 1;
    o.budgetSeconds = 0.05;
    GradeReport r = gradeSubmission(g.modules, g.paths, o);
    ASSERT_EQ(r.modules.size(), 3u);
    const ModuleGrade& first = Grader::find(r, "ndotl");
    EXPECT_EQ(first.status, GradeStatus::Timeout);
    EXPECT_TRUE(contains(first.message, "may take 0 s, and that ran out during")) << first.message;
    for (const char* id : {"g1", "smith"}) {
        const ModuleGrade& m = Grader::find(r, id);
        EXPECT_EQ(m.status, GradeStatus::Timeout) << id;
        EXPECT_EQ(m.score, 0) << id;
        EXPECT_TRUE(contains(m.message, "not graded: grading the whole submission may take"))
            << id << ": " << m.message;
    }
    EXPECT_LT(r.seconds, 30) << "the budget did not end the grading";
    // A budget that does not run out changes nothing.
    o.modules = {"ndotl"};
    o.budgetSeconds = 600;
    EXPECT_EQ(gradeSubmission(g.modules, g.paths, o).modules.at(0).status, GradeStatus::Passed);
}

TEST(Grade, ACpuQuotaSetsHowManyProcessesGradeAtOnce) {
    // Gradescope's containers see every processor of the host but may use half of one: the
    // grading processes follow the quota (rounded up), never more than the processors.
    EXPECT_EQ(cpusOfQuota("max 100000", -1, -1, 8), 8);
    EXPECT_EQ(cpusOfQuota("50000 100000", -1, -1, 64), 1);
    EXPECT_EQ(cpusOfQuota("150000 100000", -1, -1, 64), 2);
    EXPECT_EQ(cpusOfQuota("400000 100000", -1, -1, 2), 2);
    EXPECT_EQ(cpusOfQuota("", 50000, 100000, 64), 1);  // cgroup v1
    EXPECT_EQ(cpusOfQuota("", -1, 100000, 4), 4);      // v1, no quota
    EXPECT_EQ(cpusOfQuota("", -1, -1, 0), 1);          // no processor count: one
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
    for (const char* key : {"id", "status", "score", "max_score", "checks", "message", "mistake"})
        EXPECT_TRUE(ours["modules"][0].contains(key)) << key;
    fs::path file = g.dir.path / "out" / "results.json";
    writeFileAtomically(file, gs.dump());
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(file))["score"], 1);
}

TEST(Grade, InvariantsAreMeasuredOnTheStudentsFunctionAndDeduct) {
    Grader g;
    fs::path kit = g.kit(true);
    GradeReport good = g.grade(kit, {"ndf", "smith", "fresnel", "brdf"});
    for (const auto& m : good.modules) {
        int invariants = 0;
        for (const auto& c : m.checks)
            if (c["kind"] == "invariant") {
                ++invariants;
                EXPECT_TRUE(c["passed"]) << m.id << c;
            }
        EXPECT_GT(invariants, 0) << m.id;
    }
    // Without PI, D integrates to PI instead of 1: the step fails on the invariant too, and
    // the message names it.
    fs::copy_file(g.paths.labs() / "ndf/mistakes/missing_pi.glsl", kit / "ndf.glsl",
                  fs::copy_options::overwrite_existing);
    GradeReport bad = g.grade(kit, {"ndf"});
    const ModuleGrade& m = bad.modules[0];
    EXPECT_EQ(m.status, GradeStatus::Failed);
    const nlohmann::json* integral = Grader::check(m, "integral of D");
    ASSERT_NE(integral, nullptr);
    EXPECT_FALSE((*integral)["passed"]);
    EXPECT_NEAR(double((*integral)["measured"]), 3.14159, 0.01);
    EXPECT_TRUE(contains(m.message, "integral of D")) << m.message;
    EXPECT_TRUE(contains(m.message, "(= pi)")) << m.message;  // the constant factor, named
}

// The contract: every contract function of its own and earlier steps (and
// fresnelSchlickRoughness from split_sum on) is callable from a step's file, in both labs; a
// later step's is not, and the compile error says which step introduces it. Each step's
// reference solution, plus a helper calling every function it may call, must compile in that
// step's program; a call of the next step's function must not.
TEST(Grade, EveryContractFunctionOfAnEarlierStepIsCallableAndNoLaterOne) {
    auto context = createHeadlessContext();
    Grader g;
    LabRenderer renderer(g.paths);
    auto argumentFor = [](const std::string& type) -> std::string {
        if (type == "float") return "0.5";
        if (type == "uint") return "4u";
        if (type == "vec2") return "vec2(0.5)";
        if (type == "vec3") return "vec3(0.0, 0.0, 1.0)";
        if (type == "vec4") return "vec4(1.0, 0.0, 0.0, 1.0)";
        throw std::runtime_error("no argument for " + type);
    };
    // "s += float(name(args).x);" for a signature.
    auto callOf = [&](const std::string& sig) {
        std::string args;
        std::istringstream params(sig.substr(sig.find('(') + 1, sig.find(')') - sig.find('(') - 1));
        for (std::string param; std::getline(params, param, ',');) {
            std::istringstream words(param);
            std::string type;
            words >> type;
            args += (args.empty() ? "" : ", ") + argumentFor(type);
        }
        const std::string ret = sig.substr(0, sig.find(' '));
        return "    s += " + std::string(ret == "float" ? "" : "float(") + functionName(sig) + "(" +
               args + ")" + (ret == "float" ? "" : ".x)") + ";\n";
    };
    auto helperCalling = [&](const std::vector<std::string>& signatures) {
        std::string calls = "float pbrlabTestCallsContractFunctions()\n{\n    float s = 0.0;\n";
        for (const std::string& sig : signatures) calls += callOf(sig);
        return calls + "    return s;\n}\n";
    };
    for (const LoadedModule& m : g.modules.modules()) {
        const ContractStep& own = *findContractStep(m.desc->id);
        std::vector<std::string> callable;
        for (const ContractStep* step : stepsVisibleFrom(own)) callable.push_back(step->function);
        for (const ContractHelper& h : contractHelpers())
            if (findContractStep(h.introducedBy)->step <= own.step) callable.push_back(h.function);
        std::ifstream solution(m.sourceDir / "solution.glsl");
        std::stringstream text;
        text << solution.rdbuf();
        test::TempDir kit;
        kit.write(m.desc->id + ".glsl", helperCalling(callable) + text.str());
        try {
            renderer.programs().get(renderer.viewRecipe(m, {kit.path}, true, 1));
        } catch (const std::exception& e) {
            ADD_FAILURE() << m.desc->id << ": " << e.what();
        }
        if (size_t(own.step) == contractSteps().size()) continue;
        const ContractStep& next = contractSteps()[size_t(own.step)];
        test::TempDir later;  // another folder: the program cache keys programs by their files
        later.write(m.desc->id + ".glsl", helperCalling({next.function}) + text.str());
        try {
            renderer.programs().get(renderer.viewRecipe(m, {later.path}, true, 1));
            ADD_FAILURE() << m.desc->id << " can call " << next.id << "'s function";
        } catch (const ShaderError& e) {
            const std::string said = functionName(next.function) + " is introduced in step " +
                                     std::to_string(next.step) + " (" + next.id + "); " +
                                     m.desc->id + " cannot call it";
            EXPECT_TRUE(contains(e.what(), (later.path / (m.desc->id + ".glsl:")).string() + "4:"))
                << e.what();
            EXPECT_TRUE(contains(e.what(), said)) << e.what();
        }
    }
}

TEST(Grade, ARedefinedContractFunctionGetsAHint) {
    Grader g;
    fs::path kit = g.kit(true);
    std::ofstream(kit / "ndf.glsl")
        << "float lambertCosine(vec3 N, vec3 L) { return max(dot(N, L), 0.0); }\n"
           "float distributionGGX(vec3 N, vec3 H, float roughness) { return 1.0; }\n";
    GradeReport r = g.grade(kit, {"ndf"});
    EXPECT_EQ(r.modules[0].status, GradeStatus::CompileError);
    EXPECT_TRUE(contains(r.modules[0].message, "lambertCosine is a contract function"))
        << r.modules[0].message;
}

// The GUI's badge is gradeModule in the GUI's own process; `pbrlab grade` runs the same in a
// child. Same file, same status and message.
TEST(Grade, TheBadgeAgreesWithTheGrade) {
    Grader g;
    fs::path kit = g.kit(true);
    fs::copy_file(fs::path(PBRLAB_SOURCE_DIR) / "tests/exploits/ndf/three_for_pi.glsl",
                  kit / "ndf.glsl", fs::copy_options::overwrite_existing);
    const std::vector<std::string> ids = {"ndotl", "ndf", "irradiance"};
    const GradeReport r = g.grade(kit, ids);  // forks before this process holds GL
    auto context = createHeadlessContext();
    LabRenderer renderer(g.paths);
    GradeOptions o;
    o.submission = fs::canonical(kit);
    for (const std::string& id : ids) {
        const ModuleGrade badge = gradeModule(renderer, g.modules.find(id), g.paths, o);
        EXPECT_EQ(badge.status, Grader::find(r, id).status) << id;
        EXPECT_EQ(badge.message, Grader::find(r, id).message) << id;
    }
}

// A report reads back as the grade it was (gradeJson, then gradeFromJson), and the page's own
// reports (id, status, message only: a file that never finished) read as grades too; a status
// that is not one of grading/verdict.h's names is an error naming it.
TEST(Grade, AReportReadsBackAsTheGradeItWas) {
    ModuleGrade g;
    g.id = "ndf";
    g.title = "GGX";
    g.status = GradeStatus::Failed;
    g.score = 0;
    g.maxScore = 2.5;
    g.message = "probe: ...";
    g.mistake = "Your value fits alpha = roughness^1";
    g.namedBy = NamedBy::Pattern;
    g.mistakeGroup = "alpha";
    g.instructorNote = "note";
    g.checks = nlohmann::json::array({{{"name", "probe"}}});
    g.seconds = 1.5;
    const ModuleGrade back = gradeFromJson(gradeJson(g));
    EXPECT_EQ(back.id, g.id);
    EXPECT_EQ(back.title, g.title);
    EXPECT_EQ(back.status, g.status);
    EXPECT_EQ(back.maxScore, g.maxScore);
    EXPECT_EQ(back.message, g.message);
    EXPECT_EQ(back.mistake, g.mistake);
    EXPECT_EQ(back.namedBy, g.namedBy);
    EXPECT_EQ(back.mistakeGroup, g.mistakeGroup);
    EXPECT_EQ(back.instructorNote, g.instructorNote);
    EXPECT_EQ(back.checks, g.checks);
    EXPECT_EQ(back.seconds, g.seconds);

    const ModuleGrade page = gradeFromJson(
        {{"id", "ndf"}, {"status", "timeout"}, {"message", "ndf.glsl did not finish"}});
    EXPECT_EQ(page.status, GradeStatus::Timeout);
    EXPECT_EQ(page.message, "ndf.glsl did not finish");

    EXPECT_THROW(gradeFromJson({{"id", "ndf"}, {"message", "no status"}}), std::exception);
    try {
        gradeFromJson({{"id", "ndf"}, {"status", "passd"}});
        ADD_FAILURE() << "a status that is not one was read";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'passd' is not a status"), std::string::npos)
            << e.what();
    }
}
