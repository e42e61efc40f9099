// A class's submissions graded at once (`grade --batch`): several submissions in parallel,
// resumable (an unchanged submission is not graded again), one deterministic shard of N for
// grading on several machines, and the shards' outputs merged (`grade --merge`).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "course/assignment.h"
#include "course/autograder.h"

namespace pbrlab {

struct BatchOptions {
    std::filesystem::path batch;  // one sub-folder per submission
    std::filesystem::path out;    // <out>/<student>/ gets the reports; <out>/class.* the class
    // What each submission is graded with; `grade.jobs` is the number of grading processes
    // for the whole batch (split between the submissions graded at once).
    GradeOptions grade;
    int shard = 0, shards = 1;  // grade only the submissions of shard `shard` of `shards`
    // Anything else that decides the grades and must invalidate earlier ones when it changes
    // (the assignment file's text).
    std::string configuration;
    // What results.json is scored by (gradescopeResults): the assignment, when there is one.
    std::optional<Assignment> assignment;
    bool progress = true;  // a progress bar on stderr
};

struct BatchSummary {
    size_t students = 0;  // in this shard
    size_t graded = 0, skipped = 0, errors = 0;
    double seconds = 0;
};

// "I/N" (0 <= I < N) -> {I, N}; throws naming the text otherwise.
std::pair<int, int> parseShard(const std::string& text);

// Which of `shards` shards a submission belongs to: from its folder's name alone, so that it
// stays in its shard when other submissions come or go.
int shardOf(const std::string& student, int shards);

// Grades the shard's submissions that have no report for their current files yet (each graded
// submission's folder keeps the digest of what it was graded from), then writes class.csv,
// class.html, summary.csv and shard.json into `out` for all of the shard's submissions. A
// submission that cannot be graded is listed with why; it stops nothing.
BatchSummary gradeBatch(const ModuleRegistry& modules, const DataPaths& paths,
                        const BatchOptions& options);

// One class report in `out` from the outputs of `grade --batch --shard I/N` runs; throws when
// they overlap, miss a shard, or were graded by different builds or settings.
void mergeBatches(const std::vector<std::filesystem::path>& shardOutputs,
                  const std::filesystem::path& out);

}  // namespace pbrlab
