// Assignment files (docs/assignment.md): each broken field named with its file and JSON path,
// partial credit on real grades (a planted mistake that fails some categories and passes
// others, the reference solutions at full points), Gradescope's rows, the release schedule.
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <sstream>

#include "course/assignment.h"
#include "course/autograder.h"
#include "course/gradescope.h"
#include "course/kit.h"
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
    EXPECT_EQ(a.weights.at(CheckCategory::Robustness),
              0);  // reported, not deducted, unless weighted
    EXPECT_EQ(a.weights.at(CheckCategory::Probe), 1);
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

// Two planted mistakes. fresnel's pow6 passes one of the four scene checks (the scene where
// H.V is 1 and the power does not matter), the contract and both invariants: its score is the
// weights' share of what passed, 2 x (1 + 2 x 1/4 + 2) / 10 = 0.7. ndf's alpha = roughness fails
// every values check and passes the contract and the invariants (D's integrals do not see how
// alpha was made), which a stub returning 0 would pass too: no points (docs/assignment.md).
TEST(Assignment, PartialCreditIsTheWeightsShareOfTheChecksPassedOnceOneShowsWork) {
    Graded g;
    const fs::path kit = g.dir.path / "kit";
    writeKit(g.modules, {kit, true, "", false});
    fs::copy_file(g.paths.labs() / "ndf/mistakes/alpha_is_roughness.glsl", kit / "ndf.glsl",
                  fs::copy_options::overwrite_existing);
    fs::copy_file(g.paths.labs() / "fresnel/mistakes/pow6.glsl", kit / "fresnel.glsl",
                  fs::copy_options::overwrite_existing);
    const Assignment a = loadAssignment(g.dir.write("a.json", R"({
        "steps": ["ndotl", "ndf", "fresnel"], "points": {"ndotl": 2, "ndf": 3, "fresnel": 2},
        "checks": {"contract": 1, "probe": 2, "scenes": 2, "random": 2, "sphere_grid": 1,
                   "invariants": 2, "robustness": 0},
        "visibility": {"ndf": "after_due_date", "ndf.invariants": "hidden"}
    })"),
                                        stepIds(g.modules));
    GradeOptions o;
    o.submission = fs::canonical(kit);
    applyAssignment(a, o);
    const GradeReport r = gradeSubmission(g.modules, g.paths, o);
    ASSERT_EQ(r.modules.size(), 3u);
    const ModuleGrade& ndotl = r.modules[0];
    const ModuleGrade& ndf = r.modules[1];
    const ModuleGrade& fresnel = r.modules[2];
    EXPECT_EQ(ndotl.status, GradeStatus::Passed);
    EXPECT_EQ(ndotl.score, 2);  // exactly
    EXPECT_EQ(ndotl.maxScore, 2);
    EXPECT_EQ(ndf.status, GradeStatus::Failed);
    EXPECT_EQ(ndf.maxScore, 3);
    EXPECT_EQ(ndf.score, 0);
    EXPECT_EQ(fresnel.status, GradeStatus::Failed);
    // contract 1 + scenes 2 x 1/4 + invariants 2 of the weights 1 + 2 + 2 + 2 + 1 + 2 = 10,
    // exactly: every score is a whole number of micro-points.
    EXPECT_EQ(fresnel.score, 0.7);
    EXPECT_EQ(r.score, 2.7);
    EXPECT_EQ(r.maxScore, 7);

    const nlohmann::json gs = toGradescope(r, a);
    double sum = 0, ndfMax = 0;
    std::map<std::string, nlohmann::json> rows;
    for (const auto& t : gs["tests"]) {
        sum = addPoints(sum, t["score"].get<double>());
        rows[t["name"]] = t;
        EXPECT_EQ(t["output_format"], "md");
        if (t["extra_data"]["step"] == "ndf") ndfMax = addPoints(ndfMax, t["max_score"]);
    }
    EXPECT_EQ(gs["score"].get<double>(), sum);
    EXPECT_EQ(sum, 2.7);
    EXPECT_EQ(ndfMax, 3);
    ASSERT_TRUE(rows.count("ndf: probe"));
    EXPECT_EQ(rows["ndf: probe"]["status"], "failed");
    EXPECT_EQ(rows["ndf: probe"]["score"], 0);
    EXPECT_EQ(rows["ndf: probe"]["max_score"].get<double>(), 0.6);
    EXPECT_EQ(rows["ndf: probe"]["visibility"], "after_due_date");
    // The feedback names the mistake in the first failed row.
    EXPECT_NE(rows["ndf: probe"]["output"].get<std::string>().find("alpha = roughness"),
              std::string::npos);
    // Its invariants hold, and earn nothing: the row says why.
    EXPECT_EQ(rows["ndf: invariants"]["score"], 0);
    EXPECT_EQ(rows["ndf: invariants"]["status"], "failed");
    EXPECT_NE(rows["ndf: invariants"]["output"].get<std::string>().find("4 of 4 checks passed"),
              std::string::npos);
    EXPECT_NE(rows["ndf: invariants"]["output"].get<std::string>().find(
                  "until a values check of this step passes"),
              std::string::npos)
        << rows["ndf: invariants"]["output"];
    EXPECT_EQ(rows["ndf: invariants"]["visibility"], "hidden");
    EXPECT_FALSE(rows["ndf: invariants"]["extra_data"]["checks"].empty());
    EXPECT_EQ(rows["fresnel: invariants"]["status"], "passed");
    EXPECT_EQ(rows["fresnel: invariants"]["score"], 0.4);
    EXPECT_EQ(rows["fresnel: scenes"]["score"], 0.1);
    // Robustness has weight 0: no row.
    EXPECT_FALSE(rows.count("ndf: robustness"));
    EXPECT_EQ(rows["ndotl: sphere_grid"]["visibility"], "visible");
    // The check that opened fresnel's points is marked in the report.
    int shown = 0;
    for (const auto& c : fresnel.checks) shown += c.value("shows_work", false);
    EXPECT_EQ(shown, 1);
    for (const auto& c : ndf.checks) EXPECT_FALSE(c.value("shows_work", false)) << c.dump();

    // Without partial credit: all or nothing, the step's points.
    Assignment whole = a;
    whole.partialCredit = false;
    GradeOptions w;
    w.submission = o.submission;
    applyAssignment(whole, w);
    const GradeReport rw = gradeSubmission(g.modules, g.paths, w);
    EXPECT_EQ(rw.modules[0].score, 2);
    EXPECT_EQ(rw.modules[1].score, 0);
    EXPECT_EQ(rw.modules[2].score, 0);
    EXPECT_EQ(toGradescope(rw, whole)["tests"].size(), 3u);
}

