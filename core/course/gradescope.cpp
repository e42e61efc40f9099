#include "course/gradescope.h"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <fstream>

#include "steps/contract.h"
#include "steps/paths.h"
#include "util/error.h"
#include "util/fs.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

namespace {

// Text shown as markdown: the characters markdown would read as formatting, escaped.
std::string mdText(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (std::string("\\`*_[]<>|#").find(c) != std::string::npos) out += '\\';
        out += c;
    }
    return out;
}

// A message (compiler logs, feedback) verbatim in a fenced block.
std::string mdBlock(std::string s) {
    for (size_t at; (at = s.find("```")) != std::string::npos;) s.replace(at, 3, "'''");
    return "```text\n" + s + "\n```\n";
}

std::string stepNumber(const std::string& id) {
    const ContractStep* s = findContractStep(id);
    return s ? std::to_string(s->step) : "0";
}

}  // namespace

json toGradescope(const GradeReport& r, const Assignment& a) {
    json tests = json::array();
    std::string summary = "| step | status | points |\n|---|---|---|\n";
    for (const ModuleGrade& g : r.modules) {
        const std::string number = stepNumber(g.id);
        const std::vector<CategoryScore> categories = categoryScores(g, a);
        // The step's feedback goes with its first failed row (it names the mistake once).
        bool feedbackGiven = g.message.empty();
        if (categories.empty()) {
            std::string output = "**" + std::string(nameOf(g.status)) + "**\n\n";
            if (!g.message.empty()) output += mdBlock(g.message);
            tests.push_back(
                {{"name", g.id + ": " + g.title},
                 {"number", number},
                 {"score", roundPoints(g.score)},
                 {"max_score", roundPoints(g.maxScore)},
                 {"status", g.score >= g.maxScore ? "passed" : "failed"},
                 {"output", output},
                 {"output_format", "md"},
                 {"tags", {g.id}},
                 {"visibility", a.visibilityOf(g.id)},
                 {"extra_data", {{"step", g.id}, {"status", g.status}, {"checks", g.checks}}}});
        }
        for (size_t k = 0; k < categories.size(); ++k) {
            const CategoryScore& c = categories[k];
            const std::string category(nameOf(c.category));
            json checks = json::array();
            std::string list;
            for (const json& check : g.checks) {
                if (check.value("category", "") != category) continue;
                checks.push_back(check);
                list += "- " + std::string(check.value("passed", false) ? "passed" : "**failed**") +
                        ": " + mdText(check.value("name", "")) + " (" +
                        mdText(check.value("detail", "")) + ")\n";
            }
            std::string output =
                std::to_string(c.passed) + " of " + std::to_string(c.checks) + " checks passed\n\n";
            if (c.earning < c.passed)
                output += "No points for " + std::to_string(c.passed - c.earning) +
                          " of them until a values check of this step passes that the starter "
                          "code fails: checks like these pass for the starter code too.\n\n";
            output += list;
            if (c.passed < c.checks && !feedbackGiven) {
                output += "\n**Feedback**\n\n" + mdBlock(g.message);
                feedbackGiven = true;
            }
            tests.push_back({{"name", g.id + ": " + category},
                             {"number", number + "." + std::to_string(k + 1)},
                             {"score", c.score},
                             {"max_score", c.maxScore},
                             {"status", c.earning == c.checks ? "passed" : "failed"},
                             {"output", output},
                             {"output_format", "md"},
                             {"tags", {g.id, category}},
                             {"visibility", a.visibilityOf(g.id, category)},
                             {"extra_data",
                              {{"step", g.id},
                               {"status", g.status},
                               {"category", category},
                               {"checks", checks}}}});
        }
        // The summary is shown with the result as a whole: steps whose rows are not visible
        // now are left out of it.
        if (a.visibilityOf(g.id) == "visible")
            summary += "| " + g.id + " | " + std::string(nameOf(g.status)) + " | " +
                       formatPoints(g.score) + " / " + formatPoints(g.maxScore) + " |\n";
    }
    // Every score is a whole number of micro-points (course/autograder.h): the sum is exact.
    double score = 0;
    for (const json& t : tests) score = addPoints(score, t["score"].get<double>());
    return {{"score", score},
            {"execution_time", r.seconds},
            {"output", (a.name.empty() ? "" : "**" + mdText(a.name) + "**\n\n") + summary},
            {"output_format", "md"},
            {"visibility", a.visibilityOf("", "")},
            {"stdout_visibility", "hidden"},
            {"extra_data", {{"assignment", a.name}, {"max_score", roundPoints(r.maxScore)}}},
            {"tests", tests}};
}

