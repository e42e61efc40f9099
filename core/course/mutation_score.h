// `pbrlab mutants`: the grader's mutation score. Every mutant of every reference solution is
// graded exactly as a submission is (gradeJobs: a child process each, gradeStep inside); a
// mutant that passes is a survivor, and each survivor is compared with the reference solution
// on a dense sample of the teaching domain: the same values there (within float rounding) is
// the measured proof that it is equivalent; anything else is a hole in the grader.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "grading/mutants_mechanical.h"
#include "grading/verdict.h"
#include "render/renderer.h"
#include "steps/plugin_host.h"

namespace pbrlab {

struct MutationOptions {
    std::vector<std::string> modules;  // empty: all
    // Which mutants: the mechanical ones (grading/mutants_mechanical.h), the semantic ones
    // (grading/mutants_semantic.h).
    bool mechanical = true, semantic = true;
    int every = 1;  // grade every n-th mutant of each kind only (a subset, for CI)
    int jobs = 2;
    bool feedback = false;  // grade fully and record the named mistake (slower)
    std::function<void(const std::string&)> progress;
};

// What the grader made of a mutant: failed it, passed it, or could not compile it, stopped it or
// saw it crash (both count as killed).
enum class MutantStatus { Killed, Survived, Stillborn, Timeout, Crashed };
template <>
struct VerdictNames<MutantStatus> {
    static constexpr std::string_view what = "mutant status";
    static constexpr std::array<std::string_view, 5> list = {"killed", "survived", "stillborn",
                                                             "timeout", "crashed"};
};

struct MutantOutcome {
    Mutant mutant;
    MutantStatus status = MutantStatus::Killed;
    std::string killedBy;  // the first failed check
    std::string mistake;   // the feedback's named mistake (with feedback)
    NamedBy namedBy = NamedBy::Nothing;
    // Survivors: "equivalent" (same values within rounding on the whole domain, and on a
    // semantic mutant's witness), or "differs" (a hole: what and where).
    std::string equivalence, evidence;
};

// One step's mutants of one kind.
struct ModuleMutation {
    std::string id;
    std::string kind;  // "mechanical" | "semantic"
    std::vector<MutantOutcome> mutants;
    double seconds = 0;
    int count(MutantStatus status) const;
    int nonEquivalentSurvivors() const;
};

std::vector<ModuleMutation> runMutants(const ModuleRegistry& modules, const DataPaths& paths,
                                       const MutationOptions& options);

nlohmann::json toJson(const std::vector<ModuleMutation>& result);

}  // namespace pbrlab
