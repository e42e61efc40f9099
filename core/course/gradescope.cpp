#include "course/gradescope.h"

#include <array>
#include <cstdint>
#include <fstream>
#include <iterator>

#include "steps/contract.h"
#include "steps/paths.h"
#include "util/error.h"

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
            std::string output = "**" + g.status + "**\n\n";
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
            json checks = json::array();
            std::string list;
            for (const json& check : g.checks) {
                if (check.value("category", "") != c.category) continue;
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
            tests.push_back({{"name", g.id + ": " + c.category},
                             {"number", number + "." + std::to_string(k + 1)},
                             {"score", c.score},
                             {"max_score", c.maxScore},
                             {"status", c.earning == c.checks ? "passed" : "failed"},
                             {"output", output},
                             {"output_format", "md"},
                             {"tags", {g.id, c.category}},
                             {"visibility", a.visibilityOf(g.id, c.category)},
                             {"extra_data",
                              {{"step", g.id},
                               {"status", g.status},
                               {"category", c.category},
                               {"checks", checks}}}});
        }
        // The summary is shown with the result as a whole: steps whose rows are not visible
        // now are left out of it.
        if (a.visibilityOf(g.id) == "visible")
            summary += "| " + g.id + " | " + g.status + " | " + formatPoints(g.score) + " / " +
                       formatPoints(g.maxScore) + " |\n";
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

std::string zipArchive(const std::vector<ZipEntry>& entries) {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    auto crc32 = [&](const std::string& data) {
        std::uint32_t c = 0xFFFFFFFFu;
        for (unsigned char b : data) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
        return c ^ 0xFFFFFFFFu;
    };
    std::string out, directory;
    auto u16 = [](std::string& s, std::uint32_t v) {
        s += char(v & 0xFF), s += char((v >> 8) & 0xFF);
    };
    auto u32 = [&](std::string& s, std::uint32_t v) { u16(s, v & 0xFFFF), u16(s, v >> 16); };
    for (const ZipEntry& e : entries) {
        if (e.data.size() >= 0xFFFFFFFFu || out.size() >= 0xFFFFFFFFu)
            throw Error("zip: " + e.name + ": larger than 4 GB (no ZIP64 here)");
        const std::uint32_t crc = crc32(e.data), offset = std::uint32_t(out.size()),
                            size = std::uint32_t(e.data.size());
        // Local header: version 1.0, no flags, stored, time 00:00 1 Jan 1980 (reproducible).
        u32(out, 0x04034b50), u16(out, 10), u16(out, 0), u16(out, 0), u16(out, 0), u16(out, 0x21);
        u32(out, crc), u32(out, size), u32(out, size), u16(out, std::uint32_t(e.name.size())),
            u16(out, 0);
        out += e.name + e.data;
        // Central directory entry, made by Unix (3): the mode is in the external attributes,
        // so that unzip restores run_autograder's execute bit.
        const std::uint32_t mode = e.executable ? 0100755 : 0100644;
        u32(directory, 0x02014b50), u16(directory, 0x0300 | 10), u16(directory, 10),
            u16(directory, 0), u16(directory, 0), u16(directory, 0), u16(directory, 0x21);
        u32(directory, crc), u32(directory, size), u32(directory, size),
            u16(directory, std::uint32_t(e.name.size())), u16(directory, 0), u16(directory, 0),
            u16(directory, 0), u16(directory, 0), u32(directory, mode << 16),
            u32(directory, offset);
        directory += e.name;
    }
    const std::uint32_t at = std::uint32_t(out.size());
    out += directory;
    u32(out, 0x06054b50), u16(out, 0), u16(out, 0), u16(out, std::uint32_t(entries.size())),
        u16(out, std::uint32_t(entries.size())), u32(out, std::uint32_t(directory.size())),
        u32(out, at), u16(out, 0);
    return out;
}

