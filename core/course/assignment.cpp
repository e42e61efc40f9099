#include "course/assignment.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <numeric>
#include <set>
#include <sstream>

#include "course/autograder.h"
#include "course/kit.h"
#include "grading/grade_step.h"
#include "steps/plugin_host.h"
#include "util/error.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

namespace {

const std::vector<std::string> kVisibilities = {"visible", "hidden", "after_due_date",
                                                "after_published"};

// A calendar date YYYY-MM-DD (such strings compare in date order).
bool isDate(const std::string& s) {
    std::tm tm{};
    std::istringstream in(s);
    in >> std::get_time(&tm, "%Y-%m-%d");
    std::tm normalized = tm;
    return s.size() == 10 && !in.fail() && in.peek() == EOF && timegm(&normalized) != -1 &&
           normalized.tm_mday == tm.tm_mday && normalized.tm_mon == tm.tm_mon;
}

// Errors name the file and the JSON path of the field.
struct Reader {
    std::string file;
    const std::vector<std::string>& known;

    [[noreturn]] void fail(const std::string& path, const std::string& what) const {
        throw Error(file + ": " + path + ": " + what);
    }
    bool isStep(const std::string& id) const {
        return std::find(known.begin(), known.end(), id) != known.end();
    }
    size_t stepIndex(const std::string& path, const json& v) const {
        if (!v.is_string()) fail(path, "must be a step id (a string)");
        const auto it = std::find(known.begin(), known.end(), v.get<std::string>());
        if (it == known.end())
            fail(path, "'" + v.get<std::string>() + "' is not a step id (see `pbrlab list`)");
        return size_t(it - known.begin());
    }
    double number(const std::string& path, const json& v, double min, double max) const {
        if (!v.is_number() || !std::isfinite(v.get<double>()) || v.get<double>() < min ||
            v.get<double>() > max) {
            std::ostringstream o;
            o << "must be a number >= " << min;
            if (max < 1e300) o << " and <= " << max;
            fail(path, o.str());
        }
        return v.get<double>();
    }
    bool boolean(const std::string& path, const json& v) const {
        if (!v.is_boolean()) fail(path, "must be true or false");
        return v.get<bool>();
    }
    std::string string(const std::string& path, const json& v) const {
        if (!v.is_string()) fail(path, "must be a string");
        return v.get<std::string>();
    }
    const json& object(const std::string& path, const json& v) const {
        if (!v.is_object()) fail(path, "must be an object {...}");
        return v;
    }
    std::string date(const std::string& path, const json& v) const {
        const std::string s = string(path, v);
        if (!isDate(s)) fail(path, "'" + s + "' is not a date YYYY-MM-DD");
        return s;
    }
    std::vector<Assignment::Release> schedule(const std::string& path, const json& v,
                                              const std::vector<std::string>& steps) const {
        if (!v.is_array()) fail(path, "must be an array of {\"date\": ..., \"through\": ...}");
        std::vector<Assignment::Release> out;
        size_t lastStep = 0;
        for (size_t i = 0; i < v.size(); ++i) {
            const std::string at = path + "[" + std::to_string(i) + "]";
            object(at, v[i]);
            for (const auto& [key, value] : v[i].items())
                if (key != "date" && key != "through") fail(at + "." + key, "unknown field");
            if (!v[i].contains("date")) fail(at + ".date", "missing");
            if (!v[i].contains("through")) fail(at + ".through", "missing");
            Assignment::Release r{date(at + ".date", v[i]["date"]), ""};
            const size_t step = stepIndex(at + ".through", v[i]["through"]);
            r.through = known[step];
            if (std::find(steps.begin(), steps.end(), r.through) == steps.end())
                fail(at + ".through", "'" + r.through + "' is not one of the assignment's steps");
            if (!out.empty() && r.date <= out.back().date)
                fail(at + ".date", "must come after " + out.back().date + " (the entry before)");
            if (!out.empty() && step <= lastStep)
                fail(at + ".through", "must be a later step than " + out.back().through);
            lastStep = step;
            out.push_back(r);
        }
        return out;
    }
};

bool isCategory(const std::string& c) {
    return verdictNamed<CheckCategory>(c).has_value();
}

// The top level: an object of the known fields only.
void checkTopLevel(const Reader& r, const json& j) {
    if (!j.is_object()) r.fail("(top level)", "must be an object {...}");
    const std::set<std::string> fields = {
        "name",       "steps",   "points",    "checks", "partial_credit",
        "visibility", "release", "solutions", "due",    "time_limit_seconds",
        "cumulative"};
    for (const auto& [key, value] : j.items())
        if (!fields.count(key))
            r.fail(key,
                   "unknown field (known: name, steps, points, checks, partial_credit, "
                   "visibility, release, solutions, due, time_limit_seconds, cumulative)");
}

// steps: "all" or a list of ids, kept in the order of the steps.
std::vector<std::string> readSteps(const Reader& r, const json& j) {
    if (!j.contains("steps")) r.fail("steps", "missing (a list of step ids, or \"all\")");
    const json& steps = j["steps"];
    if (steps.is_string() && steps.get<std::string>() == "all") return r.known;
    if (!steps.is_array() || steps.empty())
        r.fail("steps", "must be \"all\" or a non-empty list of step ids");
    std::vector<size_t> indices;
    for (size_t i = 0; i < steps.size(); ++i) {
        const std::string at = "steps[" + std::to_string(i) + "]";
        const size_t k = r.stepIndex(at, steps[i]);
        if (std::find(indices.begin(), indices.end(), k) != indices.end())
            r.fail(at, "'" + r.known[k] + "' is listed twice");
        indices.push_back(k);
    }
    std::sort(indices.begin(), indices.end());
    std::vector<std::string> out;
    for (size_t k : indices) out.push_back(r.known[k]);
    return out;
}

// points: per step, "default" for the others (1 unless told); every step of `steps` gets some.
std::map<std::string, double> readPoints(const Reader& r, const json& j,
                                         const std::vector<std::string>& steps) {
    double defaultPoints = 1;
    std::map<std::string, double> points;
    if (j.contains("points")) {
        for (const auto& [key, value] : r.object("points", j["points"]).items()) {
            const double p = r.number("points." + key, value, 0, 1e6);
            if (key == "default")
                defaultPoints = p;
            else if (!r.isStep(key))
                r.fail("points." + key, "'" + key + "' is not a step id (see `pbrlab list`)");
            else if (std::find(steps.begin(), steps.end(), key) == steps.end())
                r.fail("points." + key, "'" + key + "' is not one of the assignment's steps");
            else
                points[key] = p;
        }
    }
    std::map<std::string, double> out;
    for (const std::string& s : steps) out[s] = points.count(s) ? points[s] : defaultPoints;
    return out;
}

// checks: a weight per category; robustness is reported, not deducted, unless weighted.
std::map<CheckCategory, double> readWeights(const Reader& r, const json& j) {
    std::map<CheckCategory, double> weights;
    for (const CheckCategory c : allOf<CheckCategory>())
        weights[c] = c == CheckCategory::Robustness ? 0 : 1;
    if (j.contains("checks")) {
        for (const auto& [key, value] : r.object("checks", j["checks"]).items()) {
            const std::optional<CheckCategory> category = verdictNamed<CheckCategory>(key);
            if (!category) {
                std::string known;
                for (const CheckCategory c : allOf<CheckCategory>())
                    known += (known.empty() ? "" : ", ") + std::string(nameOf(c));
                r.fail("checks." + key, "not a check category (" + known + ")");
            }
            weights[*category] = r.number("checks." + key, value, 0, 1e6);
        }
    }
    return weights;
}

// visibility: Gradescope's, by "default", step id, category or step.category.
std::map<std::string, std::string> readVisibility(const Reader& r, const json& v) {
    std::map<std::string, std::string> visibility;
    for (const auto& [key, value] : r.object("visibility", v).items()) {
        const size_t dot = key.find('.');
        const std::string step = key.substr(0, dot),
                          category = dot == std::string::npos ? "" : key.substr(dot + 1);
        const bool ok = key == "default" ||
                        (dot == std::string::npos && (r.isStep(key) || isCategory(key))) ||
                        (dot != std::string::npos && r.isStep(step) && isCategory(category));
        if (!ok)
            r.fail("visibility." + key,
                   "not \"default\", a step id, a check category or step.category");
        const std::string s = r.string("visibility." + key, value);
        if (std::find(kVisibilities.begin(), kVisibilities.end(), s) == kVisibilities.end())
            r.fail("visibility." + key,
                   "'" + s + "' is not visible, hidden, after_due_date or after_published");
        visibility[key] = s;
    }
    return visibility;
}

// due: a date, or a date and a time in UTC (Gradescope's own due date is what after_due_date
// waits for; this one is shown in the kit).
std::string readDue(const Reader& r, const json& v) {
    const std::string due = r.string("due", v);
    r.date("due", due.substr(0, 10));
    const std::string rest = due.substr(std::min<size_t>(10, due.size()));
    std::tm tm{};
    std::istringstream in(rest.size() > 1 ? rest.substr(1) : "");
    in >> std::get_time(&tm, "%H:%M:%S");
    if (!rest.empty() && (rest.size() != 10 || rest[0] != 'T' || rest.back() != 'Z' || in.fail()))
        r.fail("due", "'" + due + "' is not YYYY-MM-DD or YYYY-MM-DDTHH:MM:SSZ");
    return due;
}

}  // namespace