void writeZip(const fs::path& zip, const std::vector<ZipEntry>& entries) {
    if (zip.has_parent_path()) fs::create_directories(zip.parent_path());
    fs::path tmp = zip;
    tmp += ".tmp" + std::to_string(getpid());
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw Error(tmp.string() + ": cannot write");
    auto u16 = [](std::string& s, std::uint32_t v) {
        s += char(v & 0xFF), s += char((v >> 8) & 0xFF);
    };
    auto u32 = [&](std::string& s, std::uint32_t v) { u16(s, v & 0xFFFF), u16(s, v >> 16); };
    std::string directory;
    std::uint64_t offset = 0;
    for (const ZipEntry& e : entries) {
        const std::string data = e.data.empty() && !e.file.empty() ? readFile(e.file) : e.data;
        if (data.size() >= 0xFFFFFFFFu || offset >= 0xFFFFFFFFu)
            throw Error("zip: " + e.name + ": past 4 GB (no ZIP64 here)");
        const std::uint32_t crc =
            std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(data.data()), uInt(data.size())));
        // Raw deflate (no zlib header), as ZIP's method 8 wants it.
        std::string packed(deflateBound(nullptr, uLong(data.size())) + 64, '\0');
        z_stream z{};
        if (deflateInit2(&z, 6, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK)
            throw Error("zip: zlib's deflateInit2 failed");
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
        z.avail_in = uInt(data.size());
        z.next_out = reinterpret_cast<Bytef*>(packed.data());
        z.avail_out = uInt(packed.size());
        const int done = deflate(&z, Z_FINISH);
        packed.resize(z.total_out);
        deflateEnd(&z);
        if (done != Z_STREAM_END) throw Error("zip: " + e.name + ": deflate failed");
        const bool deflated = packed.size() < data.size();
        const std::string& stored = deflated ? packed : data;
        const std::uint32_t method = deflated ? 8 : 0, version = deflated ? 20 : 10,
                            size = std::uint32_t(data.size()), csize = std::uint32_t(stored.size()),
                            at = std::uint32_t(offset);
        // Local header: no flags, time 00:00 1 Jan 1980 (reproducible).
        std::string header;
        u32(header, 0x04034b50), u16(header, version), u16(header, 0), u16(header, method),
            u16(header, 0), u16(header, 0x21);
        u32(header, crc), u32(header, csize), u32(header, size),
            u16(header, std::uint32_t(e.name.size())), u16(header, 0);
        header += e.name;
        out.write(header.data(), std::streamsize(header.size()));
        out.write(stored.data(), std::streamsize(stored.size()));
        offset += header.size() + stored.size();
        // Central directory entry, made by Unix (3): the mode is in the external attributes,
        // so that unzip restores the scripts' execute bit.
        const std::uint32_t mode = e.executable ? 0100755 : 0100644;
        u32(directory, 0x02014b50), u16(directory, 0x0300 | version), u16(directory, version),
            u16(directory, 0), u16(directory, method), u16(directory, 0), u16(directory, 0x21);
        u32(directory, crc), u32(directory, csize), u32(directory, size),
            u16(directory, std::uint32_t(e.name.size())), u16(directory, 0), u16(directory, 0),
            u16(directory, 0), u16(directory, 0), u32(directory, mode << 16), u32(directory, at);
        directory += e.name;
    }
    if (offset + directory.size() >= 0xFFFFFFFFu) throw Error("zip: past 4 GB (no ZIP64 here)");
    std::string end;
    u32(end, 0x06054b50), u16(end, 0), u16(end, 0), u16(end, std::uint32_t(entries.size())),
        u16(end, std::uint32_t(entries.size())), u32(end, std::uint32_t(directory.size())),
        u32(end, std::uint32_t(offset)), u16(end, 0);
    out.write(directory.data(), std::streamsize(directory.size()));
    out.write(end.data(), std::streamsize(end.size()));
    out.close();
    if (!out) throw Error(tmp.string() + ": cannot write");
    fs::rename(tmp, zip);
}

