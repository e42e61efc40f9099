// Stepwise checking must accept correct solutions written differently and reject typical
// mistakes at their own step. Correct variants live in tests/variants/<id>/correct_*.glsl;
// the typical mistakes in labs/NN-id/mistakes/*.glsl, where the grader also reads them to name
// a student's mistake (tests/variants/<id>/mistake_*.glsl are still read, for modules in
// progress). Each is a complete student file, checked as `pbrlab check <id> --submission` does.
#include <gtest/gtest.h>

#include "check.h"
#include "gl/context.h"
#include "pbrlab/contract.h"
#include "test_support.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

fs::path variantsRoot() {
    return fs::path(PBRLAB_SOURCE_DIR) / "tests" / "variants";
}

struct Variant {
    std::string module, file;  // file: "correct_x.glsl" or "mistake_x.glsl"
    fs::path path;
};
void PrintTo(const Variant& v, std::ostream* os) {
    *os << v.module << "/" << v.file;
}

std::vector<Variant> allVariants() {
    std::vector<Variant> v;
    if (fs::exists(variantsRoot()))
        for (const auto& dir : fs::directory_iterator(variantsRoot()))
            for (const auto& f : fs::directory_iterator(dir.path()))
                if (f.path().extension() == ".glsl")
                    v.push_back(
                        {dir.path().filename().string(), f.path().filename().string(), f.path()});
    for (const auto& step : contractSteps()) {
        fs::path dir = fs::path(PBRLAB_SOURCE_DIR) / "labs" / step.folder() / "mistakes";
        if (!fs::exists(dir)) continue;
        for (const auto& f : fs::directory_iterator(dir))
            if (f.path().extension() == ".glsl")
                v.push_back({step.id, "mistake_" + f.path().filename().string(), f.path()});
    }
    std::sort(v.begin(), v.end(), [](const Variant& a, const Variant& b) {
        return a.module + a.file < b.module + b.file;
    });
    return v;
}

struct Session {
    std::unique_ptr<GlContext> context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR, paths.labs()};
    LabRenderer renderer{paths};
};

class VariantTest : public testing::TestWithParam<Variant> {};

}  // namespace

TEST_P(VariantTest, CorrectPassesAndMistakeFailsAtItsOwnStep) {
    const Variant& v = GetParam();
    Session s;
    const LoadedModule& m = s.modules.find(v.module);
    test::TempDir kit;
    fs::copy(v.path, kit.path / (v.module + ".glsl"));
    Scene scene = loadScene(s.paths.scene(m.desc->scene));
    CheckResult r = checkModule(s.renderer, m, ParamValues(m.desc->params), scene, {kit.path}, 128,
                                128);  // a mistake that does not compile throws: test fails
    std::string details = "scene: " + describe(r.scene, m.desc->tolerance) +
                          "\nprobe: " + describe(r.probe, m.desc->tolerance);
    if (v.file.rfind("correct_", 0) == 0)
        EXPECT_TRUE(r.passed) << details;
    else
        EXPECT_FALSE(r.passed) << details;
}

TEST(Variants, EveryModuleHasTwoCorrectVariantsAndThreeMistakes) {
    Session s;
    for (const auto& m : s.modules.modules()) {
        int correct = 0, mistakes = 0;
        for (const auto& v : allVariants())
            if (v.module == m.desc->id) (v.file.rfind("correct_", 0) == 0 ? correct : mistakes)++;
        EXPECT_GE(correct, 2) << m.desc->id;
        EXPECT_GE(mistakes, 3) << m.desc->id;
    }
}

INSTANTIATE_TEST_SUITE_P(Labs, VariantTest, testing::ValuesIn(allVariants()),
                         [](const testing::TestParamInfo<Variant>& info) {
                             std::string name = info.param.module + "_" + info.param.file;
                             name = name.substr(0, name.size() - 5);  // drop .glsl
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });
