// What a class does at each step: one row per student and step (class.csv), and a page
// (class.html) with each step's pass rate, its most common named mistakes and the histogram of
// total scores. Written by `grade --batch` and by `grade --merge` from shard outputs.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "grading/verdict.h"

namespace pbrlab {

// One student's grade at one step, as class.csv holds it.
struct ClassRow {
    std::string student, step;
    GradeStatus status = GradeStatus::Missing;
    double score = 0, maxScore = 0;
    std::string mistake;  // the named mistake, or empty
    NamedBy namedBy = NamedBy::Nothing;
    std::string group;  // the mistake without this student's figures: what the chart counts
};

// One submission's line of summary.csv; `error` says why it could not be graded at all.
struct StudentTotal {
    std::string student;
    double score = 0, maxScore = 0, seconds = 0;
    std::string error;
};

// The rows of one student's report.json (toJson of a GradeReport), in the report's step order.
std::vector<ClassRow> classRows(const std::string& student, const nlohmann::json& report);

// CSV text (RFC 4180 quoting) and back; reading throws naming the file and the line.
std::string classCsv(const std::vector<ClassRow>& rows);
std::vector<ClassRow> readClassCsv(const std::filesystem::path& file);
std::string summaryCsv(const std::vector<StudentTotal>& totals);
std::vector<StudentTotal> readSummaryCsv(const std::filesystem::path& file);

// The page: per step the pass rate and the most common named mistakes (bar charts), the
// histogram of total scores, and the submissions that could not be graded. Self-contained
// (inline SVG and CSS, nothing fetched), so it opens offline.
std::string classHtml(const std::vector<ClassRow>& rows, const std::vector<StudentTotal>& totals,
                      const std::string& title);

// class.csv, class.html and summary.csv in `folder`; rows sorted by student (steps keep their
// order), totals by student.
void writeClassReport(std::vector<ClassRow> rows, std::vector<StudentTotal> totals,
                      const std::filesystem::path& folder, const std::string& title);

}  // namespace pbrlab
