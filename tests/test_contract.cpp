#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>

#include "steps/contract.h"
#include "test_support.h"
#include "util/error.h"

using namespace pbrlab;
namespace test = pbrlab::test;

TEST(Contract, TheThreeLabsStepsInOrderWithUniqueIds) {
    // direct: 14 steps, ibl: 7, energy: 5 (the ids that start each lab are checked below).
    const auto& steps = contractSteps();
    ASSERT_EQ(steps.size(), 26u);
    std::set<std::string> ids;
    for (size_t i = 0; i < steps.size(); ++i) {
        EXPECT_EQ(steps[i].step, int(i + 1));
        EXPECT_TRUE(ids.insert(steps[i].id).second) << steps[i].id;
        EXPECT_EQ(steps[i].lab, i < 14 ? "direct" : i < 21 ? "ibl" : "energy");
        EXPECT_TRUE(std::filesystem::exists(steps[i].folder / "solution.glsl")) << steps[i].id;
        if (i > 0) {
            EXPECT_LT(steps[i - 1].order, steps[i].order);
        }
        for (const auto& c : steps[i].calls) {
            const ContractStep* callee = findContractStep(c);
            ASSERT_NE(callee, nullptr) << c;
            EXPECT_LT(callee->step, steps[i].step) << "files are concatenated in step order";
        }
    }
    EXPECT_EQ(findContractStep("ndotl")->numbered(), "04-ndotl");
    EXPECT_EQ(findContractStep("ndotl")->folder.filename(), "ndotl");
    EXPECT_EQ(findContractStep("hammersley")->step, 15);
    EXPECT_EQ(findContractStep("furnace")->step, 22);
}

TEST(Contract, ClosureHoldsEarlierStepsOfTheLabAndWhatTheyCall) {
    std::vector<std::string> ids;
    for (auto* s : contractClosure("ndotl", {})) ids.push_back(s->id);
    EXPECT_EQ(ids, (std::vector<std::string>{"albedo", "radiance", "halfway", "ndotl"}));
    ids.clear();
    for (auto* s : contractClosure("split_sum", {})) ids.push_back(s->id);
    // IBL steps pull in only the direct-lab functions they call.
    EXPECT_EQ(std::count(ids.begin(), ids.end(), "f0"), 1);
    EXPECT_EQ(std::count(ids.begin(), ids.end(), "reflectance"), 0);
}

// docs/design.md carries the contract students write against: each row must say what the
// host's contract says (number, id, signature), so the document cannot drift from the code.
TEST(Contract, TheDesignDocumentsTableIsTheHostsContract) {
    std::ifstream in(std::string(PBRLAB_SOURCE_DIR) + "/docs/design.md");
    ASSERT_TRUE(in) << "docs/design.md is missing";
    std::vector<std::string> rows;
    for (std::string line; std::getline(in, line);)
        if (line.size() > 3 && line[0] == '|' && std::isdigit(static_cast<unsigned char>(line[2])))
            rows.push_back(line);
    const auto& steps = contractSteps();
    ASSERT_EQ(rows.size(), steps.size());
    for (size_t i = 0; i < steps.size(); ++i) {
        const std::string start = "| " + std::to_string(steps[i].step) + " | " + steps[i].id +
                                  " | `" + steps[i].function + "`";
        EXPECT_EQ(rows[i].rfind(start, 0), 0u) << rows[i] << "\nexpected to start with " << start;
    }
}

