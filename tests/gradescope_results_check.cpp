// Validates a results.json against Gradescope's documented format (autograder specifications,
// "Output format"): only the documented fields, each of its documented type and values, and
// the total equal to the sum of the tests' scores. Used by gradescope_bundle.sh and
// grader_bare_system.sh.
// Usage: pbrlab_gradescope_check results.json [expected-score] [--visibility]
//                                [--same-as OTHER.json]
// Prints the score (with --visibility, then "<name>: <visibility>" for the result as a whole,
// named "(result)", and for each test in order, for a test to compare row by row); exit 1 with
// every problem listed when the file does not validate. --same-as: also a problem for every
// difference from OTHER.json but the time grading took (execution_time): the same grade.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

using nlohmann::json;

namespace {

std::vector<std::string> problems;

void problem(const std::string& where, const std::string& what) {
    problems.push_back(where + ": " + what);
}

const std::set<std::string> kVisibility = {"hidden", "after_due_date", "after_published",
                                           "visible"};
const std::set<std::string> kFormats = {"text", "html", "simple_format", "md", "ansi"};

void checkField(const std::string& where, const json& v, const std::string& type) {
    const bool ok = type == "number"   ? v.is_number()
                    : type == "string" ? v.is_string()
                    : type == "object" ? v.is_object()
                    : type == "array"  ? v.is_array()
                    : type == "visibility"
                        ? v.is_string() && kVisibility.count(v.get<std::string>())
                    : type == "format" ? v.is_string() && kFormats.count(v.get<std::string>())
                    : type == "status" ? v.is_string() && (v == "passed" || v == "failed")
                    : type == "tags"   ? v.is_array()
                                       : false;
    if (!ok) problem(where, "must be " + type + ", is " + v.dump().substr(0, 80));
    if (type == "tags" && v.is_array())
        for (const json& t : v)
            if (!t.is_string()) problem(where, "tags must be strings");
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    const auto flag = std::find(args.begin(), args.end(), "--visibility");
    const bool listVisibility = flag != args.end();
    if (listVisibility) args.erase(flag);
    std::string sameAs;
    if (const auto at = std::find(args.begin(), args.end(), "--same-as");
        at != args.end() && at + 1 != args.end()) {
        sameAs = *(at + 1);
        args.erase(at, at + 2);
    }
    if (args.empty() || args.size() > 2) {
        std::fprintf(stderr,
                     "usage: %s results.json [expected-score] [--visibility] [--same-as OTHER]\n",
                     argv[0]);
        return 2;
    }
    std::ifstream in(args[0]);
    json r;
    try {
        r = json::parse(in);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: not JSON: %s\n", args[0].c_str(), e.what());
        return 1;
    }
    const std::vector<std::pair<std::string, std::string>> top = {
        {"score", "number"},
        {"execution_time", "number"},
        {"output", "string"},
        {"output_format", "format"},
        {"test_output_format", "format"},
        {"test_name_format", "format"},
        {"visibility", "visibility"},
        {"stdout_visibility", "visibility"},
        {"extra_data", "object"},
        {"tests", "array"},
        {"leaderboard", "array"}};
    const std::vector<std::pair<std::string, std::string>> test = {
        {"score", "number"},          {"max_score", "number"},     {"status", "status"},
        {"name", "string"},           {"name_format", "format"},   {"number", "string"},
        {"output", "string"},         {"output_format", "format"}, {"tags", "tags"},
        {"visibility", "visibility"}, {"extra_data", "object"}};
    auto validate = [](const std::string& where, const json& object,
                       const std::vector<std::pair<std::string, std::string>>& fields) {
        if (!object.is_object()) return problem(where, "must be an object");
        for (const auto& [key, value] : object.items()) {
            bool known = false;
            for (const auto& [name, type] : fields)
                if (key == name) {
                    known = true;
                    checkField(where + "." + key, value, type);
                }
            if (!known) problem(where + "." + key, "not a field of Gradescope's format");
        }
    };
    validate("results", r, top);
    double sum = 0;
    bool perTestScores = true;
    if (r.contains("tests") && r["tests"].is_array())
        for (size_t i = 0; i < r["tests"].size(); ++i) {
            const json& t = r["tests"][i];
            const std::string where = "tests[" + std::to_string(i) + "]";
            validate(where, t, test);
            if (!t.contains("score")) perTestScores = false;
            if (t.contains("score") && t["score"].is_number()) sum += t["score"].get<double>();
            if (t.contains("score") && t.contains("max_score") && t["score"].is_number() &&
                t["max_score"].is_number() &&
                (t["score"].get<double>() < 0 ||
                 t["score"].get<double>() > t["max_score"].get<double>() + 1e-9))
                problem(where, "score outside 0..max_score");
        }
    // "score": optional, but required if not on each test case.
    if (!r.contains("score") && !perTestScores)
        problem("results", "no score, and not every test has one");
    const double total = r.value("score", sum);
    if (std::abs(total - sum) > 1e-9 * std::max(1.0, std::abs(sum)))
        problem("results.score", std::to_string(total) + " is not the sum of the tests' scores " +
                                     std::to_string(sum));
    if (args.size() > 1 &&
        std::abs(total - std::stod(args[1])) > 1e-9 * std::max(1.0, std::abs(total)))
        problem("results.score", std::to_string(total) + ", expected " + args[1]);
    if (!sameAs.empty()) {
        std::ifstream otherIn(sameAs);
        json other;
        try {
            other = json::parse(otherIn);
        } catch (const std::exception& e) {
            problem(sameAs, std::string("not JSON: ") + e.what());
        }
        json mine = r;
        mine.erase("execution_time");
        other.erase("execution_time");
        // Every difference as a JSON patch operation, the value it would take shortened.
        for (const json& op : json::diff(other, mine))
            problem("--same-as " + sameAs,
                    op.value("op", std::string()) + " " + op.value("path", std::string()) +
                        (op.contains("value") ? ": " + op["value"].dump().substr(0, 160) : ""));
    }
    for (const std::string& p : problems)
        std::fprintf(stderr, "%s: %s\n", args[0].c_str(), p.c_str());
    std::printf("%.9g\n", total);
    if (listVisibility) {
        // Absent reads "(absent)": Gradescope's default would hide a missing field's meaning.
        auto visibility = [](const json& o) {
            return o.contains("visibility") && o["visibility"].is_string()
                       ? o["visibility"].get<std::string>()
                       : std::string("(absent)");
        };
        std::printf("(result): %s\n", visibility(r).c_str());
        if (r.contains("tests") && r["tests"].is_array())
            for (const json& t : r["tests"])
                std::printf("%s: %s\n", t.value("name", std::string("(no name)")).c_str(),
                            visibility(t).c_str());
    }
    return problems.empty() ? 0 : 1;
}