namespace {

// Every example assignment of the repository: docs/autograder/*.json, those the
// tests and scripts grade by (as they write them), and every step with every category
// weighted (robustness and the estimators' checks included).
std::vector<Assignment> exampleAssignments(const Graded& g) {
    std::vector<Assignment> out;
    for (const char* file : {"assignment.json", "assignment-energy.json"})
        out.push_back(loadAssignment(fs::path(PBRLAB_SOURCE_DIR) / "docs/autograder" / file,
                                     stepIds(g.modules)));
    const std::vector<std::pair<std::string, std::string>> inline_ = {
        {"test_assignment.cpp",
         R"({"steps": ["ndotl", "ndf", "fresnel"], "points": {"ndotl": 2, "ndf": 3, "fresnel": 2},
             "checks": {"contract": 1, "probe": 2, "scenes": 2, "random": 2, "sphere_grid": 1,
                        "invariants": 2, "robustness": 0}})"},
        {"gradescope_bundle.sh",
         R"({"name": "bundle test", "steps": ["ndotl", "ndf", "fresnel"], "points": {"ndf": 3},
             "checks": {"contract": 1, "probe": 2, "scenes": 2, "random": 2, "sphere_grid": 1,
                        "invariants": 2}})"},
        {"classroom_workflow.sh",
         R"({"name": "test", "steps": ["ndf", "fresnel"], "points": {"default": 2, "ndf": 3}})"},
        {"every step, every category",
         R"({"steps": "all", "checks": {"contract": 1, "probe": 1, "scenes": 1, "random": 1,
             "sphere_grid": 1, "invariants": 1, "estimator": 1, "robustness": 1}})"},
    };
    for (const auto& [name, text] : inline_)
        out.push_back(parseAssignment(nlohmann::json::parse(text), name, stepIds(g.modules)));
    return out;
}

// The report `gradeSubmission` gives under the assignment, from grades of its steps made
// without one (a grade's checks do not depend on the points).
GradeReport scored(const GradeReport& graded, const Assignment& a) {
    GradeReport r;
    for (ModuleGrade g : graded.modules) {
        if (std::find(a.steps.begin(), a.steps.end(), g.id) == a.steps.end()) continue;
        scoreGrade(g, a);
        r.score = addPoints(r.score, g.score);
        r.maxScore = addPoints(r.maxScore, g.maxScore);
        r.modules.push_back(g);
    }
    return r;
}

}  // namespace

// Points say that something of a step was done: the untouched kit (every stub returns 0, which
// reads no forbidden map, keeps 0 <= G <= 1 and is finite) scores exactly 0 under every example
// assignment, Gradescope's rows included, and the reference solutions score every point.
TEST(Assignment, AFreshKitScoresZeroAndTheSolutionsFullMarksUnderEveryExampleAssignment) {
    Graded g;
    const fs::path stubs = g.dir.path / "stubs", solutions = g.dir.path / "solutions";
    writeKit(g.modules, {stubs, false, "", false});
    writeKit(g.modules, {solutions, true, "", false});
    GradeOptions o;
    o.timeoutSeconds = 300;
    o.submission = fs::canonical(stubs);
    const GradeReport kit = gradeSubmission(g.modules, g.paths, o);
    o.submission = fs::canonical(solutions);
    const GradeReport reference = gradeSubmission(g.modules, g.paths, o);
    for (const Assignment& a : exampleAssignments(g)) {
        const GradeReport k = scored(kit, a);
        EXPECT_EQ(k.score, 0) << a.file;
        for (const ModuleGrade& m : k.modules) {
            EXPECT_EQ(m.status, GradeStatus::Failed) << a.file << " " << m.id;
            EXPECT_EQ(m.score, 0) << a.file << " " << m.id;
            for (const CategoryScore& c : categoryScores(m, a))
                EXPECT_EQ(c.score, 0) << a.file << " " << m.id << " " << c.category;
        }
        EXPECT_EQ(toGradescope(k, a)["score"].get<double>(), 0) << a.file;
        const GradeReport s = scored(reference, a);
        EXPECT_EQ(s.score, s.maxScore) << a.file;
        EXPECT_GT(s.maxScore, 0) << a.file;
        for (const ModuleGrade& m : s.modules) {
            EXPECT_EQ(m.status, GradeStatus::Passed) << a.file << " " << m.id;
            EXPECT_EQ(m.score, m.maxScore) << a.file << " " << m.id;
        }
        EXPECT_EQ(toGradescope(s, a)["score"].get<double>(), s.maxScore) << a.file;
    }
}

namespace {

// What `pbrlab ARGS` prints on stdout; fails the test unless it exits 0.
std::string pbrlabOutput(const std::string& args) {
    std::string out;
    FILE* p = popen((PBRLAB_EXECUTABLE " " + args).c_str(), "r");
    char buffer[512];
    for (size_t n; (n = fread(buffer, 1, sizeof buffer, p)) > 0;) out.append(buffer, n);
    EXPECT_EQ(pclose(p), 0) << args << "\n" << out;
    return out;
}

std::string fileText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every "score" and "max_score" in a report, as JSON writes it, with where it is.
void pointsIn(const nlohmann::json& j, const std::string& at,
              std::vector<std::pair<std::string, std::string>>& out) {
    if (j.is_object()) {
        for (const auto& [key, value] : j.items()) {
            if ((key == "score" || key == "max_score") && value.is_number())
                out.push_back({at + "." + key, value.dump()});
            else
                pointsIn(value, at + "." + key, out);
        }
    } else if (j.is_array()) {
        for (size_t i = 0; i < j.size(); ++i)
            pointsIn(j[i], at + "[" + std::to_string(i) + "]", out);
    }
}

// The fields of the line of `text` that starts with `first` (whitespace-separated).
std::vector<std::string> lineStartingWith(const std::string& text, const std::string& first) {
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
        std::istringstream in(line);
        std::vector<std::string> fields;
        for (std::string f; in >> f;) fields.push_back(f);
        if (!fields.empty() && fields[0] == first) return fields;
    }
    return {};
}

}  // namespace

