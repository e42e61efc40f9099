// An instructor's assignment file (docs/assignment.md): which steps, points per step, weights
// of the check categories (partial credit), what students see on Gradescope and when, the
// release schedule of the kit, the time limit. Read by `grade`, `kit` and `autograder`
// with --assignment.
#pragma once

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "grading/verdict.h"

namespace pbrlab {

struct ModuleGrade;
struct GradeOptions;
struct KitOptions;
class ModuleRegistry;

struct Assignment {
    std::filesystem::path file;
    std::string name;
    std::vector<std::string> steps;           // in the order of the steps
    std::map<std::string, double> points;     // every step of `steps`
    std::map<CheckCategory, double> weights;  // every category
    bool partialCredit = true;
    // Gradescope's visibility by "default", step id, category or "step.category".
    std::map<std::string, std::string> visibility;
    struct Release {
        std::string date;     // YYYY-MM-DD
        std::string through;  // a step id
    };
    std::vector<Release> release;    // the kit's starter files: steps up to `through` by `date`
    std::vector<Release> solutions;  // the kit's reference solutions: up to `through` by `date`
    std::string due;                 // as written (ISO 8601), shown in the kit's README
    double timeLimitSeconds = 60;    // per step
    bool cumulative = false;

    // The most specific of step.category, step, category, default.
    std::string visibilityOf(const std::string& step, const std::string& category = "") const;
};

// The file read and validated against the steps that exist (in their order). Throws
// pbrlab::Error "FILE: JSON.PATH: what is wrong" for the first problem found.
Assignment loadAssignment(const std::filesystem::path& file,
                          const std::vector<std::string>& knownSteps);
Assignment parseAssignment(const nlohmann::json& j, const std::string& fileName,
                           const std::vector<std::string>& knownSteps);

// One category of one step's checks, and the points it is worth.
struct CategoryScore {
    CheckCategory category = CheckCategory::Contract;
    int checks = 0, passed = 0;
    int earning = 0;  // of the passed checks, those that earn (all, or none: categoryScores)
    double score = 0, maxScore = 0;
};

// A grade's points by category (docs/assignment.md): max = points * w_c / sum(w) over the
// categories the step's checks have (weight > 0), score = max * earning / checks, in whole
// micro-points (course/autograder.h: the maxima add up to the points exactly). The passed checks
// earn once one of them shows work (a values check that the kit's stub fails,
// CheckReport::showsWork); until then none does: a stub earns nothing. Empty when the grade is
// all-or-nothing: no partial credit, no graded checks (compile error, timeout, missing, crashed), a
// failed contract check, or no category with weight.
std::vector<CategoryScore> categoryScores(const ModuleGrade& grade, const Assignment& a);

// Sets the grade's max_score (the step's points) and score (the sum of categoryScores, or
// all-or-nothing), rounded to the micro-point.
void scoreGrade(ModuleGrade& grade, const Assignment& a);

// The steps whose starter files (`schedule` = release) or solutions (= solutions) are out by
// `date` (YYYY-MM-DD): the `through` of the last entry dated on or before it; empty when none.
std::string releasedThrough(const std::vector<Assignment::Release>& schedule,
                            const std::string& date);

// Today's date in UTC as YYYY-MM-DD.
std::string todayUtc();

// The ids of the loaded steps, in their order (what an assignment may name).
std::vector<std::string> stepIds(const ModuleRegistry& modules);

// `grade --assignment`: its steps, time limit, cumulative setting and scoring.
void applyAssignment(const Assignment& a, GradeOptions& options);

// `kit --assignment`: the steps whose starter files are out by `date` (all of the
// assignment's with --with-solutions), the solutions out by then, the due date. Throws when
// nothing is out yet.
void applyAssignment(const Assignment& a, const std::string& date, KitOptions& options);

}  // namespace pbrlab
