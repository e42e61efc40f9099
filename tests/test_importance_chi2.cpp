// Step 16 judged as a sampler, in the grader: the chi-square test of the student's own half
// vectors against the GGX density D(h) (N.h) (ref::ggxHalfVectorChiSquare, run by the
// importance module's invariants on its sample.glsl view). Correct samplers in any orthonormal
// frame pass it; the typical mistakes (labs/importance/mistakes) are rejected by it or by
// the unit-length check beside it. The chi-square machinery itself is checked on CPU samplers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gl/context.h"
#include "grading/grade_step.h"
#include "pbrlab/ibl_reference.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

struct Sampler {
    std::string file;  // a correct variant or a mistake; empty: the reference solution
    bool correct = true;
};
void PrintTo(const Sampler& s, std::ostream* os) {
    *os << (s.file.empty() ? "reference solution" : s.file);
}

std::vector<Sampler> samplers() {
    std::vector<Sampler> v{{"", true}};
    const fs::path root(PBRLAB_SOURCE_DIR);
    for (const auto& [dir, correct] : {std::pair{root / "tests/variants/importance", true},
                                       std::pair{root / "labs/importance/mistakes", false}})
        if (fs::exists(dir))
            for (const auto& f : fs::directory_iterator(dir))
                if (f.path().extension() == ".glsl") v.push_back({f.path().string(), correct});
    std::sort(v.begin(), v.end(),
              [](const Sampler& a, const Sampler& b) { return a.file < b.file; });
    return v;
}

class ImportanceChiSquare : public testing::TestWithParam<Sampler> {};

}  // namespace

TEST_P(ImportanceChiSquare, CorrectSamplersFollowTheGgxDensityMistakesDoNot) {
    const Sampler& sampler = GetParam();
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};
    test::TempDir kit;
    StudentSource source;
    if (!sampler.file.empty()) {
        fs::copy(sampler.file, kit.path / "importance.glsl");
        source.dir = kit.path;
    }
    GradeSettings settings;
    settings.robustness = false;
    const StepResult r = gradeStep(renderer, modules.find("importance"), paths, source, settings);
    const CheckReport* chi2 = nullptr;
    const CheckReport* unit = nullptr;
    for (const CheckReport& c : r.checks) {
        if (c.name.rfind("chi-square", 0) == 0) chi2 = &c;
        if (c.name.rfind("samples that are not unit vectors", 0) == 0) unit = &c;
    }
    ASSERT_TRUE(chi2 && unit);
    std::printf(
        "[ measured ] %s: smallest p %.3g (%s), %g samples not unit vectors above N\n",
        sampler.file.empty() ? "reference solution" : fs::path(sampler.file).filename().c_str(),
        chi2->measured, chi2->expected.c_str(), unit->measured);
    if (sampler.correct) {
        EXPECT_TRUE(chi2->passed) << chi2->detail;
        EXPECT_TRUE(unit->passed) << unit->detail;
    } else {
        EXPECT_FALSE(chi2->passed && unit->passed) << "a mistake follows the GGX density";
    }
}

INSTANTIATE_TEST_SUITE_P(Labs, ImportanceChiSquare, testing::ValuesIn(samplers()),
                         [](const testing::TestParamInfo<Sampler>& info) {
                             std::string name = info.param.file.empty()
                                                    ? std::string("reference_solution")
                                                    : fs::path(info.param.file).stem().string();
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

// The test itself, on CPU samplers: the reference sampler in double passes at every case;
// alpha in place of alpha^2 (invisible at roughness 1 only) and a sampler that ignores phi's
// second half are rejected; an unnormalised H is counted invalid.
TEST(ImportanceChiSquare, TheTestTellsTheGgxDensityFromOthers) {
    DomainRandom random(11);
    auto run = [&](auto sample, const glm::dvec3& N, double roughness) {
        std::vector<glm::dvec3> H;
        for (int i = 0; i < 4096; ++i)
            H.push_back(sample(glm::dvec2(random.uniform(), random.uniform()), N, roughness));
        return ref::ggxHalfVectorChiSquare(H, N, roughness);
    };
    const glm::dvec3 N = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
    for (double r : {0.1, 0.3, 0.6, 1.0}) {
        const ref::ChiSquareTest t = run(ref::importanceSampleGGX, N, r);
        EXPECT_GT(t.pValue, 1e-4) << "roughness " << r;
        EXPECT_EQ(t.invalid, 0);
    }
    auto alphaNotSquared = [](const glm::dvec2& xi, const glm::dvec3& n, double r) {
        return ref::importanceSampleGGX(xi, n, std::sqrt(r));
    };
    EXPECT_LT(run(alphaNotSquared, N, 0.3).pValue, 1e-6);
    auto halfTurn = [](const glm::dvec2& xi, const glm::dvec3& n, double r) {
        return ref::importanceSampleGGX({0.5 * xi.x, xi.y}, n, r);
    };
    EXPECT_LT(run(halfTurn, N, 0.6).pValue, 1e-6);
    auto unnormalised = [](const glm::dvec2& xi, const glm::dvec3& n, double r) {
        return 0.5 * ref::importanceSampleGGX(xi, n, r);
    };
    EXPECT_EQ(run(unnormalised, N, 0.6).invalid, 4096);
}