std::string Assignment::visibilityOf(const std::string& step, const std::string& category) const {
    for (const std::string& key :
         {category.empty() ? std::string() : step + "." + category, step, category})
        if (!key.empty())
            if (auto it = visibility.find(key); it != visibility.end()) return it->second;
    auto it = visibility.find("default");
    return it == visibility.end() ? "visible" : it->second;
}

Assignment parseAssignment(const json& j, const std::string& fileName,
                           const std::vector<std::string>& knownSteps) {
    const Reader r{fileName, knownSteps};
    Assignment a;
    a.file = fileName;
    checkTopLevel(r, j);
    if (j.contains("name")) a.name = r.string("name", j["name"]);
    a.steps = readSteps(r, j);
    a.points = readPoints(r, j, a.steps);
    a.weights = readWeights(r, j);
    if (j.contains("partial_credit"))
        a.partialCredit = r.boolean("partial_credit", j["partial_credit"]);
    if (j.contains("visibility")) a.visibility = readVisibility(r, j["visibility"]);
    if (j.contains("release")) a.release = r.schedule("release", j["release"], a.steps);
    if (j.contains("solutions")) a.solutions = r.schedule("solutions", j["solutions"], a.steps);
    if (j.contains("due")) a.due = readDue(r, j["due"]);
    if (j.contains("time_limit_seconds"))
        a.timeLimitSeconds = r.number("time_limit_seconds", j["time_limit_seconds"], 1, 3600);
    if (j.contains("cumulative")) a.cumulative = r.boolean("cumulative", j["cumulative"]);
    return a;
}

