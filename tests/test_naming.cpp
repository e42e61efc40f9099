// Feedback that names a missing or extra term (term_fits.h), measured on mistakes written
// apart from the grader's catalogue: tests/naming/<id>/*.glsl, in other styles (variable
// names, formulations, orders of operations) than labs/<id>/mistakes, which the grader
// compares with; these files are never compared with. The first line of each says what the
// message must contain ("// expect: the geometry term G missing"). Each is graded as a
// submission is (a child process per step, every check, feedback on): it must fail, and the
// share of them whose message names the mistake is the named rate of docs/grading.md.
#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "grade.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

struct Mistake {
    std::string step;
    fs::path file;
    std::string expect;
};

std::vector<Mistake> mistakes() {
    std::vector<Mistake> out;
    const fs::path root = fs::path(PBRLAB_SOURCE_DIR) / "tests" / "naming";
    for (const auto& dir : fs::directory_iterator(root))
        for (const auto& f : fs::directory_iterator(dir.path())) {
            if (f.path().extension() != ".glsl") continue;
            std::ifstream in(f.path());
            std::string first;
            std::getline(in, first);
            const std::string prefix = "// expect: ";
            out.push_back({dir.path().filename().string(), f.path(),
                           first.rfind(prefix, 0) == 0 ? first.substr(prefix.size()) : ""});
        }
    std::sort(out.begin(), out.end(),
              [](const Mistake& a, const Mistake& b) { return a.file < b.file; });
    return out;
}

}  // namespace

// Measured on 2026-12-03 (docs/grading.md, "Feedback: the missing or extra term"): 48 of 48
// named. The assertion keeps the measured figure.
constexpr double kMeasuredNamedRate = 1.0;

TEST(Naming, MistakesOutsideTheCatalogueFailAndAreNamedByTheirTerm) {
    const std::vector<Mistake> all = mistakes();
    ASSERT_GE(all.size(), 40u);
    // Rounds of one file per step, each round one submission graded at once.
    std::map<std::string, std::vector<const Mistake*>> byStep;
    for (const Mistake& m : all) {
        ASSERT_FALSE(m.expect.empty()) << m.file << ": no first line `// expect: WORDS`";
        byStep[m.step].push_back(&m);
    }
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    int named = 0, graded = 0;
    for (size_t round = 0;; ++round) {
        test::TempDir kit;
        std::map<std::string, const Mistake*> inRound;
        for (const auto& [step, files] : byStep)
            if (round < files.size()) {
                inRound[step] = files[round];
                fs::copy_file(files[round]->file, kit.path / (step + ".glsl"));
            }
        if (inRound.empty()) break;
        GradeOptions o;
        o.submission = fs::canonical(kit.path);
        for (const auto& [step, m] : inRound) o.modules.push_back(step);
        o.timeoutSeconds = 300;
        const GradeReport r = gradeSubmission(modules, paths, o);
        for (const ModuleGrade& g : r.modules) {
            const Mistake& m = *inRound.at(g.id);
            ++graded;
            EXPECT_EQ(g.status, "failed") << m.file << ": " << g.message;
            const bool ok = g.message.find(m.expect) != std::string::npos;
            named += ok;
            std::printf("[ measured ] %s/%s: %s (%.1f s)%s%s\n", g.id.c_str(),
                        m.file.filename().c_str(), ok ? "named" : "NOT named", g.seconds,
                        ok ? "" : "\n    ", ok ? "" : g.message.c_str());
        }
    }
    EXPECT_EQ(graded, int(all.size()));
    const double rate = double(named) / double(graded);
    std::printf("[ measured ] named %d of %d (%.0f%%)\n", named, graded, 100 * rate);
    EXPECT_GE(rate, kMeasuredNamedRate);
}