namespace {

// The scripts hold to what the bundle needs of the system: /bin/sh and the tools of every base
// image (mkdir, rm, chmod, cat). BUDGET in run_autograder becomes gradingBudgetSeconds()'s
// seconds.
const char* const kSetup = R"(#!/bin/sh
# Gradescope runs this once, as root, when it builds the autograder's image (written by
# `pbrlab autograder`, docs/assignment.md). It installs nothing: pbrlab/ beside it is the grader
# bundle, which needs only glibc >= 2.35. It grades the reference solutions of the
# assignment's steps once: that fills the caches every grade reads, so that no submission pays
# for them, and proves that the bundle grades on this image. A step that does not pass fails
# the build, so that "Update autograder" shows it, not the students.
#   PBRLAB_AUTOGRADER_ROOT  instead of /autograder (tests)
set -eu
root=${PBRLAB_AUTOGRADER_ROOT:-/autograder}
source_dir=$root/source
pbrlab=$source_dir/pbrlab/bin/pbrlab
chmod 755 "$pbrlab" "$source_dir/run_autograder"  # in case the unzip dropped the modes
export PBRLAB_CACHE="$source_dir/pbrlab-cache" MESA_SHADER_CACHE_DIR="$source_dir/mesa-cache"
reference=$source_dir/reference-solutions
rm -rf "$reference"
"$pbrlab" kit --assignment "$source_dir/assignment.json" --with-solutions --out "$reference"
# No time limit of the assignment's here: these are the reference solutions, and the first
# grade of some steps computes the converged integrals that every later grade reads (minutes
# on half a processor).
"$pbrlab" grade "$reference" --assignment "$source_dir/assignment.json" --fail-unless-passed \
    --timeout 3600
rm -rf "$reference"
echo "setup.sh: the grader bundle grades here; caches filled in $PBRLAB_CACHE"
)";

const char* const kRunAutograder = R"(#!/bin/sh
# Gradescope runs this for every submission (written by `pbrlab autograder`): grade
# /autograder/submission by the assignment into /autograder/results/results.json, within
# BUDGET s of wall clock (the assignment's Gradescope timeout less a margin: a step still
# grading then, or not started, scores 0 and says so). pbrlab exits 0 whenever grading ran,
# whatever the score; should it not run to the end at all (killed for memory, say), a
# results.json still says what happened. The same variable as setup.sh.
root=${PBRLAB_AUTOGRADER_ROOT:-/autograder}
source_dir=$root/source
results=$root/results/results.json
mkdir -p "$root/results"
rm -f "$results"
export PBRLAB_CACHE="$source_dir/pbrlab-cache" MESA_SHADER_CACHE_DIR="$source_dir/mesa-cache"
"$source_dir/pbrlab/bin/pbrlab" grade "$root/submission" \
    --assignment "$source_dir/assignment.json" --gradescope "$results" --time-budget BUDGET
status=$?
if [ ! -s "$results" ]; then
    cat > "$results" <<RESULTS
{"score": 0, "output_format": "md", "stdout_visibility": "hidden", "tests": [],
 "output": "**Not graded.** The autograder stopped (exit status $status) before it could grade this submission: this says nothing of your work. Your instructor sees what happened and can grade it again."}
