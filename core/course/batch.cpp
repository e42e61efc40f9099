#include "course/batch.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <set>

#include "course/class_report.h"
#include "course/gradescope.h"
#include "util/digest.h"
#include "util/error.h"
#include "util/fs.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

namespace {

// Every file under `folder` (names relative to it, contents; links by their target), in name
// order. Empty when something cannot be read: then the submission is simply graded again.
std::string folderDigest(const fs::path& folder) {
    try {
        std::vector<fs::path> files;
        for (auto it = fs::recursive_directory_iterator(folder); it != fs::end(it); ++it)
            if (!it->is_directory() || it->is_symlink()) files.push_back(it->path());
        std::sort(files.begin(), files.end());
        Digest d;
        for (const fs::path& file : files) {
            d.add(fs::relative(file, folder).generic_string());
            if (fs::is_symlink(fs::symlink_status(file))) {
                d.add("link " + fs::read_symlink(file).string());
            } else if (fs::is_regular_file(file)) {
                // The grader refuses files over 10 MB; size and time stand for huge ones.
                const auto size = fs::file_size(file);
                if (size > (64u << 20))
                    d.add("large " + std::to_string(size) + " " +
                          std::to_string(fs::last_write_time(file).time_since_epoch().count()));
                else
                    d.add(readFile(file));
            }
        }
        return d.hex();
    } catch (const std::exception&) {
        return "";
    }
}

// What decides a grade besides the submission: the code (the program's and the steps'
// build IDs), the steps' folders (solutions, scenes), the shaders, the settings and the
// assignment. Empty when a build ID is missing: then nothing is skipped.
std::string configurationDigest(const ModuleRegistry& modules, const DataPaths& paths,
                                const BatchOptions& o) {
    std::vector<std::string> libraries{""};
    Digest d;
    for (const auto& m : modules.modules()) {
        const auto& only = o.grade.modules;
        if (!only.empty() && std::find(only.begin(), only.end(), m.desc->id) == only.end())
            continue;
        libraries.push_back(m.library.filename().string());
        d.add(m.desc->id);
        d.add(folderDigest(m.sourceDir));
    }
    const std::string code = buildIds(libraries);
    if (code.empty()) return "";
    d.add(code);
    d.add(folderDigest(paths.shaders()));
    d.add(o.grade.cumulative);
    d.add(o.grade.timeoutSeconds);
    d.add(o.grade.memoryLimitMb);
    const GradeSettings& s = o.grade.settings;
    d.add(s.size);
    d.add(s.seed);
    d.add(s.domainPoints);
    d.add(s.feedback);
    d.add(s.typicalMistakes);
    d.add(s.mutantCatalogue);
    d.add(s.robustness);
    d.add(s.stopAtFirstFailure);
    d.add(o.configuration);
    // Points, weights and time limit change grades: a changed assignment regrades everyone.
    if (o.assignment) d.add(readFile(o.assignment->file));
    return d.hex();
}

std::string clock(double seconds) {
    if (!std::isfinite(seconds)) return "?";
    const long s = std::lround(seconds);
    char text[32];
    std::snprintf(text, sizeof text, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
    return text;
}

// [#########.........] 12/50  3 unchanged  0.41/s  ETA 0:01:32
void drawProgress(size_t done, size_t total, size_t skipped, size_t graded, double seconds,
                  bool last) {
    const int width = 30;
    const int filled = int(double(width) * double(done) / double(std::max<size_t>(total, 1)));
    const double rate = seconds > 0 ? double(graded) / seconds : 0;
    const size_t left = total - done;
    std::fprintf(stderr, "\r[%s%s] %zu/%zu", std::string(size_t(filled), '#').c_str(),
                 std::string(size_t(width - filled), '.').c_str(), done, total);
    if (skipped) std::fprintf(stderr, "  %zu unchanged", skipped);
    if (graded) std::fprintf(stderr, "  %.2f/s", rate);
    if (last)
        std::fprintf(stderr, "  done in %s\n", clock(seconds).c_str());
    else
        std::fprintf(stderr, "  ETA %s   ",
                     graded ? clock(double(left) / rate).c_str() : std::string("?").c_str());
    std::fflush(stderr);
}

// One submission graded in a child process that writes its reports, then the digest; a
// crash there costs that submission only.
pid_t startWorker(const ModuleRegistry& modules, const DataPaths& paths, const GradeOptions& o,
                  const std::optional<Assignment>& assignment, const fs::path& submission,
                  const fs::path& out, const std::string& digest) {
    std::fflush(nullptr);
    std::cout.flush();
    const pid_t pid = fork();
    if (pid < 0) throw Error("grade --batch: fork failed: " + std::string(std::strerror(errno)));
    if (pid > 0) return pid;
    int code = 0;
    try {
        GradeOptions each = o;
        each.submission = fs::canonical(submission);
        each.html = out / "html";
        each.progress = nullptr;
        GradeReport report = gradeSubmission(modules, paths, each);
        writeFileAtomically(out / "report.json", jsonText(toJson(report)));
        writeFileAtomically(out / "results.json", jsonText(gradescopeResults(report, assignment)));
        writeHtml(report, each.html);
        if (!digest.empty()) writeFileAtomically(out / "digest.txt", digest + "\n");
    } catch (const std::exception& e) {
        try {
            writeFileAtomically(out / "error.txt", validUtf8(e.what()) + "\n");
        } catch (...) {
        }
        code = 1;
    }
    std::fflush(nullptr);
    _exit(code);
}

std::string trimmed(std::string text) {
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
}

// Seconds since `start`, for the progress line and the summary.
double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The shard's submissions in name order, with each one's total (its error, once graded), the
// digest its reports will carry (empty: none) and which of them are to be graded.
struct Submissions {
    std::vector<fs::path> folders;
    std::vector<StudentTotal> totals;
    std::vector<std::string> digests;
    std::vector<size_t> todo;
};

// The folders in the batch that belong to this shard, in name order.
std::vector<fs::path> shardFolders(const BatchOptions& o) {
    std::vector<fs::path> students;
    for (const auto& e : fs::directory_iterator(o.batch)) {
        std::error_code ec;
        if (e.is_directory(ec) && shardOf(e.path().filename().string(), o.shards) == o.shard)
            students.push_back(e.path());
    }
    std::sort(students.begin(), students.end());
    return students;
}

// Which submissions to grade: those without reports whose digest matches the submission's
// files and the `configuration` now (the others are counted as skipped in `summary`).
Submissions submissionsToGrade(std::vector<fs::path> students, const BatchOptions& o,
                               const std::string& configuration, BatchSummary& summary) {
    Submissions s{std::move(students), {}, {}, {}};
    s.totals.resize(s.folders.size());
    s.digests.resize(s.folders.size());
    for (size_t i = 0; i < s.folders.size(); ++i) {
        const std::string name = s.folders[i].filename().string();
        const fs::path out = o.out / name;
        s.totals[i].student = name;
        const std::string files = folderDigest(s.folders[i]);
        if (!configuration.empty() && !files.empty()) {
            Digest d;
            d.add(configuration);
            d.add(files);
            s.digests[i] = d.hex();
        }
        std::error_code ec;
        const bool unchanged = !s.digests[i].empty() && fs::exists(out / "report.json", ec) &&
                               fs::exists(out / "digest.txt", ec) &&
                               trimmed(readFile(out / "digest.txt")) == s.digests[i];
        if (unchanged) {
            ++summary.skipped;
        } else {
            s.todo.push_back(i);
        }
    }
    return s;
}

// Grades the submissions to grade in worker processes, recording each one's error in its
// total and drawing the progress as each ends.
void gradeInWorkers(const ModuleRegistry& modules, const DataPaths& paths, const BatchOptions& o,
                    Submissions& s, BatchSummary& summary,
                    std::chrono::steady_clock::time_point start) {
    const std::vector<fs::path>& students = s.folders;
    std::vector<StudentTotal>& totals = s.totals;
    const std::vector<size_t>& todo = s.todo;
    // Submissions at once, and grading processes each: about `jobs` processes in all.
    const size_t jobs = size_t(std::max(1, o.grade.jobs));
    const size_t atOnce = std::max<size_t>(1, std::min(jobs, todo.size()));
    GradeOptions each = o.grade;
    each.jobs = int(std::max<size_t>(1, jobs / atOnce));
    std::map<pid_t, size_t> running;
    size_t next = 0;
    if (o.progress) drawProgress(summary.skipped, students.size(), summary.skipped, 0, 0, false);
    while (next < todo.size() || !running.empty()) {
        while (running.size() < atOnce && next < todo.size()) {
            const size_t i = todo[next++];
            const fs::path out = o.out / totals[i].student;
            std::error_code ec;
            // A stale digest must not vouch for reports this run is about to replace.
            fs::remove(out / "digest.txt", ec);
            fs::remove(out / "error.txt", ec);
            try {
                fs::create_directories(out);
                running[startWorker(modules, paths, each, o.assignment, students[i], out,
                                    s.digests[i])] = i;
            } catch (const std::exception& e) {
                totals[i].error = e.what();
            }
        }
        if (running.empty()) continue;
        int status = 0;
        const pid_t pid = waitpid(-1, &status, 0);
        if (pid < 0) {
            if (errno == EINTR) continue;
            throw Error("grade --batch: waitpid failed: " + std::string(std::strerror(errno)));
        }
        auto it = running.find(pid);
        if (it == running.end()) continue;
        const size_t i = it->second;
        running.erase(it);
        ++summary.graded;
        const fs::path out = o.out / totals[i].student;
        if (WIFSIGNALED(status))
            totals[i].error =
                std::string("the grading process died (") + strsignal(WTERMSIG(status)) + ")";
        else if (fs::exists(out / "error.txt"))
            totals[i].error = trimmed(readFile(out / "error.txt"));
        else if (WEXITSTATUS(status) != 0)
            totals[i].error =
                "the grading process ended with status " + std::to_string(WEXITSTATUS(status));
        if (o.progress)
            drawProgress(summary.skipped + summary.graded, students.size(), summary.skipped,
                         summary.graded, secondsSince(start), false);
    }
}

// The class report's rows from each report.json, with each student's score in `totals`; a
// report that cannot be read is that student's error (counted in `summary`, as are the
// others').
std::vector<ClassRow> readReports(const BatchOptions& o, std::vector<StudentTotal>& totals,
                                  BatchSummary& summary) {
    std::vector<ClassRow> rows;
    for (StudentTotal& t : totals) {
        if (!t.error.empty()) {
            ++summary.errors;
            continue;
        }
        try {
            const json report = json::parse(readFile(o.out / t.student / "report.json"));
            t.score = report.at("score").get<double>();
            t.maxScore = report.at("max_score").get<double>();
            t.seconds = report.value("seconds", 0.0);
            const auto mine = classRows(t.student, report);
            rows.insert(rows.end(), mine.begin(), mine.end());
        } catch (const std::exception& e) {
            t.error = (o.out / t.student / "report.json").string() + ": " + e.what();
            ++summary.errors;
        }
    }
    return rows;
}

// shard.json: which shard this is, what graded it and its students, for grade --merge.
void writeShardIndex(const BatchOptions& o, const std::string& configuration,
                     const std::vector<StudentTotal>& totals) {
    std::vector<std::string> names;
    for (const StudentTotal& t : totals) names.push_back(t.student);
    const json shard = {{"shard", o.shard},
                        {"shards", o.shards},
                        {"configuration", configuration},
                        {"students", names}};
    writeFileAtomically(o.out / "shard.json", shard.dump(2) + "\n");
}

// The class report's title: the batch folder's name, and the shard when there are several.
std::string batchTitle(const BatchOptions& o) {
    fs::path folder = fs::absolute(o.batch).lexically_normal();
    if (!folder.has_filename()) folder = folder.parent_path();  // "class/"
    std::string title = folder.filename().string();
    if (o.shards > 1)
        title += " (shard " + std::to_string(o.shard) + " of " + std::to_string(o.shards) + ")";
    return title;
}

}  // namespace

std::pair<int, int> parseShard(const std::string& text) {
    int i = -1, n = 0;
    char slash = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &i, &slash, &n, &extra) != 3 || slash != '/' ||
        n < 1 || i < 0 || i >= n)
        throw Error("--shard \"" + text + "\": expected I/N with 0 <= I < N (e.g. 0/4)");
    return {i, n};
}

int shardOf(const std::string& student, int shards) {
    Digest d;
    d.add(student);
    return int(d.h % std::uint64_t(std::max(shards, 1)));
}

BatchSummary gradeBatch(const ModuleRegistry& modules, const DataPaths& paths,
                        const BatchOptions& o) {
    const auto start = std::chrono::steady_clock::now();
    if (!fs::is_directory(o.batch)) throw Error(o.batch.string() + ": not a directory");
    if (o.out.empty()) throw Error("--batch needs --out DIR for the reports");
    std::vector<fs::path> students = shardFolders(o);
    fs::create_directories(o.out);

    const std::string configuration = configurationDigest(modules, paths, o);
    BatchSummary summary;
    summary.students = students.size();
    Submissions s = submissionsToGrade(std::move(students), o, configuration, summary);
    gradeInWorkers(modules, paths, o, s, summary, start);
    const std::vector<ClassRow> rows = readReports(o, s.totals, summary);
    writeShardIndex(o, configuration, s.totals);
    writeClassReport(rows, s.totals, o.out, batchTitle(o));
    summary.seconds = secondsSince(start);
    if (o.progress)
        drawProgress(s.folders.size(), s.folders.size(), summary.skipped, summary.graded,
                     summary.seconds, true);
    return summary;
}

