// What grading one step means (docs/grading.md): every check that the module's declarations
// and the contract call for, run on the student's function (or the reference solution), each
// with what it measured. The grader's child processes, `pbrlab check`, the GUI's badges and
// `pbrlab mutants` all grade through gradeStep, so they cannot disagree.
#pragma once

#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "grading/error_patterns.h"
#include "grading/verdict.h"
#include "render/evaluate.h"

namespace pbrlab {

struct GradeSettings {
    int size = 96;           // image side of the scene checks
    std::uint64_t seed = 1;  // of the random domain points (instructors may choose another)
    int domainPoints = 2048;
    bool feedback = true;  // on failure, name the mistake (costs a few more renders)
    // What the feedback may compare with besides the patterns: the step's typical mistakes
    // (labs/<id>/mistakes) and the mutants of its reference solution. Off: patterns alone
    // (how the patterns' reach is measured).
    bool typicalMistakes = true, mutantCatalogue = true;
    bool robustness = true;  // the extreme-input sweep (reported, not deducted)
    // Stop at the first check that fails (the verdict is the same; what mutation testing
    // needs, fast).
    bool stopAtFirstFailure = false;
    // Told as each check starts, so that a crash can be reported with where it happened.
    std::function<void(const std::string&)> stage;
    // The bands of the checks' CPU references, kept from grade to grade where one program
    // grades many files (the page's grader): the next file's checks take them from here.
    BandCache* bands = nullptr;
    // The environment with a sun the environment-reading steps are also graded on (empty: the
    // step's, EstimatorSpec::sunEnvironment): an instructor's own HDR, a real sky.
    std::string sunEnvironment;
};

struct CheckReport {
    std::string name;  // "probe", "random inputs", "samples = 7", "integral of D ..."
    CheckKind kind = CheckKind::Values;
    std::optional<CheckCategory> category;  // set where each check is made
    bool passed = true;
    bool deducted = true;  // robustness and quality are reported, not deducted
    // A values check passed that the step's stub (the kit's starter code) fails: the function
    // computes something. Asked until one check of the step is found; what opens the step's
    // points with partial credit (assignment.h).
    bool showsWork = false;
    std::string detail;  // one line: what was measured and the rule
    // values: points compared and where the band was left worst
    int points = 0, outside = 0, nan = 0, inf = 0, negative = 0;
    double worstExcess = 0;  // distance outside the band at the worst point, in tolerances
    std::string worstAt;     // the inputs there
    glm::dvec3 worstValue{0}, worstExpected{0}, worstLo{0}, worstHi{0};
    // invariants and convergence
    double measured = 0;
    std::string expected;
};

struct StepResult {
    bool passed = false;
    std::vector<CheckReport> checks;
    std::string message;  // why it failed (the first failed check, the named mistake)
    std::string mistake;  // the mistake recognised from the shape of the error, or empty
    NamedBy namedBy = NamedBy::Nothing;
    // The mistake as a class report counts it: a typical mistake's or a mutant family's name,
    // else the pattern without this student's figures (withoutFigures).
    std::string mistakeGroup;
    // For the instructor only: the mutant's change, quoted from the reference solution (never
    // shown to the student, who would otherwise read the solution off the feedback).
    std::string instructorNote;
    double seconds = 0;
    // Every value the host gave the step's program in its values checks, by the name the
    // program reads it by (NUM_LIGHTS, uLightPositions, uPrefilterMaxLod, uBrdfLut's size,
    // u_<parameter>, ...): what shows that each is graded at more than one value.
    std::map<std::string, std::set<std::string>> hostValues;
};

// Throws ShaderError when the student's file does not compile, pbrlab::Error for refused
// files; everything else is a result.
StepResult gradeStep(LabRenderer& renderer, const LoadedModule& module, const DataPaths& paths,
                     const StudentSource& source, const GradeSettings& settings);

// The random points of the module's domain the grader uses (seeded), empty when it has none.
std::vector<Surface> domainSurfaces(const ModuleDesc& module, std::uint64_t seed, int count);

// The values a parameter is graded at besides its default ("samples=7"): every parameter the
// student's function receives is exercised; counts up to 1024 and, where the parameter allows,
// 4096 and 65536.
std::vector<std::string> exercisedValues(const ParamDecl& p);
// Counts above this are graded on kFewPoints random points of the domain only (the probe, the
// scenes and 2048 points would cost 64 times the work at 65536).
constexpr int kFewPointsAbove = 1024, kFewPoints = 64;

nlohmann::json toJson(const CheckReport& check);

}  // namespace pbrlab
