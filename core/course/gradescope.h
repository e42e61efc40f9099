// Gradescope (docs/assignment.md): results.json graded by an assignment, and the autograder
// zip that installs a built pbrlab from its Debian package.
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

// The files of a ZIP archive (stored, not compressed: the .deb inside is compressed already).
struct ZipEntry {
    std::string name;
    std::string data;
    bool executable = false;
};
std::string zipArchive(const std::vector<ZipEntry>& entries);

struct AutograderOptions {
    std::filesystem::path assignment;  // the assignment file, copied as it is
    std::filesystem::path out;         // the folder of autograder.zip
    std::filesystem::path deb;         // pbrlab_<version>_<arch>.deb (cpack -G DEB)
};

// Writes OUT/autograder.zip: setup.sh, run_autograder, assignment.json and the .deb, after
// validating the assignment against these steps; without options.deb, findDebianPackage().
// Returns the zip's path.
std::filesystem::path writeAutograderBundle(AutograderOptions options,
                                            const ModuleRegistry& modules);

// `grade --assignment FILE` (empty: none): the assignment loaded and applied to the options.
std::optional<Assignment> gradeAssignment(const std::string& file, const ModuleRegistry& modules,
                                          GradeOptions& options);

// results.json: by the assignment when there is one, else 1 point per step (toGradescope).
nlohmann::json gradescopeResults(const GradeReport& report, const std::optional<Assignment>& a);

// The .deb to bundle when none is given: pbrlab_*.deb in the current folder or beside the
// executable (where `cpack -G DEB` in the build folder writes it). Throws naming where it
// looked.
std::filesystem::path findDebianPackage();

}  // namespace pbrlab
