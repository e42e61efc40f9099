// Correct solutions written differently must pass and typical mistakes must fail, at their
// own step, graded exactly as a submission is (gradeSubmission: a child process, every check).
//   tests/variants/<id>/correct_*.glsl   correct alternatives (other frames, sequences,
//                                        quadratures, epsilons, the lesson's code)
//   tests/variants/<id>/mistake_*.glsl   mistakes planted against one check of the grader
//                                        (a NaN on an input callers produce, a hard-coded host
//                                        value, a count ignored above the graded ones)
//   tests/variants/<id>/mistake_band_*   estimator mistakes that fail by the value band alone:
//                                        every other check passes, so a band that lets
//                                        everything through is noticed
//   labs/<id>/mistakes/*.glsl           the typical mistakes the grader also names
//   labs/<id>/variants/*.glsl           correct_* and mistake_* as in tests/variants, kept in the
//                                        step's own folder (an added lab needs no other)
//   tests/exploits/<id>/*.glsl           shortcuts found by reading the grader
// Every mistake and exploit has a line "// expect: WORDS": what the failure message must
// contain, the mistake named as the student is to read it. A file of labs/<id>/mistakes is
// also what the grader's typical-mistake match compares with (its leading comment is the
// name), so its words are checked here in what the student reads and, apart from that match,
// by Naming.CatalogueMistakesAreNamedWithoutTheCatalogue (test_naming.cpp).
// A mistake must fail by a margin, not by a hair: its worst check is at least twice outside
// the band (or an invariant, convergence or contract check fails).
#include <gtest/gtest.h>

#include <fstream>

#include "course/autograder.h"
#include "steps/contract.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

struct Variant {
    std::string module, kind, file;  // kind: correct | mistake | exploit
    fs::path path;
};
void PrintTo(const Variant& v, std::ostream* os) {
    *os << v.module << "/" << v.kind << "/" << v.file;
}

std::vector<Variant> allVariants() {
    std::vector<Variant> v;
    const fs::path root = fs::path(PBRLAB_SOURCE_DIR) / "tests";
    for (const char* kind : {"variants", "exploits"}) {
        if (!fs::exists(root / kind)) continue;
        for (const auto& dir : fs::directory_iterator(root / kind))
            for (const auto& f : fs::directory_iterator(dir.path()))
                if (f.path().extension() == ".glsl")
                    v.push_back({dir.path().filename().string(),
                                 std::string(kind) == "exploits" ? "exploit"
                                 : f.path().filename().string().rfind("mistake_", 0) == 0
                                     ? "mistake"
                                     : "correct",
                                 f.path().filename().string(), f.path()});
    }
    for (const auto& step : contractSteps()) {
        for (const char* folder : {"mistakes", "variants"}) {
            const fs::path dir = step.folder / folder;
            if (!fs::exists(dir)) continue;
            for (const auto& f : fs::directory_iterator(dir)) {
                if (f.path().extension() != ".glsl") continue;
                const std::string file = f.path().filename().string();
                const bool mistake =
                    std::string(folder) == "mistakes" || file.rfind("mistake_", 0) == 0;
                v.push_back({step.id, mistake ? "mistake" : "correct", file, f.path()});
            }
        }
    }
    std::sort(v.begin(), v.end(), [](const Variant& a, const Variant& b) {
        return a.module + a.kind + a.file < b.module + b.kind + b.file;
    });
    return v;
}

// What the file says the message must contain ("// expect: pi/4"), or "".
std::string expectation(const fs::path& file) {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("// expect: ", 0) == 0) return line.substr(11);
    return "";
}

// The margin a mistake must fail by: 2 unless the file states a floor of its own and why
// (`// margin: 1.5 because ...`), for a mistake the band can only see through the converged
// value's own error.
double marginFloor(const fs::path& file) {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
        if (line.rfind("// margin: ", 0) == 0) {
            const double floor = std::stod(line.substr(11));
            EXPECT_GT(floor, 1.0) << file;
            EXPECT_NE(line.find(" because "), std::string::npos) << file << ": a margin says why";
            return floor;
        }
    return 2.0;
}

struct Grader {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
};

