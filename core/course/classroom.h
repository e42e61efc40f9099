// The GitHub Classroom workflow (`pbrlab classroom`): one points row per step through GitHub
// Classroom's command grader, then its reporter. It runs in the student's repository, so its
// points are feedback the student controls, not a grade (docs/grading.md). And the workflow that
// publishes the course's browser site to GitHub Pages from the template (`--pages`).
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
    // How the job gets pbrlab (docs/assignment.md, "GitHub Classroom"): the grader bundle
    // downloaded from bundleUrl (a .tar.gz with one top folder holding bin/pbrlab) when one is
    // given; otherwise built from pbrlabRepository (OWNER/NAME on GitHub) at pbrlabRef (a branch
    // or tag; "": its default branch) in a debian:bookworm container, the Debian package cached.
    std::string bundleUrl;
    std::string pbrlabRepository;
    std::string pbrlabRef;
    int timeoutMinutes = 10;  // per step (the grader's limit)
};

// Where the Pages workflow reads the course's assignment file in the template repository.
inline constexpr const char* kPagesAssignmentPath = ".github/pbrlab/assignment.json";

// The steps and points of an assignment file: its "steps" (a list of ids, or "all") and
// "points" ({"default": n, "<id>": n}); other fields are left to the assignment's own reader.
// Throws naming the file and the field.
std::vector<ClassroomStep> assignmentSteps(const ModuleRegistry& modules,
                                           const std::filesystem::path& assignment);

// `ids` (comma-separated, empty: all steps) at `points` each; throws for an unknown id.
std::vector<ClassroomStep> listedSteps(const ModuleRegistry& modules, const std::string& ids,
                                       int points);

// .github/workflows/classroom.yml's text. Throws when neither a bundle URL nor a repository is
// given (there is no sensible default: the workflow would fetch something that does not exist)
// or when one is not of its form (https URL; GitHub's OWNER/NAME; a ref name).
std::string classroomWorkflow(const ClassroomOptions& options);

// .github/workflows/pages.yml's text: in the template repository only (not in the students'
// copies), the course's site built from pbrlabRepository at pbrlabRef for the assignment file at
// kPagesAssignmentPath (scripts/build-web.sh --assignment, by today's date), deployed to GitHub
// Pages. Throws as classroomWorkflow does; the repository is required (the site is built from
// source, whatever the classroom workflow installs).
std::string pagesWorkflow(const ClassroomOptions& options);

}  // namespace pbrlab