namespace {

// A step folder in `root`: step.json with these fields (JSON text of the object's members).
void stepFolder(const test::TempDir& root, const std::string& id, const std::string& members) {
    root.write(id + "/step.json", "{" + members + "}");
}

std::string errorOf(const std::vector<std::filesystem::path>& roots) {
    try {
        readStepFolders(roots);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

// A step inserted between two others takes its place by its order key alone: nothing else
// changes, and the steps after it move down one position.
TEST(Contract, AStepFolderJoinsAtItsOrderKey) {
    test::TempDir extra;
    stepFolder(extra, "lambert_again",
               R"j("id": "lambert_again", "lab": "direct", "order": 45,
                  "function": "float lambertAgain(vec3 N, vec3 L)", "calls": ["ndotl"])j");
    const auto builtIn = std::filesystem::path(PBRLAB_SOURCE_DIR) / "labs";
    const std::vector<ContractStep> steps = readStepFolders({builtIn, extra.path});
    ASSERT_EQ(steps.size(), contractSteps().size() + 1);
    EXPECT_EQ(steps[3].id, "ndotl");
    EXPECT_EQ(steps[4].id, "lambert_again");
    EXPECT_EQ(steps[4].step, 5);
    EXPECT_EQ(steps[5].id, "ndf");
    EXPECT_EQ(steps[5].step, 6);
    EXPECT_EQ(steps[4].folder, extra.path / "lambert_again");
}

TEST(Contract, BrokenStepFoldersAreErrorsNamingTheFile) {
    const auto builtIn = std::filesystem::path(PBRLAB_SOURCE_DIR) / "labs";
    struct Case {
        std::string members, says;
    };
    const std::vector<Case> cases = {
        {R"j("id": "x", "lab": "direct", "order": 45)j", "missing field \"function\""},
        {R"j("id": "x", "lab": "direct", "order": "first", "function": "float f()")j",
         "wrong type"},
        {R"j("id": "no good", "lab": "direct", "order": 45, "function": "float f()")j",
         "letters, digits and _"},
        {R"j("id": "ndotl", "lab": "direct", "order": 45, "function": "float f()")j",
         "already declared by"},
        {R"j("id": "x", "lab": "direct", "order": 40, "function": "float f()")j",
         "is also ndotl's"},
        {R"j("id": "x", "lab": "direct", "order": 45, "function": "float lambertCosine(vec3 N)")j",
         "function lambertCosine is already ndotl's"},
        {R"j("id": "x", "lab": "direct", "order": 45, "function": "float f()", "hides": ["ndf"])j",
         "hides 'ndf', which is no earlier step"},
        {R"j("id": "x", "lab": "direct", "order": 115, "function": "float f()",
             "hides": ["specular"])j",
         "hides 'specular', which brdf calls"},
        {R"j("id": "x", "lab": "direct", "order": 45, "function": "float f()", "calls": ["nope"])j",
         "calls 'nope', which no step folder declares"},
        {R"j("id": "x", "lab": "direct", "order": 45, "function": "float f()", "calls": ["ndf"])j",
         "calls 'ndf', which comes after it"},
        {R"j("id": "x", "lab": "direct", "order": 45, "function": "float f()",
             "helpers": [{"function": "float g()"}])j",
         "each \"helpers\" entry names its \"function\""},
    };
    for (const Case& c : cases) {
        test::TempDir extra;
        stepFolder(extra, "x", c.members);
        const std::string error = errorOf({builtIn, extra.path});
        EXPECT_NE(error.find(c.says), std::string::npos) << c.members << "\n" << error;
        EXPECT_NE(error.find("step.json"), std::string::npos) << error;
    }
    // A step's precompute pass: a kind the host runs, a shader of the step's own folder, the
    // sampler its map is bound to.
    const std::string x = R"j("id": "x", "lab": "ibl", "order": 205, "function": "float f()", )j";
    const std::vector<Case> passes = {
        {x + R"j("precompute": "pass.frag")j", "\"precompute\" must be an object"},
        {x + R"j("precompute": {"kind": "sphere", "shader": "pass.frag", "sampler": "uX"})j",
         "\"kind\" is \"sphere\"; one of cube, cube_mips, square"},
        {x + R"j("precompute": {"kind": "cube", "sampler": "uX"})j", "missing field \"shader\""},
        {x + R"j("precompute": {"kind": "cube", "shader": "pass.frag"})j",
         "missing field \"sampler\""},
        {x + R"j("precompute": {"kind": "cube", "shader": "none.frag", "sampler": "uX"})j",
         "none.frag does not exist"},
        {x + R"j("precompute": {"kind": "cube", "shader": "../pass.frag", "sampler": "uX"})j",
         "must name a file in the step folder"},
        {x + R"j("precompute": {"kind": "cube", "shader": "pass.frag", "sampler": "u X"})j",
         "\"sampler\" is not a GLSL name"},
    };
    for (const Case& c : passes) {
        test::TempDir extra;
        stepFolder(extra, "x", c.members);
        extra.write("x/pass.frag", "void main() {}\n");
        extra.write("pass.frag", "void main() {}\n");
        const std::string error = errorOf({builtIn, extra.path});
        EXPECT_NE(error.find(c.says), std::string::npos) << c.members << "\n" << error;
        EXPECT_NE(error.find("step.json: \"precompute\""), std::string::npos) << error;
    }
    test::TempDir notJson;
    notJson.write("x/step.json", "{ id: ");
    EXPECT_NE(errorOf({builtIn, notJson.path}).find("not valid JSON"), std::string::npos);
}

// A step declares the pass that computes its map in its own folder; the map's sampler is what
// it provides.
TEST(Contract, APrecomputePassIsDeclaredInTheStepFolder) {
    test::TempDir extra;
    stepFolder(extra, "x",
               R"j("id": "x", "lab": "ibl", "order": 205, "function": "float f()",
                  "precompute": {"kind": "cube_mips", "shader": "pass.frag",
                                 "sampler": "uOtherMap"})j");
    extra.write("x/pass.frag", "void main() {}\n");
    const auto builtIn = std::filesystem::path(PBRLAB_SOURCE_DIR) / "labs";
    const std::vector<ContractStep> steps = readStepFolders({builtIn, extra.path});
    const auto x =
        std::find_if(steps.begin(), steps.end(), [](const ContractStep& s) { return s.id == "x"; });
    ASSERT_NE(x, steps.end());
    ASSERT_TRUE(x->precompute.has_value());
    EXPECT_EQ(x->precompute->kind, ContractStep::PrecomputePass::Kind::CubeMips);
    EXPECT_EQ(x->precompute->shader, extra.path / "x" / "pass.frag");
    EXPECT_EQ(x->provides, std::vector<std::string>{"uOtherMap"});
    // The built-in map steps declare theirs the same way.
    for (const auto& [id, sampler] : {std::pair{"irradiance", "uIrradianceMap"},
                                      {"prefilter", "uPrefilterMap"},
                                      {"brdf_lut", "uBrdfLut"}}) {
        const auto s = std::find_if(steps.begin(), steps.end(),
                                    [&](const ContractStep& t) { return t.id == id; });
        ASSERT_NE(s, steps.end());
        ASSERT_TRUE(s->precompute.has_value()) << id;
        EXPECT_EQ(s->precompute->sampler, sampler);
        EXPECT_TRUE(std::filesystem::is_regular_file(s->precompute->shader)) << id;
    }
}