// How clearly a failed grade failed: the worst band excess of its failed value checks, or
// infinity when an invariant, convergence or contract check failed.
double failureMargin(const ModuleGrade& g) {
    double margin = 0;
    for (const auto& c : g.checks) {
        if (c.value("passed", true) || !c.value("deducted", true)) continue;
        if (c.value("kind", "") == "values")
            margin = std::max(margin, double(c.value("worst_excess", 0.0)));
        else
            margin = 1e30;
    }
    return margin;
}

class VariantTest : public testing::TestWithParam<Variant> {};

}  // namespace

// Each variant is graded at its own step only (that a mistake costs no other step is
// Grade.EachProblemCostsOnlyItsOwnStep's: grading all 21 steps per variant would cost 149 x).
TEST_P(VariantTest, CorrectPassesMistakeFailsByAMargin) {
    const Variant& v = GetParam();
    Grader g;
    test::TempDir kit;
    fs::copy(v.path, kit.path / (v.module + ".glsl"));
    GradeOptions o;
    o.submission = fs::canonical(kit.path);
    o.modules = {v.module};
    o.timeoutSeconds = 300;
    const GradeReport r = gradeSubmission(g.modules, g.paths, o);
    ASSERT_EQ(r.modules.size(), 1u);
    const ModuleGrade& m = r.modules[0];
    if (v.kind == "correct") {
        EXPECT_EQ(m.status, GradeStatus::Passed) << m.message;
        return;
    }
    // A mistake that does not compile proves nothing about the grader.
    EXPECT_EQ(m.status, GradeStatus::Failed) << m.message;
    const double margin = failureMargin(m);
    std::printf("[ measured ] %s/%s: fails by %.3g x the tolerance\n", v.module.c_str(),
                v.file.c_str(), margin);
    EXPECT_GE(margin, marginFloor(v.path)) << m.message;
    // A mistake matched to a mutant of the reference is named by the mutant's family; the
    // change itself quotes the reference solution and goes to the instructor only.
    if (m.namedBy == NamedBy::Mutant) {
        EXPECT_EQ(m.message.find('`'), std::string::npos) << m.message;
        EXPECT_FALSE(m.instructorNote.empty());
    }
    const std::string e = expectation(v.path);
    ASSERT_FALSE(e.empty()) << v.path << ": no line `// expect: WORDS` (what the message names)";
    EXPECT_NE(m.message.find(e), std::string::npos) << "expected \"" << e << "\" in: " << m.message;
    // The estimator's band tested on its own: every check that fails is a values check (the
    // fall, the bias test, the counts used, linearity, finite values and the overall scale
    // all pass), and one of the bands at the graded counts fails. The checks facing a sun and
    // in the picture, detectors of their own that came after these files, may see it too.
    if (v.file.rfind("mistake_band_", 0) == 0) {
        int failedValues = 0;
        for (const auto& c : m.checks) {
            if (c.value("passed", true) || !c.value("deducted", true)) continue;
            const std::string name = c.value("name", "");
            if (name.find("in the picture") != std::string::npos ||
                name.find("facing the sun") != std::string::npos)
                continue;
            EXPECT_EQ(c.value("kind", ""), "values")
                << "not a band: " << c.value("name", "") << ": " << c.value("detail", "");
            failedValues += c.value("kind", "") == "values";
        }
        EXPECT_GT(failedValues, 0) << m.message;
    }
}

TEST(Variants, EveryModuleHasTwoCorrectVariantsAndThreeMistakes) {
    Grader g;
    ASSERT_EQ(g.modules.modules().size(), contractSteps().size());  // all 21 load
    for (const auto& m : g.modules.modules()) {
        int correct = 0, mistakes = 0;
        for (const auto& v : allVariants())
            if (v.module == m.desc->id) (v.kind == "correct" ? correct : mistakes)++;
        // Estimators: other frames, sequences, quadratures, filtered sampling, plain MC.
        EXPECT_GE(correct, m.desc->estimator ? 3 : 2) << m.desc->id;
        EXPECT_GE(mistakes, 3) << m.desc->id;
    }
}

INSTANTIATE_TEST_SUITE_P(Labs, VariantTest, testing::ValuesIn(allVariants()),
                         [](const testing::TestParamInfo<Variant>& info) {
                             std::string name =
                                 info.param.module + "_" + info.param.kind + "_" + info.param.file;
                             name = name.substr(0, name.size() - 5);  // drop .glsl
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });
