// The GitHub Classroom workflow (`pbrlab classroom`): one points row per step through GitHub
// Classroom's command grader, then its reporter. It runs in the student's repository, so its
// points are feedback the student controls, not a grade (docs/grading.md).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "steps/plugin_host.h"

namespace pbrlab {

struct ClassroomStep {
    std::string id, title;
    int points = 1;  // whole points: the command grader reads max-score as an integer
};

struct ClassroomOptions {
    std::vector<ClassroomStep> steps;
    std::string pbrlabRepository;  // OWNER/NAME on GitHub, where the workflow builds pbrlab from
    int timeoutMinutes = 10;       // per step (the grader's limit)
};

// The steps and points of an assignment file: its "steps" (a list of ids, or "all") and
// "points" ({"default": n, "<id>": n}); other fields are left to the assignment's own reader.
// Throws naming the file and the field.
std::vector<ClassroomStep> assignmentSteps(const ModuleRegistry& modules,
                                           const std::filesystem::path& assignment);

// `ids` (comma-separated, empty: all steps) at `points` each; throws for an unknown id.
std::vector<ClassroomStep> listedSteps(const ModuleRegistry& modules, const std::string& ids,
                                       int points);

// .github/workflows/classroom.yml's text. Throws when pbrlabRepository is missing (there is no
// sensible default: the workflow would clone a repository that does not exist) or is not of
// GitHub's OWNER/NAME form.
std::string classroomWorkflow(const ClassroomOptions& options);

}  // namespace pbrlab