Assignment loadAssignment(const fs::path& file, const std::vector<std::string>& knownSteps) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw Error(file.string() + ": cannot read");
    json j;
    try {
        // Comments are allowed: an assignment is a file instructors annotate.
        j = json::parse(in, nullptr, true, true);
    } catch (const json::parse_error& e) {
        throw Error(file.string() + ": not valid JSON: " + e.what());
    }
    return parseAssignment(j, file.string(), knownSteps);
}

std::vector<CategoryScore> categoryScores(const ModuleGrade& g, const Assignment& a) {
    std::vector<CategoryScore> out;
    if (!a.partialCredit || (g.status != GradeStatus::Passed && g.status != GradeStatus::Failed))
        return out;
    // Points say that something of the step was done: none until a values check passed that
    // the kit's stub fails (the grader marks it shows_work). The stub passes the contract,
    // invariants such as 0 <= G <= 1, finite values, robustness, values where the reference
    // is what it returns.
    bool workShown = false;
    for (const json& check : g.checks)
        workShown = workShown || (check.value("shows_work", false) && check.value("passed", false));
    for (const CheckCategory c : allOf<CheckCategory>()) {
        CategoryScore s;
        s.category = c;
        for (const json& check : g.checks) {
            if (check.value("category", "") != nameOf(c)) continue;
            // A contract violation reads black where the step may not read: nothing else it
            // measured means anything.
            if (c == CheckCategory::Contract && !check.value("passed", false)) return {};
            const bool passed = check.value("passed", false);
            ++s.checks;
            s.passed += passed;
            s.earning += passed && workShown;
        }
        if (s.checks > 0 && a.weights.at(c) > 0) out.push_back(s);
    }
    double total = 0;
    for (const CategoryScore& s : out) total += a.weights.at(s.category);
    if (total <= 0) return {};
    // In whole micro-points (course/autograder.h): the maxima add up to the points exactly, the
    // last category taking what the others leave, and each score is its maximum's share rounded
    // once.
    const std::int64_t points = toMicroPoints(a.points.count(g.id) ? a.points.at(g.id) : 1);
    std::int64_t given = 0;
    for (size_t k = 0; k < out.size(); ++k) {
        CategoryScore& s = out[k];
        const std::int64_t max =
            k + 1 < out.size()
                ? std::min<std::int64_t>(
                      std::llround(double(points) * a.weights.at(s.category) / total),
                      points - given)
                : points - given;
        given += max;
        // max * earning / checks, rounded half up, in integers.
        const std::int64_t score = (2 * max * s.earning + s.checks) / (2 * std::int64_t(s.checks));
        s.maxScore = fromMicroPoints(max);
        s.score = fromMicroPoints(score);
    }
    return out;
}