namespace {

const char* const kSetup = R"(#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder image (written by
# `pbrlab autograder`): install pbrlab from the Debian package beside this file, then fill the
# caches every grade reads by grading the reference solutions of the assignment's steps, so
# that no submission pays for them.
#   PBRLAB_AUTOGRADER_ROOT  instead of /autograder
#   PBRLAB_PREFIX           unpack the package there (dpkg-deb -x) instead of installing it
#                           with apt-get: no root needed (tests)
set -euo pipefail
root=${PBRLAB_AUTOGRADER_ROOT:-/autograder}
source_dir=$root/source
debs=("$source_dir"/pbrlab_*.deb)
if [ ! -f "${debs[0]}" ]; then
    echo "setup.sh: no pbrlab_*.deb in $source_dir" >&2
    exit 1
fi
if [ -n "${PBRLAB_PREFIX:-}" ]; then
    dpkg-deb -x "${debs[0]}" "$PBRLAB_PREFIX"
    pbrlab=$PBRLAB_PREFIX/usr/bin/pbrlab
else
    apt-get update
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${debs[0]}"
    pbrlab=/usr/bin/pbrlab
fi
export PBRLAB_CACHE=$source_dir/pbrlab-cache
reference=$(mktemp -d)
trap 'rm -rf "$reference"' EXIT
"$pbrlab" kit --assignment "$source_dir/assignment.json" --with-solutions --out "$reference/kit"
"$pbrlab" grade "$reference/kit" --assignment "$source_dir/assignment.json" > /dev/null
echo "setup.sh: pbrlab installed, caches filled in $PBRLAB_CACHE"
)";

const char* const kRunAutograder = R"(#!/usr/bin/env bash
# Gradescope runs this for every submission (written by `pbrlab autograder`): grade
# /autograder/submission by the assignment into /autograder/results/results.json. pbrlab
# exits 0 whenever grading ran, whatever the score. The same variables as setup.sh.
set -euo pipefail
root=${PBRLAB_AUTOGRADER_ROOT:-/autograder}
if [ -n "${PBRLAB_PREFIX:-}" ]; then
    pbrlab=$PBRLAB_PREFIX/usr/bin/pbrlab
else
    pbrlab=/usr/bin/pbrlab
fi
mkdir -p "$root/results"
export PBRLAB_CACHE=$root/source/pbrlab-cache
"$pbrlab" grade "$root/submission" --assignment "$root/source/assignment.json" \
    --gradescope "$root/results/results.json"
)";

}  // namespace

fs::path findDebianPackage() {
    std::vector<fs::path> found;
    const std::vector<fs::path> places = {fs::current_path(), executableDir()};
    for (const fs::path& place : places) {
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(place, ec)) {
            const std::string name = e.path().filename().string();
            if (name.rfind("pbrlab_", 0) == 0 && e.path().extension() == ".deb")
                found.push_back(e.path());
        }
        if (!found.empty()) break;
    }
    if (found.size() == 1) return found.front();
    throw Error(std::string(found.empty() ? "no" : "more than one") + " pbrlab_*.deb in " +
                places[0].string() + " or " + places[1].string() +
                ": build it with `cpack -G DEB` in the build folder, or give --deb FILE");
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

fs::path writeAutograderBundle(AutograderOptions o, const ModuleRegistry& modules) {
    loadAssignment(o.assignment, stepIds(modules));  // a broken file is refused here, not on
                                                     // Gradescope
    if (o.deb.empty()) o.deb = findDebianPackage();
    const std::string debName = o.deb.filename().string();
    if (debName.rfind("pbrlab_", 0) != 0 || o.deb.extension() != ".deb")
        throw Error(o.deb.string() + ": not a pbrlab_*.deb (cpack -G DEB in the build folder)");
    const std::vector<ZipEntry> entries = {{"setup.sh", kSetup, true},
                                           {"run_autograder", kRunAutograder, true},
                                           {"assignment.json", readWholeFile(o.assignment), false},
                                           {debName, readWholeFile(o.deb), false}};
    const fs::path zip = o.out / "autograder.zip";
    fs::create_directories(o.out);
    writeFileAtomically(zip, zipArchive(entries));
    return zip;
}

}  // namespace pbrlab