// One rounding rule in every report: points in whole micro-points, written as decimals of at
// most six places, the total the sum of the parts. Steps worth 0.1 and 0.2 (whose binary sum
// is 0.30000000000000004) and fresnel's planted mistake pow6 graded in thirds (contract 1,
// probe 1, scenes 1): fresnel earns the contract's 0.333333 and 1 of the 4 scene checks'
// 0.333334 (the last category takes what the others leave), 0.083334 rounded half up.
TEST(Assignment, EveryReportGivesTheSamePointsRoundedToTheMicroPoint) {
    Graded g;
    const fs::path kit = g.dir.path / "kit";
    KitOptions k;
    k.out = kit;
    k.withSolutions = true;
    k.steps = {"ndotl", "ndf", "fresnel"};
    writeKit(g.modules, k);
    fs::copy_file(g.paths.labs() / "fresnel/mistakes/pow6.glsl", kit / "fresnel.glsl",
                  fs::copy_options::overwrite_existing);
    const fs::path assignment = g.dir.write("a.json", R"({
        "steps": ["ndotl", "ndf", "fresnel"], "points": {"ndotl": 0.1, "ndf": 0.2, "fresnel": 1},
        "checks": {"contract": 1, "probe": 1, "scenes": 1, "random": 0, "sphere_grid": 0,
                   "invariants": 0, "robustness": 0}
    })");
    const fs::path out = g.dir.path / "out";
    const std::string text = pbrlabOutput(
        "grade " + kit.string() + " --assignment " + assignment.string() + " --json " +
        (out / "report.json").string() + " --gradescope " + (out / "results.json").string() +
        " --html " + (out / "html").string() + " --jobs 2");
    // The class reports: the same submission graded with --batch.
    fs::create_directories(g.dir.path / "class");
    fs::copy(kit, g.dir.path / "class/alice", fs::copy_options::recursive);
    pbrlabOutput("grade --batch " + (g.dir.path / "class").string() + " --out " +
                 (g.dir.path / "reports").string() + " --assignment " + assignment.string() +
                 " --jobs 2 2>/dev/null");

    const std::map<std::string, std::string> steps = {
        {"ndotl", "0.1"}, {"ndf", "0.2"}, {"fresnel", "0.416667"}};
    const std::map<std::string, std::string> maxima = {
        {"ndotl", "0.1"}, {"ndf", "0.2"}, {"fresnel", "1"}};
    for (const fs::path& dir : {out, g.dir.path / "reports/alice"}) {
        const auto report = nlohmann::json::parse(fileText(dir / "report.json"));
        const auto results = nlohmann::json::parse(fileText(dir / "results.json"));
        // Every number as JSON writes it: a decimal of at most six places.
        std::vector<std::pair<std::string, std::string>> numbers;
        pointsIn(report, "report.json", numbers);
        pointsIn(results, "results.json", numbers);
        EXPECT_GE(numbers.size(), 14u);
        for (const auto& [where, number] : numbers)
            EXPECT_TRUE(std::regex_match(number, std::regex(R"(-?[0-9]+(\.[0-9]{1,6})?)")))
                << where << " = " << number;
        EXPECT_EQ(report["score"].get<double>(), 0.716667);
        EXPECT_EQ(report["max_score"].get<double>(), 1.3);
        for (const auto& m : report["modules"]) {
            EXPECT_EQ(m["score"].get<double>(), std::stod(steps.at(m["id"]))) << m["id"];
            EXPECT_EQ(m["max_score"].get<double>(), std::stod(maxima.at(m["id"]))) << m["id"];
        }
        // results.json: the same total, the sum of its rows exactly.
        EXPECT_EQ(results["score"].get<double>(), 0.716667);
        EXPECT_EQ(results["extra_data"]["max_score"].get<double>(), 1.3);
        double sum = 0;
        std::map<std::string, std::pair<double, double>> rows;
        for (const auto& t : results["tests"]) {
            sum = addPoints(sum, t["score"].get<double>());
            rows[t["name"]] = {t["score"].get<double>(), t["max_score"].get<double>()};
        }
        EXPECT_EQ(sum, results["score"].get<double>());
        EXPECT_EQ(rows["fresnel: contract"], std::make_pair(0.333333, 0.333333));
        EXPECT_EQ(rows["fresnel: probe"], std::make_pair(0.0, 0.333333));
        EXPECT_EQ(rows["fresnel: scenes"], std::make_pair(0.083334, 0.333334));
        EXPECT_NE(results["output"].get<std::string>().find("| fresnel | failed | 0.416667 / 1 |"),
                  std::string::npos)
            << results["output"];
    }
    // The text `pbrlab grade` prints.
    for (const auto& [id, score] : steps) {
        const std::vector<std::string> line = lineStartingWith(text, id);
        ASSERT_GE(line.size(), 5u) << text;
        EXPECT_EQ(line[2] + " / " + line[4], score + " / " + maxima.at(id)) << text;
    }
    const std::vector<std::string> total = lineStartingWith(text, "total");
    ASSERT_GE(total.size(), 4u) << text;
    EXPECT_EQ(total[1] + " / " + total[3], "0.716667 / 1.3") << text;
    // The HTML report.
    const std::string html = fileText(out / "html/index.html");
    EXPECT_NE(html.find("score 0.716667 / 1.3 "), std::string::npos);
    EXPECT_NE(html.find("<br>0.416667 / 1</td>"), std::string::npos);
    // The class reports.
    const fs::path reports = g.dir.path / "reports";
    EXPECT_NE(fileText(reports / "summary.csv").find("\nalice,0.716667,1.3,"), std::string::npos)
        << fileText(reports / "summary.csv");
    const std::string csv = fileText(reports / "class.csv");
    EXPECT_NE(csv.find("\nalice,ndotl,passed,0.1,0.1,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("\nalice,fresnel,failed,0.416667,1,"), std::string::npos) << csv;
    EXPECT_NE(fileText(reports / "class.html").find("mean score 0.716667 / 1.3;"),
              std::string::npos);
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
