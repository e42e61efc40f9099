// The mutation score, in CI: the generator makes every family from a solution's text (and
// leaves comments and preprocessor lines alone), and a fixed subset of the reference
// solutions' mutants, graded exactly as submissions are, leaves no survivor that is not
// equivalent. The full run is `pbrlab mutants` (docs/grading.md has its table).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "course/mutation_score.h"
#include "gl/context.h"
#include "grading/mutants_semantic.h"
#include "shader/program.h"
#include "steps/contract.h"
#include "test_support.h"

using namespace pbrlab;

namespace {

const char* kSample = R"(// a comment with 2.0 * PI that is left alone
#define PBRLAB_SOMETHING 3
float pbrlab_helper(float x) { return x * x; }

vec3 fresnelLike(float cosTheta, vec3 F0, uint n)
{
    // BEGIN SOLUTION
    float c = clamp(1.0 - cosTheta, 0.0, 1.0);
    vec3 sum = vec3(0.0);
    for (uint i = 0u; i < n; ++i) sum += F0 * float(i);
    float w = c > 0.5 ? c : -c;
    return F0 + (1.0 - F0) * pow(c, 5.0) / PI + normalize(sum).xyz * sqrt(w) + max(w, 0.1);
    // END SOLUTION
}
)";

}  // namespace

TEST(Mutants, EveryFamilyIsMadeAndCommentsArePreserved) {
    const std::vector<Mutant> mutants = generateMutants(kSample);
    std::set<std::string> families;
    for (const Mutant& m : mutants) {
        families.insert(m.family);
        EXPECT_NE(m.text, kSample);
        EXPECT_NE(m.text.find("// a comment with 2.0 * PI that is left alone"), std::string::npos)
            << m.description;
        EXPECT_NE(m.text.find("#define PBRLAB_SOMETHING 3"), std::string::npos) << m.description;
        EXPECT_GT(m.line, 2) << m.description;
    }
    for (const MutantFamily& f : mutantFamilies())
        EXPECT_TRUE(families.count(f.name)) << "no mutant of family " << f.name;
    // No two mutants are the same program.
    std::set<std::string> texts;
    for (const Mutant& m : mutants) EXPECT_TRUE(texts.insert(m.text).second) << m.description;
}

