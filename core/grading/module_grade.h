// One step graded in this process: gradeStep's result as a grade (status, message, every
// check), the form every report, `pbrlab check --json`, the GUI's badges and the page's grader
// (web/, in a Web Worker) read. The autograder runs it in a child per step (course/autograder.h).
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "grading/grade_step.h"

namespace pbrlab {

struct ModuleGrade {
    std::string id, title;
    GradeStatus status = GradeStatus::Missing;
    double score = 0, maxScore = 1;
    std::string message;
    std::string mistake;  // the mistake named from the shape of the error, when recognised
    NamedBy namedBy = NamedBy::Nothing;
    std::string mistakeGroup;                         // see StepResult: what a class report counts
    std::string instructorNote;                       // see StepResult: not for the student's eyes
    nlohmann::json checks = nlohmann::json::array();  // every check with what it measured
    double seconds = 0;
};

// gradeStep on the module with the student's `source`: status passed | failed |
// compile_error, the message (with hints for a compile error, valid UTF-8), every check.
// `afterGrading` runs when gradeStep returned, and what it throws fails the grade too.
ModuleGrade gradeModuleHere(LabRenderer& renderer, const LoadedModule& module,
                            const DataPaths& paths, const StudentSource& source,
                            const GradeSettings& settings,
                            const std::function<void()>& afterGrading = {});

// A grade as the reports write it ("modules" of `grade --json`, `check --json`), and read
// back (a grading child's answer, the page's reports). Only the status is required (the page
// writes its own timeouts as id, status and message); it throws on a report without one, or
// with a status or named_by that is not a name of grading/verdict.h.
nlohmann::json gradeJson(const ModuleGrade& grade);
ModuleGrade gradeFromJson(const nlohmann::json& report);

// Points as every report gives them (docs/assignment.md, "Rounding"): whole micro-points.
std::int64_t toMicroPoints(double points);  // the nearest whole number of micro-points
double fromMicroPoints(std::int64_t micro);
double roundPoints(double points);  // to the nearest micro-point

// `text` with every byte sequence that is not UTF-8 replaced by U+FFFD, so that a message
// quoting a student's file can always be written as JSON.
std::string validUtf8(const std::string& text);

}  // namespace pbrlab
