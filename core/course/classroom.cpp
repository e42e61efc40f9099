#include "course/classroom.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "course/assignment.h"
#include "util/error.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

namespace {

// A YAML double-quoted scalar (JSON's string syntax is valid YAML).
std::string quoted(const std::string& text) {
    return json(text).dump();
}

// A step id as a GitHub Actions step id and the reporter's <ID>_RESULTS variable: letters,
// digits and '_', not starting with a digit (every contract id is already of that form).
void checkActionId(const std::string& id) {
    bool ok = !id.empty() && !std::isdigit(static_cast<unsigned char>(id[0]));
    for (char c : id) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
    if (!ok)
        throw Error("step \"" + id +
                    "\": not usable as a GitHub Actions step id (letters, digits, _)");
}

ClassroomStep stepOf(const ModuleRegistry& modules, const std::string& id, int points) {
    const LoadedModule& m = modules.find(id);  // throws listing the known ids
    checkActionId(id);
    return {id, m.desc->title, points};
}

int wholePoints(const json& value, const std::string& where) {
    if (!value.is_number() || value.get<double>() < 0 ||
        value.get<double>() != std::floor(value.get<double>()) || value.get<double>() > 1e6)
        throw Error(where +
                    ": must be a whole number >= 0 (GitHub Classroom's command grader reads "
                    "max-score as an integer)");
    return int(value.get<double>());
}

// GitHub's OWNER/NAME: the owner letters, digits and '-', the name also '.' and '_' (and not
// "." or ".."). Checked, as it is written into a shell command of the workflow.
void checkRepository(const std::string& repository) {
    if (repository.empty())
        throw Error(
            "classroom: pass --repository OWNER/NAME, the GitHub repository the workflow clones "
            "and builds pbrlab from (your course's fork or copy, e.g. --repository "
            "my-course/pbrlab)");
    const size_t slash = repository.find('/');
    const std::string owner = repository.substr(0, slash),
                      name = slash == std::string::npos ? "" : repository.substr(slash + 1);
    bool ok = !owner.empty() && !name.empty() && name != "." && name != "..";
    for (char c : owner) ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '-');
    for (char c : name)
        ok =
            ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.');
    if (!ok)
        throw Error("classroom: --repository " + quoted(repository) +
                    ": expected a GitHub repository as OWNER/NAME (e.g. my-course/pbrlab)");
}

}  // namespace

std::vector<ClassroomStep> assignmentSteps(const ModuleRegistry& modules, const fs::path& file) {
    const Assignment a = loadAssignment(file, stepIds(modules));  // validated, errors name fields
    std::vector<ClassroomStep> out;
    for (const std::string& id : a.steps)
        out.push_back(stepOf(modules, id,
                             wholePoints(json(a.points.at(id)), file.string() + ": points." + id)));
    return out;
}

std::vector<ClassroomStep> listedSteps(const ModuleRegistry& modules, const std::string& ids,
                                       int points) {
    if (points < 0) throw Error("--points: must be a whole number >= 0");
    std::vector<ClassroomStep> out;
    std::stringstream list(ids);
    for (std::string id; std::getline(list, id, ',');)
        if (!id.empty()) out.push_back(stepOf(modules, id, points));
    if (ids.empty())
        for (const auto& m : modules.modules()) out.push_back(stepOf(modules, m.desc->id, points));
    return out;
}

std::string classroomWorkflow(const ClassroomOptions& o) {
    checkRepository(o.pbrlabRepository);
    if (o.steps.empty()) throw Error("classroom: no steps to grade");
    std::ostringstream y;
    y << "# GitHub Classroom autograding for pbrlab, written by `pbrlab classroom`: one points "
         "row\n"
         "# per step (GitHub Classroom's command grader), then the reporter that sends them to\n"
         "# Classroom. Copy to .github/workflows/classroom.yml in the assignment template.\n"
         "#\n"
         "# This runs in the student's own repository: the student can edit this file and what\n"
         "# it runs, so its points are feedback, not a grade. Grade through Gradescope or\n"
         "# `pbrlab grade --batch` on a machine the students do not control (docs/grading.md).\n"
         "name: Autograding Tests\n"
         "\"on\":\n"
         "  - push\n"
         "  - workflow_dispatch\n"
         "  - repository_dispatch\n"
         "permissions:\n"
         "  checks: write\n"
         "  actions: read\n"
         "  contents: read\n"
         "jobs:\n"
         "  run-autograding-tests:\n"
         "    runs-on: ubuntu-22.04\n"
         "    if: github.actor != 'github-classroom[bot]'\n"
         "    steps:\n"
         "      - name: Checkout code\n"
         "        uses: actions/checkout@v4\n"
         "      - name: Install pbrlab\n"
         "        run: |\n"
         "          git clone --depth 1 https://github.com/"
      << o.pbrlabRepository
      << ".git \"$RUNNER_TEMP/pbrlab\"\n"
         "          bash \"$RUNNER_TEMP/pbrlab/scripts/install-deps.sh\"\n"
         "          cmake -S \"$RUNNER_TEMP/pbrlab\" -B \"$RUNNER_TEMP/build\" "
         "-DCMAKE_BUILD_TYPE=Release -DPBRLAB_BUILD_TESTS=OFF\n"
         "          cmake --build \"$RUNNER_TEMP/build\" -j 2\n"
         "          sudo cmake --install \"$RUNNER_TEMP/build\"\n";
    std::string runners;
    for (const ClassroomStep& s : o.steps) {
        const std::string name = s.id + ": " + s.title;
        y << "      - name: " << quoted(name) << "\n"
          << "        id: " << s.id << "\n"
          << "        uses: classroom-resources/autograding-command-grader@v1\n"
          << "        with:\n"
          << "          test-name: " << quoted(name) << "\n"
          << "          command: "
          << quoted("pbrlab grade . --steps " + s.id + " --fail-unless-passed") << "\n"
          << "          timeout: " << o.timeoutMinutes << "\n"
          << "          max-score: " << s.points << "\n";
        runners += (runners.empty() ? "" : ",") + s.id;
    }
    y << "      - name: Autograding Reporter\n"
         "        uses: classroom-resources/autograding-grading-reporter@v1\n"
         "        env:\n";
    for (const ClassroomStep& s : o.steps) {
        std::string upper = s.id;
        for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
        y << "          " << upper << "_RESULTS: \"${{steps." << s.id << ".outputs.result}}\"\n";
    }
    y << "        with:\n"
      << "          runners: " << runners << "\n";
    return y.str();
}

}  // namespace pbrlab
