// Gradescope (docs/assignment.md): results.json graded by an assignment, and the autograder
// zip that carries the grader bundle.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "course/assignment.h"
#include "course/autograder.h"

namespace pbrlab {

// Gradescope's results.json: one test per category of each step's checks (one per step when
// the step is all-or-nothing), each with the assignment's visibility, its checks' metrics in
// extra_data and its feedback as markdown; the total is the sum of the tests' scores.
nlohmann::json toGradescope(const GradeReport& report, const Assignment& assignment);

// One file of a ZIP archive: `data`, or the contents of `file` when `data` is empty and `file`
// is not.
struct ZipEntry {
    std::string name;
    std::string data;
    std::filesystem::path file;
    bool executable = false;
};
// Writes the archive to `zip` (through a temporary file, then renamed), one entry at a time:
// each deflated (zlib, level 6), or stored where deflate would not make it smaller. The mode
// (0755 or 0644) is in each entry's external attributes, which unzip restores.
void writeZip(const std::filesystem::path& zip, const std::vector<ZipEntry>& entries);

// The grader bundle (scripts/grader-bundle.sh): a headless pbrlab with the step plugins, the
// data and every shared library it loads but glibc's, found relative to the executable; it
// runs on any x86-64 Linux with glibc >= 2.35. Its marker file, at its top.
inline constexpr const char* kGraderBundleMarker = "pbrlab-grader-bundle.txt";

struct AutograderOptions {
    std::filesystem::path assignment;  // the assignment file, copied as it is
    std::filesystem::path out;         // the folder of autograder.zip
    std::filesystem::path bundle;      // the grader bundle (empty: findGraderBundle())
    // The assignment's autograder timeout on Gradescope (its default: 10 minutes): grading
    // stops early enough to write results.json within it.
    double gradescopeTimeoutSeconds = 600;
};

// Writes OUT/autograder.zip: setup.sh, run_autograder, assignment.json and the grader bundle
// under pbrlab/, after validating the assignment against these steps and checking that the
// bundle has a plugin for each of its steps. Returns the zip's path.
std::filesystem::path writeAutograderBundle(AutograderOptions options,
                                            const ModuleRegistry& modules);

// The whole submission's time budget run_autograder grades within: Gradescope's timeout less
// what starting and writing the results may take.
double gradingBudgetSeconds(double gradescopeTimeoutSeconds);

// `grade --assignment FILE` (empty: none): the assignment loaded and applied to the options.
std::optional<Assignment> gradeAssignment(const std::string& file, const ModuleRegistry& modules,
                                          GradeOptions& options);

// results.json: by the assignment when there is one, else 1 point per step (toGradescope).
nlohmann::json gradescopeResults(const GradeReport& report, const std::optional<Assignment>& a);

// The grader bundle to zip when none is given: the one this pbrlab runs from (the bundle's own
// pbrlab), else grader-bundle/ beside the executable (where scripts/grader-bundle.sh writes it
// for a build). Throws saying how to make one.
std::filesystem::path findGraderBundle();

}  // namespace pbrlab