void mergeBatches(const std::vector<fs::path>& shardOutputs, const fs::path& out) {
    if (shardOutputs.empty()) throw Error("grade --merge: give the shard outputs to merge");
    std::vector<ClassRow> rows;
    std::vector<StudentTotal> totals;
    std::map<std::string, fs::path> owner;  // student -> the output that has it
    std::map<int, fs::path> seen;           // shard index -> its output
    int shards = 0;
    std::string configuration;
    for (const fs::path& dir : shardOutputs) {
        const fs::path file = dir / "shard.json";
        json shard;
        try {
            shard = json::parse(readFile(file));
        } catch (const std::exception& e) {
            throw Error(file.string() + ": " + e.what() +
                        " (not an output of pbrlab grade --batch?)");
        }
        int index = 0, count = 0;
        std::vector<std::string> students;
        std::string config;
        try {
            index = shard.at("shard").get<int>();
            count = shard.at("shards").get<int>();
            config = shard.at("configuration").get<std::string>();
            students = shard.at("students").get<std::vector<std::string>>();
        } catch (const std::exception& e) {
            throw Error(file.string() + ": " + e.what());
        }
        if (shards == 0) {
            shards = count;
            configuration = config;
        }
        if (count != shards)
            throw Error(file.string() + ": shard " + std::to_string(index) + " of " +
                        std::to_string(count) + ", but " + shardOutputs[0].string() +
                        " is one of " + std::to_string(shards));
        if (config != configuration || config.empty())
            throw Error(file.string() +
                        ": graded by another pbrlab build, steps, settings or assignment than " +
                        shardOutputs[0].string() + " (or by a build without build IDs)");
        if (auto [at, fresh] = seen.insert({index, dir}); !fresh)
            throw Error(dir.string() + " and " + at->second.string() + " are both shard " +
                        std::to_string(index) + " of " + std::to_string(shards));
        for (const std::string& s : students)
            if (auto [at, fresh] = owner.insert({s, dir}); !fresh)
                throw Error("submission \"" + s + "\" is in both " + at->second.string() + " and " +
                            dir.string());
        const std::set<std::string> listed(students.begin(), students.end());
        for (const ClassRow& r : readClassCsv(dir / "class.csv")) {
            if (!listed.count(r.student))
                throw Error((dir / "class.csv").string() + ": submission \"" + r.student +
                            "\" is not in " + file.string());
            rows.push_back(r);
        }
        for (const StudentTotal& t : readSummaryCsv(dir / "summary.csv")) {
            if (!listed.count(t.student))
                throw Error((dir / "summary.csv").string() + ": submission \"" + t.student +
                            "\" is not in " + file.string());
            totals.push_back(t);
        }
    }
    std::string missing;
    for (int i = 0; i < shards; ++i)
        if (!seen.count(i)) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
    if (!missing.empty())
        throw Error("grade --merge: shard(s) " + missing + " of " + std::to_string(shards) +
                    " missing");
    fs::create_directories(out);
    writeClassReport(rows, totals, out, "merged from " + std::to_string(shards) + " shards");
}

}  // namespace pbrlab
