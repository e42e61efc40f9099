// The autograder: every module of a submission graded in its own child process (time and
// memory limits; a crash or an endless loop costs that module only), stepwise by default,
// with feedback that names the mistake when the output looks like a known one.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "plugins.h"
#include "renderer.h"

namespace pbrlab {

struct GradeOptions {
    std::filesystem::path submission;
    std::vector<std::string> modules;  // empty: all loaded modules
    bool cumulative = false;
    double timeoutSeconds = 60;        // per module, wall clock
    std::size_t memoryLimitMb = 8192;  // per module, address space (llvmpipe reserves a lot)
    std::filesystem::path html;        // folder for the HTML report and its images, or empty
    int size = 96;                     // image side of the graded renders
};

struct ModuleGrade {
    std::string id, title;
    // passed | failed | compile_error | timeout | missing | crashed
    std::string status = "missing";
    double score = 0, maxScore = 1;
    std::string message;
    nlohmann::json metrics = nlohmann::json::object();
};

struct GradeReport {
    std::filesystem::path submission;
    std::vector<ModuleGrade> modules;
    double score = 0, maxScore = 0, seconds = 0;
};

// Rejects what a grader must not read: a file over 10 MB, NUL bytes, a symlink leaving the
// folder. Empty when the file may be graded, else why not.
std::string screenStudentFile(const std::filesystem::path& file,
                              const std::filesystem::path& submission);

GradeReport gradeSubmission(const ModuleRegistry& modules, const DataPaths& paths,
                            const GradeOptions& options);

nlohmann::json toJson(const GradeReport& report);
nlohmann::json toGradescope(const GradeReport& report);
void writeHtml(const GradeReport& report, const std::filesystem::path& folder);
// Temporary file in the same folder, then rename: a reader never sees half a report.
void writeFileAtomically(const std::filesystem::path& file, const std::string& text);

}  // namespace pbrlab