RESULTS
fi
exit 0
)";

bool isGraderBundle(const fs::path& dir) {
    std::error_code ec;
    return fs::is_regular_file(dir / kGraderBundleMarker, ec) &&
           fs::is_regular_file(dir / "bin" / "pbrlab", ec);
}

}  // namespace

fs::path findGraderBundle() {
    const fs::path exe = executableDir();
    if (isGraderBundle(exe.parent_path())) return exe.parent_path();
    if (isGraderBundle(exe / "grader-bundle")) return exe / "grader-bundle";
    throw Error("no grader bundle: this pbrlab runs from none, and there is no " +
                (exe / "grader-bundle").string() +
                "; make it with `bash scripts/grader-bundle.sh` in pbrlab's source folder, or "
                "give --bundle DIR");
}

std::optional<Assignment> gradeAssignment(const std::string& file, const ModuleRegistry& modules,
                                          GradeOptions& options) {
    if (file.empty()) return std::nullopt;
    Assignment a = loadAssignment(file, stepIds(modules));
    applyAssignment(a, options);
    return a;
}

json gradescopeResults(const GradeReport& report, const std::optional<Assignment>& a) {
    return a ? toGradescope(report, *a) : toGradescope(report);
}

double gradingBudgetSeconds(double gradescopeTimeoutSeconds) {
    // A tenth of the timeout, at least 30 s, for the container's and pbrlab's start and
    // writing results.json; never below half the timeout.
    return std::max(0.5 * gradescopeTimeoutSeconds,
                    gradescopeTimeoutSeconds - std::max(30.0, 0.1 * gradescopeTimeoutSeconds));
}

fs::path writeAutograderBundle(AutograderOptions o, const ModuleRegistry& modules) {
    // A broken file is refused here, not on Gradescope.
    const Assignment a = loadAssignment(o.assignment, stepIds(modules));
    if (o.gradescopeTimeoutSeconds < 60)
        throw Error("--gradescope-timeout: at least 60 s (Gradescope's default is 600)");
    if (o.bundle.empty()) o.bundle = findGraderBundle();
    if (!isGraderBundle(o.bundle))
        throw Error(o.bundle.string() + ": not a grader bundle (no " + kGraderBundleMarker +
                    " and bin/pbrlab; scripts/grader-bundle.sh makes one)");
    for (const std::string& id : a.steps)
        if (!fs::exists(o.bundle / "lib" / "pbrlab" / "modules" / ("pbrlab-" + id + ".so")))
            throw Error(o.bundle.string() + ": has no plugin for step " + id +
                        " of the assignment (a bundle of another build?)");
    std::string run = kRunAutograder;
    const std::string budget =
        std::to_string(int(gradingBudgetSeconds(o.gradescopeTimeoutSeconds)));
    for (size_t at; (at = run.find("BUDGET")) != std::string::npos;) run.replace(at, 6, budget);
    std::vector<ZipEntry> entries = {{"setup.sh", kSetup, {}, true},
                                     {"run_autograder", run, {}, true},
                                     {"assignment.json", readFile(o.assignment), {}, false}};
    // The bundle's files in a fixed order: the same bundle makes the same zip.
    std::vector<fs::path> files;
    for (const auto& e : fs::recursive_directory_iterator(o.bundle)) {
        if (e.is_symlink())
            throw Error(e.path().string() +
                        ": a symbolic link in the grader bundle (it holds "
                        "copies: not every unzip keeps links)");
        if (e.is_regular_file()) files.push_back(e.path());
    }
    std::sort(files.begin(), files.end());
    for (const fs::path& f : files) {
        const bool executable =
            (fs::status(f).permissions() & fs::perms::owner_exec) != fs::perms::none;
        entries.push_back(
            {"pbrlab/" + f.lexically_relative(o.bundle).generic_string(), "", f, executable});
    }
    const fs::path zip = o.out / "autograder.zip";
    writeZip(zip, entries);
    return zip;
}

}  // namespace pbrlab
