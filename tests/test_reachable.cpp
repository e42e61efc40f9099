// Nothing reachable computes the step (docs/grading.md): per step, every function and macro of
// its program that a student's file can see, parsed from the expanded program source, is one
// the contract allows, and none of the functions computes the step: a file that returns one
// of them, called with the step's arguments, fails grading (helperCallMutants).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>

#include "gl/context.h"
#include "grading/grade_step.h"
#include "grading/mutants_helper.h"
#include "steps/contract.h"
#include "test_support.h"
#include "util/fs.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

struct Lab {
    std::unique_ptr<GlContext> context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};
};

bool isBuiltIn(const std::string& type) {
    static const std::regex builtIn(R"((void|float|int|uint|bool|[iub]?vec[234]|mat[234]))");
    return std::regex_match(type, builtIn);
}

bool endsWith(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// Why the program of `module` refuses a student's file that declares `f` (above the reference
// solution, which then stands in the student's place), or "" when it compiles that far.
std::string refusalOf(Lab& lab, const LoadedModule& module, const VisibleFunction& f) {
    test::TempDir kit;
    kit.write(module.desc->id + ".glsl",
              f.signature() + ";\n" + readFile(module.sourceDir / "solution.glsl"));
    try {
        const ProgramRecipe r = lab.renderer.viewRecipe(module, {kit.path}, true, 1);
        lab.renderer.programs().preprocessor().expand(r.fragment, r.defines);
    } catch (const ShaderError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

// What a student's file of each step can name: the contract functions of its own and earlier
// steps, the helpers those steps introduce (fresnelSchlickRoughness from split_sum on),
// common.glsl's utilities, and the macros NUM_LIGHTS (contract) and PBRLAB_IBL / PBRLAB_PROBE
// (the host's flags: readable, never redefined: Preprocessor.*). Every other function of the
// program is refused when named (a private helper of a reference solution, the host's pbrlab_
// code after the student's part) or cannot be named at all (types declared after the
// student's part; main, whose call recurses).
TEST(Reachable, EveryNameAStepsFileCanSeeIsOneTheContractAllows) {
    Lab lab;
    // PBRLAB_LIGHT_SLOTS: the light arrays' length; PBRLAB_LOOP_GUARD: the program bounds the
    // student's loops (loop_guard.h); the built-ins' names route a student's calls to their
    // defined versions (definedBuiltins).
    std::set<std::string> allowedMacros = {"NUM_LIGHTS", "PBRLAB_IBL", "PBRLAB_PROBE",
                                           "PBRLAB_LIGHT_SLOTS", kLoopGuardMacro};
    std::set<std::string> definedVersions;
    for (const auto& [builtin, definition] : definedBuiltins()) {
        allowedMacros.insert(builtin);
        definedVersions.insert(definition);
    }
    for (const LoadedModule& m : lab.modules.modules()) {
        SCOPED_TRACE(m.desc->id);
        const ContractStep& own = *findContractStep(m.desc->id);
        std::set<std::string> contract, later;  // later: also the steps it hides
        for (const ContractStep& s : contractSteps()) {
            const bool hidden =
                std::find(own.hides.begin(), own.hides.end(), s.id) != own.hides.end();
            (s.step <= own.step && !hidden ? contract : later).insert(functionName(s.function));
        }
        for (const ContractHelper& h : contractHelpers())
            (findContractStep(h.introducedBy)->step <= own.step ? contract : later)
                .insert(functionName(h.function));

        const VisibleNames names = namesVisibleToStudent(lab.renderer, m);
        std::set<std::string> seenContract;
        std::vector<std::string> utilities, refused, unnameable;
        for (const VisibleFunction& f : names.functions) {
            EXPECT_FALSE(later.count(f.name)) << f.name << " of a later step is in the program";
            // A prototype needs every type of the signature declared before the student's part.
            const bool declarable =
                !f.afterStudent ||
                (isBuiltIn(f.returnType) &&
                 std::all_of(f.parameterTypes.begin(), f.parameterTypes.end(), isBuiltIn));
            if (contract.count(f.name) && !f.afterStudent) {
                seenContract.insert(f.name);
            } else if (!f.afterStudent && (endsWith(f.source, "shaders/common.glsl") ||
                                           definedVersions.count(f.name))) {
                utilities.push_back(f.name);  // they compute no step: the test below
            } else if (!declarable || f.name == "main") {
                unnameable.push_back(f.name);
            } else {
                // A private helper of a reference solution, or the host's code after the
                // student's part: naming it is refused, at the student's line.
                const std::string why = refusalOf(lab, m, f);
                EXPECT_NE(why.find(f.name + " is private to"), std::string::npos)
                    << f.signature() << " (" << f.source << ") can be named:\n"
                    << why;
                EXPECT_NE(why.find(m.desc->id + ".glsl:1: error:"), std::string::npos) << why;
                refused.push_back(f.name);
            }
        }
        EXPECT_EQ(seenContract, contract) << "every contract function it may call is declared";
        EXPECT_TRUE(std::includes(allowedMacros.begin(), allowedMacros.end(), names.macros.begin(),
                                  names.macros.end()))
            << testing::PrintToString(names.macros);
        auto list = [](const std::vector<std::string>& v) {
            std::string s;
            for (const std::string& x : v) s += (s.empty() ? "" : " ") + x;
            return s.empty() ? "-" : s;
        };
        std::string macros;
        for (const std::string& x : names.macros) macros += x + " ";
        std::cout << own.step << " " << own.id << ": " << seenContract.size()
                  << " contract functions; utilities: " << list(utilities)
                  << "; refused: " << list(refused) << "; not nameable: " << list(unnameable)
                  << "; macros: " << macros << "\n";
    }
}

// What the screening costs a grade: the largest program (split_sum's) expanded with the
// reference solution as the student's file (screened) and without a student's file, the
// fastest of 20 expansions each (the least disturbed by other processes); the difference is
// the screening. Measured 0.1 to 1.8 ms (mean of 20, five runs, the machine shared with four
// other builds); the bound, 5 ms, is what the cheapest compile of this program takes (from
// Mesa's disk cache: 3 to 5 ms, `pbrlab render split_sum --stats`; 10 to 20 ms without), so
// the screening never costs more than a compile it precedes.
TEST(Reachable, TheScreeningCostsLittleNextToACompile) {
    Lab lab;
    const LoadedModule* splitSum = nullptr;
    for (const LoadedModule& m : lab.modules.modules())
        if (m.desc->id == "split_sum") splitSum = &m;
    ASSERT_NE(splitSum, nullptr);
    test::TempDir kit;
    kit.write("split_sum.glsl", readFile(splitSum->sourceDir / "solution.glsl"));
    auto fastestExpansion = [&](const StudentSource& source) {
        const ProgramRecipe r = lab.renderer.viewRecipe(*splitSum, source, true, 1);
        double fastest = 1e30;
        for (int i = 0; i < 20; ++i) {
            const auto start = std::chrono::steady_clock::now();
            lab.renderer.programs().preprocessor().expand(r.fragment, r.defines);
            fastest = std::min(fastest, std::chrono::duration<double, std::milli>(
                                            std::chrono::steady_clock::now() - start)
                                            .count());
        }
        return fastest;
    };
    const double screened = fastestExpansion({kit.path}), reference = fastestExpansion({});
    std::cout << "split_sum's program expanded: " << screened << " ms with a student's file, "
              << reference << " ms without (fastest of 20)\n";
    EXPECT_LT(screened - reference, 5.0);
}

// No function a step's file can see computes the step: each helper mutant (a file returning
// one of them called with the step's own arguments) fails grading, by a refusal, a compile
// error or a failed check.
TEST(Reachable, NoFunctionAStepsFileCanSeeComputesTheStep) {
    Lab lab;
    GradeSettings settings;
    settings.stopAtFirstFailure = true;
    settings.feedback = false;
    settings.robustness = false;
    int total = 0;
    for (const LoadedModule& m : lab.modules.modules()) {
        SCOPED_TRACE(m.desc->id);
        const auto start = std::chrono::steady_clock::now();
        int refused = 0, compileErrors = 0, failedChecks = 0;
        for (const Mutant& mutant : helperCallMutants(lab.renderer, m)) {
            test::TempDir kit;
            kit.write(m.desc->id + ".glsl", mutant.text);
            try {
                const StepResult r = gradeStep(lab.renderer, m, lab.paths, {kit.path}, settings);
                EXPECT_FALSE(r.passed) << "computes the step: " << mutant.description;
                ++failedChecks;
            } catch (const ShaderError& e) {
                ++(std::string(e.what()).find("is private to") != std::string::npos
                       ? refused
                       : compileErrors);
            }
            ++total;
        }
        std::cout << m.desc->id << ": " << refused + compileErrors + failedChecks
                  << " helper mutants: " << refused << " refused, " << compileErrors
                  << " compile errors, " << failedChecks << " failed a check; "
                  << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                  << " s\n";
    }
    EXPECT_GT(total, 21);  // the generator made mutants at all
}