TEST(Mutants, TypicalMutationsAreAmongThem) {
    const std::vector<Mutant> mutants = generateMutants(kSample);
    auto has = [&](const std::string& text) {
        for (const Mutant& m : mutants)
            if (m.text.find(text) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(has("pow(c, 5.0) / 1.0"));            // PI removed
    EXPECT_TRUE(has("pow(c, 2.5)"));                  // a constant halved
    EXPECT_TRUE(has("float c = (1.0 - cosTheta);"));  // the clamp dropped
    EXPECT_TRUE(has("pow(5.0, c)"));                  // arguments swapped
    EXPECT_TRUE(has("(sum).xyz"));                    // normalize removed
    EXPECT_TRUE(has("i < 64u"));                      // the sample count fixed
    EXPECT_TRUE(has("return F0 + (1.0 - F0) * pow(c, 5.0) / PI + normalize(sum).xyz * sqrt(w);"));
    EXPECT_TRUE(has("float w = c > 0.5 ? -c : c;"));  // branches swapped
    EXPECT_TRUE(has("return x;"));                    // a square removed
    EXPECT_TRUE(has("F0 + (F0) * pow"));              // 1.0 - x turned into x
}

// Each semantic family makes mutants on exactly the steps whose reference solution has what it
// changes (a texture read, an integer parameter, a bit operation, a host-provided value), each
// with a witness, and every one of them compiles in the step's program.
TEST(SemanticMutants, EachFamilyAppliesWhereItFitsAndEveryMutantCompiles) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer(paths);
    // Read from the reference solutions: uEnvironment, uIrradianceMap, uPrefilterMap and
    // uBrdfLut are sampled in steps 17-19, 21 and the energy lab's (furnace, both
    // multiscatter steps, vndf_specular); sample counts and Hammersley's (i, n) are the integer
    // parameters; only hammersley reverses bits; NUM_LIGHTS and the light arrays are in
    // reflectance, textureSize(uEnvironment) in irradiance, uPrefilterMaxLod in split_sum and
    // multiscatter_ibl.
    const std::map<std::string, std::set<std::string>> expected = {
        {"radiance",
         {"mc_specular", "irradiance", "prefilter", "split_sum", "furnace", "multiscatter_ibl",
          "multiscatter_direct", "vndf_specular"}},
        {"count", {"hammersley", "mc_specular", "prefilter", "brdf_lut", "vndf_specular"}},
        {"bits", {"hammersley"}},
        {"host", {"reflectance", "irradiance", "split_sum", "multiscatter_ibl"}},
    };
    std::map<std::string, std::set<std::string>> made;
    int compiled = 0;
    for (const LoadedModule& m : modules.modules()) {
        const std::string solution = [&] {
            std::ifstream in(m.sourceDir / "solution.glsl");
            std::stringstream s;
            s << in.rdbuf();
            return s.str();
        }();
        const std::vector<Mutant> mutants = generateSemanticMutants({renderer, m, paths, solution});
        std::set<std::string> texts{solution};
        for (const Mutant& x : mutants) {
            // The helper family has no witness (its survivors are never equivalent) and
            // Reachable.NoFunctionAStepsFileCanSeeComputesTheStep grades all of its mutants.
            if (x.family == "helper") continue;
            made[x.family].insert(m.desc->id);
            EXPECT_TRUE(texts.insert(x.text).second) << x.description;
            EXPECT_FALSE(x.witness.empty()) << m.desc->id << ": " << x.description;
            EXPECT_FALSE(x.change.empty()) << x.description;
            test::TempDir dir;
            dir.write(m.desc->id + ".glsl", x.text);
            try {
                renderer.programs().get(renderer.viewRecipe(m, {dir.path, false}, false, 1));
                ++compiled;
            } catch (const std::exception& e) {
                ADD_FAILURE() << m.desc->id << ": " << x.description << " does not compile:\n"
                              << e.what();
            }
        }
    }
    for (const SemanticFamily& f : semanticFamilies())
        if (std::string(f.name) != "helper") {
            EXPECT_EQ(made[f.name], expected.at(f.name)) << "family " << f.name;
        }
    std::printf("[ measured ] %d semantic mutants compiled\n", compiled);
}

// The bits family on the other common Hammersley (LearnOpenGL's radical inverse by swaps of
// bit groups): every mask narrowed and every constant shift changed, one at a time.
TEST(SemanticMutants, FewerBitsNarrowsMasksAndChangesShifts) {
    const std::string shifts = R"(float radicalInverse(uint bits)
{
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    return float(bits) * 2.3283064365386963e-10;
}
)";
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer(paths);
    const std::vector<Mutant> mutants =
        semanticFamily("bits")->generate({renderer, modules.modules().front(), paths, shifts});
    std::set<std::string> changes;
    for (const Mutant& m : mutants) {
        changes.insert(m.change);
        EXPECT_FALSE(m.witness.byConstruction.empty()) << m.change;
    }
    EXPECT_EQ(changes, (std::set<std::string>{"`24u` for `16u`", "`0x5555u` for `0x55555555u`",
                                              "`0xAAAAu` for `0xAAAAAAAAu`", "`9u` for `1u`"}));
    EXPECT_EQ(mutants.size(), 6u);  // four shifts (16, 16, 1, 1), two masks
}

// A fixed third of the mutants of four steps of both labs (a deterministic subset), graded as
// submissions: every survivor must be proven equivalent on the teaching domain.
TEST(Mutants, NoMutantThatIsNotEquivalentSurvivesASubset) {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    MutationOptions o;
    o.modules = {"ndf", "fresnel", "reflectance", "hammersley", "brdf_lut"};
    o.every = 3;
    o.semantic = false;  // mechanical: the semantic ones are measured by `pbrlab mutants`
    const std::vector<ModuleMutation> result = runMutants(modules, paths, o);
    ASSERT_EQ(result.size(), o.modules.size());
    for (const ModuleMutation& m : result) {
        EXPECT_GT(m.count(MutantStatus::Killed), 0) << m.id;
        std::printf(
            "[ measured ] %s: %zu mutants, %d killed, %d equivalent survivors, %d do not "
            "compile, %.0f s\n",
            m.id.c_str(), m.mutants.size(), m.count(MutantStatus::Killed),
            m.count(MutantStatus::Survived) - m.nonEquivalentSurvivors(),
            m.count(MutantStatus::Stillborn), m.seconds);
        for (const MutantOutcome& x : m.mutants)
            if (x.status == MutantStatus::Survived)
                EXPECT_EQ(x.equivalence, "equivalent")
                    << m.id << ": " << x.mutant.description << "\n"
                    << x.evidence;
            else
                EXPECT_TRUE(x.status == MutantStatus::Killed || x.status == MutantStatus::Stillborn)
                    << m.id << ": " << x.mutant.description << " " << x.status;
    }
}