void scoreGrade(ModuleGrade& g, const Assignment& a) {
    g.maxScore = roundPoints(a.points.count(g.id) ? a.points.at(g.id) : 1);
    const std::vector<CategoryScore> scores = categoryScores(g, a);
    if (scores.empty()) {
        g.score = g.status == GradeStatus::Passed ? g.maxScore : 0;
        return;
    }
    g.score = 0;
    for (const CategoryScore& s : scores) g.score = addPoints(g.score, s.score);
}

std::string releasedThrough(const std::vector<Assignment::Release>& schedule,
                            const std::string& date) {
    std::string through;
    for (const Assignment::Release& r : schedule)
        if (r.date <= date) through = r.through;
    return through;
}

std::vector<std::string> stepIds(const ModuleRegistry& modules) {
    std::vector<std::string> ids;
    for (const LoadedModule& m : modules.modules()) ids.push_back(m.desc->id);
    return ids;
}

void applyAssignment(const Assignment& a, GradeOptions& o) {
    o.modules = a.steps;
    o.timeoutSeconds = a.timeLimitSeconds;
    o.cumulative = a.cumulative;
    o.scoring = [a](ModuleGrade& g) { scoreGrade(g, a); };
}

void applyAssignment(const Assignment& a, const std::string& date, KitOptions& o) {
    if (!isDate(date)) throw Error("--date " + date + ": not a date YYYY-MM-DD");
    o.steps = a.steps;
    if (!o.withSolutions && !a.release.empty()) {
        const std::string through = releasedThrough(a.release, date);
        if (through.empty())
            throw Error(a.file.string() + ": release: nothing is out by " + date +
                        " (the first release is on " + a.release.front().date + ")");
        o.steps.erase(std::find(o.steps.begin(), o.steps.end(), through) + 1, o.steps.end());
    }
    if (o.releaseThrough.empty()) o.releaseThrough = releasedThrough(a.solutions, date);
    o.due = a.due;
}

std::string todayUtc() {
    const std::time_t now = std::time(nullptr);
    std::tm tm{};
    gmtime_r(&now, &tm);
    char text[16];
    std::strftime(text, sizeof text, "%Y-%m-%d", &tm);
    return text;
}

}  // namespace pbrlab
