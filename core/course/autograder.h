// The autograder: every module of a submission graded in its own child process (time and
// memory limits; a crash or an endless loop costs that module only), stepwise by default,
// through gradeStep (grading/grade_step.h), with feedback that names the mistake.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "grading/grade_step.h"
#include "grading/module_grade.h"
#include "render/renderer.h"
#include "shader/student_file.h"
#include "steps/plugin_host.h"

namespace pbrlab {

struct GradeOptions {
    std::filesystem::path submission;
    std::vector<std::string> modules;  // empty: all loaded modules
    bool cumulative = false;
    double timeoutSeconds = 60;  // per module, wall clock
    // The whole submission's wall clock (0: none): a step still grading when it runs out is
    // killed, one not started is not graded; both score 0 and say why (status "timeout"). So
    // that a grader with a time limit of its own (Gradescope's) still writes its results.
    double budgetSeconds = 0;
    std::size_t memoryLimitMb = 8192;  // per module, address space (llvmpipe reserves a lot)
    int jobs = 2;                      // modules graded at once (one child process each)
    std::filesystem::path html;        // folder for the HTML report and its images, or empty
    GradeSettings settings;            // what gradeStep checks (size, seed, feedback)
    // Told as each module's grade comes in (progress output).
    std::function<void(const struct ModuleGrade&)> progress;
    // Sets a grade's max_score and score (an assignment's points and partial credit,
    // assignment.h); empty: 1 point per step, all or nothing.
    std::function<void(struct ModuleGrade&)> scoring;
};

struct GradeReport {
    std::filesystem::path submission;
    std::vector<ModuleGrade> modules;
    double score = 0, maxScore = 0, seconds = 0;
};

// One step in this process (no fork): what a grade's child runs, and the GUI's badges.
ModuleGrade gradeModule(LabRenderer& renderer, const LoadedModule& module, const DataPaths& paths,
                        const GradeOptions& options);

// One module of one submission folder.
struct GradeJob {
    const LoadedModule* module = nullptr;
    std::filesystem::path submission;
};

// Each job in a child process (options.jobs at a time), costliest kinds of step first; the
// grades come back in the order of the jobs.
std::vector<ModuleGrade> gradeJobs(const std::vector<GradeJob>& jobs, const DataPaths& paths,
                                   const GradeOptions& options);

// Every step of the submission, each in a child process. Never throws for a bad submission:
// whatever is wrong with one file is that step's status and message.
GradeReport gradeSubmission(const ModuleRegistry& modules, const DataPaths& paths,
                            const GradeOptions& options);

// The processors this process may keep busy: those it may run on, fewer under a CPU quota
// (a container's cgroup, as Gradescope's: half a processor by default shows every processor of
// the host). The default number of grading processes, and of llvmpipe's threads in each under
// a quota.
int usableCpus();
// The rule, from cgroup v2's cpu.max line ("max 100000", "50000 100000"; empty: none) or else
// cgroup v1's quota and period (-1: none), and the processors it may run on: the quota rounded
// up, at least 1, at most the processors.
int cpusOfQuota(const std::string& cgroup2CpuMax, long cgroup1Quota, long cgroup1Period,
                int processors);

// Points as every report gives them (docs/assignment.md, "Rounding"): whole micro-points.
// A score is a whole number of millionths of a point, held as the double nearest that decimal
// (which JSON and the text reports print as the decimal); a sum of scores is the sum of those
// whole numbers, so that a total is exactly the sum of its parts in every report.
double addPoints(double a, double b);     // the exact sum of two rounded scores
std::string formatPoints(double points);  // "2.025", "3", "0.083333": no trailing zeros

nlohmann::json toJson(const GradeReport& report);
nlohmann::json toGradescope(const GradeReport& report);
void writeHtml(const GradeReport& report, const std::filesystem::path& folder);
// Temporary file in the same folder, then rename: a reader never sees half a report.
void writeFileAtomically(const std::filesystem::path& file, const std::string& text);
// A report as indented JSON text (any invalid UTF-8 left in it replaced).
std::string jsonText(const nlohmann::json& report);

}  // namespace pbrlab
