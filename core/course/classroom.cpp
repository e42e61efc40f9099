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
// "." or ".."). Checked, as it names what the workflow builds.
void checkRepository(const std::string& repository) {
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

// A branch or tag name as git takes it (git check-ref-format's rules that matter here).
void checkRef(const std::string& ref) {
    bool ok = ref.empty() || (ref.find("..") == std::string::npos && ref[0] != '-' &&
                              ref[0] != '/' && ref.back() != '/' && ref.back() != '.');
    for (char c : ref)
        ok = ok && (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ||
                    c == '.' || c == '/');
    if (!ok)
        throw Error("classroom: --ref " + quoted(ref) +
                    ": expected a branch or tag name of the repository (e.g. v1.0)");
}

// An https URL of RFC 3986's characters: no space, quote, brace ("${{" would be an Actions
// expression) or backslash, whatever the instructor pastes.
void checkBundleUrl(const std::string& url) {
    const std::string scheme = "https://";
    bool ok = url.size() > scheme.size() && url.compare(0, scheme.size(), scheme) == 0;
    for (char c : url)
        ok = ok && (std::isalnum(static_cast<unsigned char>(c)) ||
                    std::string("-._~:/?#[]@!$&'()*+,;=%").find(c) != std::string::npos);
    if (!ok)
        throw Error("classroom: --bundle-url " + quoted(url) +
                    ": expected the https URL of the grader bundle (a .tar.gz, e.g. a release "
                    "asset https://github.com/OWNER/NAME/releases/download/TAG/FILE.tar.gz)");
}

// How the job gets pbrlab, checked: the bundle when a URL is given, else the source.
void checkSource(const ClassroomOptions& o, bool needRepository) {
    if (!o.bundleUrl.empty()) checkBundleUrl(o.bundleUrl);
    if (o.pbrlabRepository.empty() && (needRepository || o.bundleUrl.empty()))
        throw Error(
            std::string("classroom: ") +
            (needRepository ? "--pages builds the site from pbrlab's source: pass "
                            : "pass --bundle-url URL, the grader bundle the workflow installs, "
                              "or ") +
            "--repository OWNER/NAME, the GitHub repository of pbrlab's source (your course's "
            "fork or copy, e.g. --repository my-course/pbrlab)");
    if (!o.pbrlabRepository.empty()) checkRepository(o.pbrlabRepository);
    checkRef(o.pbrlabRef);
}

// Caches are restored and saved by separate steps: Classroom's reporter fails the job whenever a
// test fails, and actions/cache's own save runs only after a job that succeeded, so a class whose
// students have not yet passed every step would never save one. Keys name pbrlab's version
// (steps.pbrlab.outputs.version): a cache entry is written once and never goes stale.
void cacheStep(std::ostream& y, const std::string& verb, const std::string& name,
               const std::string& id, const std::string& condition, const std::string& path,
               const std::string& key) {
    y << "      - name: " << name << "\n";
    if (!id.empty()) y << "        id: " << id << "\n";
    if (!condition.empty()) y << "        if: " << condition << "\n";
    y << "        uses: actions/cache/" << verb << "@v4\n"
      << "        with:\n"
      << "          path: " << path << "\n"
      << "          key: " << key << "-${{ steps.pbrlab.outputs.version }}\n";
}

// The steps that check out the repository the workflow runs in and put pbrlab on PATH, at a
// job's step indentation; the step with id "pbrlab" outputs its version. From the grader bundle:
// a download, on the runner as it is (the bundle needs glibc >= 2.35; GitHub's ubuntu-latest
// has it), the version its checksum. From source: the job runs in a debian:bookworm container
// (jobHeader), as scripts/install-deps.sh installs Debian 12's packages; the version is the
// commit, and the Debian package built from it is cached, so that later runs install it with
// only its run-time dependencies.
void installSteps(std::ostream& y, const ClassroomOptions& o, bool fromSource) {
    if (!fromSource) {
        y << "      - name: Checkout code\n"
             "        uses: actions/checkout@v4\n"
             "      - name: Install pbrlab (the grader bundle)\n"
             "        id: pbrlab\n"
             "        env:\n"
             "          PBRLAB_BUNDLE_URL: "
          << quoted(o.bundleUrl)
          << "\n"
             "        run: |\n"
             "          curl -fsSL --retry 3 -o \"$RUNNER_TEMP/pbrlab.tar.gz\" "
             "\"$PBRLAB_BUNDLE_URL\"\n"
             "          mkdir -p \"$RUNNER_TEMP/pbrlab\"\n"
             "          tar -xzf \"$RUNNER_TEMP/pbrlab.tar.gz\" -C \"$RUNNER_TEMP/pbrlab\" "
             "--strip-components=1\n"
             "          \"$RUNNER_TEMP/pbrlab/bin/pbrlab\" list > /dev/null\n"
             "          echo \"$RUNNER_TEMP/pbrlab/bin\" >> \"$GITHUB_PATH\"\n"
             "          echo \"version=$(sha256sum \"$RUNNER_TEMP/pbrlab.tar.gz\" | cut -c1-16)\" "
             ">> \"$GITHUB_OUTPUT\"\n";
        return;
    }
    y << "      - name: Fetch pbrlab's source\n"
         "        id: pbrlab\n"
         "        env:\n"
         "          PBRLAB_SOURCE: "
      << quoted("https://github.com/" + o.pbrlabRepository + ".git")
      << "\n"
         "          PBRLAB_REF: "
      << quoted(o.pbrlabRef.empty() ? "HEAD" : o.pbrlabRef)
      << "\n"
         "        run: |\n"
         "          apt-get update -qq\n"
         "          apt-get install -y -qq --no-install-recommends git ca-certificates\n"
         "          git init -q /opt/pbrlab/src\n"
         "          git -C /opt/pbrlab/src fetch -q --depth 1 \"$PBRLAB_SOURCE\" \"$PBRLAB_REF\"\n"
         "          git -C /opt/pbrlab/src checkout -q FETCH_HEAD\n"
         "          echo \"version=$(git -C /opt/pbrlab/src rev-parse HEAD)\" >> "
         "\"$GITHUB_OUTPUT\"\n"
         "      - name: Checkout code\n"
         "        uses: actions/checkout@v4\n";
    cacheStep(y, "restore", "Restore pbrlab's Debian package", "deb", "", "/opt/pbrlab/deb",
              "pbrlab-deb-bookworm");
    y << "      - name: Install pbrlab\n"
         "        run: |\n"
         "          if ! compgen -G \"/opt/pbrlab/deb/pbrlab_*.deb\" > /dev/null; then\n"
         "            bash /opt/pbrlab/src/scripts/install-deps.sh\n"
         "            cmake -S /opt/pbrlab/src -B /opt/pbrlab/build -DCMAKE_BUILD_TYPE=Release \\\n"
         "              -DPBRLAB_BUILD_TESTS=OFF -DPBRLAB_BUILD_BENCHMARKS=OFF\n"
         "            cmake --build /opt/pbrlab/build -j \"$(nproc)\"\n"
         "            (cd /opt/pbrlab/build && cpack -G DEB)\n"
         "            mkdir -p /opt/pbrlab/deb\n"
         "            cp /opt/pbrlab/build/pbrlab_*.deb /opt/pbrlab/deb/\n"
         "          fi\n"
         "          apt-get install -y -qq --no-install-recommends /opt/pbrlab/deb/pbrlab_*.deb\n"
         "          pbrlab list > /dev/null\n";
    cacheStep(y, "save", "Save pbrlab's Debian package", "",
              "steps.deb.outputs.cache-hit != 'true'", "/opt/pbrlab/deb", "pbrlab-deb-bookworm");
}

// A job's lines from runs-on to its steps, for one that builds from source or not.
void jobHeader(std::ostream& y, bool inContainer, const std::string& condition) {
    y << "    runs-on: ubuntu-latest\n";
    if (inContainer)
        y << "    container: debian:bookworm\n"
             "    env:\n"
             "      DEBIAN_FRONTEND: noninteractive\n"
             "    defaults:\n"
             "      run:\n"
             "        shell: bash\n";
    y << "    if: " << condition << "\n"
      << "    steps:\n";
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
    checkSource(o, false);
    if (o.steps.empty()) throw Error("classroom: no steps to grade");
    const bool fromSource = o.bundleUrl.empty();
    std::ostringstream y;
    y << "# GitHub Classroom autograding for pbrlab, written by `pbrlab classroom`: one points "
         "row\n"
         "# per step (GitHub Classroom's command grader), then the reporter that sends them to\n"
         "# Classroom. Copy to .github/workflows/classroom.yml in the assignment template.\n"
      << (fromSource
              ? "# pbrlab is built from source in a debian:bookworm container (its Debian package\n"
                "# cached per commit of pbrlab); `pbrlab classroom --bundle-url URL` installs the\n"
                "# grader bundle instead (docs/assignment.md).\n"
              : "# pbrlab is the grader bundle, downloaded (docs/assignment.md).\n")
      << "#\n"
         "# This runs in the student's own repository: the student can edit this file and what\n"
         "# it runs, so its points are feedback, not a grade. Grade through Gradescope or\n"
         "# `pbrlab grade --batch` on a machine the students do not control (docs/grading.md).\n"
         "name: Autograding Tests\n"
         // The events as a mapping: the list form means the same to GitHub, but the workflow
         // schema test's parser reads `repository_dispatch` in a list as another event's name.
         "\"on\":\n"
         "  push:\n"
         "  workflow_dispatch:\n"
         "  repository_dispatch:\n"
         "permissions:\n"
         "  checks: write\n"
         "  actions: read\n"
         "  contents: read\n"
         "jobs:\n"
         "  run-autograding-tests:\n";
    jobHeader(y, fromSource, "github.actor != 'github-classroom[bot]'");
    installSteps(y, o, fromSource);
    // pbrlab's own cache, keyed by its build: most of a grade from a cold cache is the
    // reference's renders and maps, which are the same on every push.
    cacheStep(y, "restore", "Restore pbrlab's grading cache", "grading-cache", "",
              "~/.cache/pbrlab", "pbrlab-grading");
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
    cacheStep(y, "save", "Save pbrlab's grading cache", "",
              "always() && steps.grading-cache.outputs.cache-hit != 'true'", "~/.cache/pbrlab",
              "pbrlab-grading");
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

std::string pagesWorkflow(const ClassroomOptions& o) {
    checkSource(o, true);
    std::ostringstream y;
    y << "# The course's pbrlab site on GitHub Pages, written by `pbrlab classroom --pages`: the\n"
         "# lab in the browser for the assignment in "
      << kPagesAssignmentPath
      << ",\n"
         "# with the steps released by the day it runs and no solution the assignment has not\n"
         "# released (docs/web.md). Copy to .github/workflows/pages.yml in the assignment\n"
         "# template; it runs there only, on a push to the default branch or from the Actions\n"
         "# tab (run it again on each release date), never in the students' copies.\n"
         "name: Course site\n"
         "\"on\":\n"
         "  push:\n"
         "  workflow_dispatch:\n"
         "permissions:\n"
         "  contents: read\n"
         "concurrency:\n"
         "  group: pages\n"
         "  cancel-in-progress: false\n"
         "jobs:\n"
         "  build:\n";
    // The students' repositories are made from the template and are not templates themselves.
    jobHeader(y, true,
              "github.event.repository.is_template && github.ref_name == "
              "github.event.repository.default_branch");
    installSteps(y, o, true);  // the site needs pbrlab's source: never the bundle
    y << "      - name: Build the site\n"
         "        run: |\n"
         "          bash /opt/pbrlab/src/scripts/build-web.sh /opt/pbrlab/web \\\n"
         "            --assignment \"$GITHUB_WORKSPACE/"
      << kPagesAssignmentPath
      << "\" --pbrlab /usr/bin/pbrlab\n"
         "      - name: Upload the site\n"
         "        uses: actions/upload-pages-artifact@v3\n"
         "        with:\n"
         "          path: /opt/pbrlab/web/assignment-site\n"
         "  deploy:\n"
         "    needs: build\n"
         "    runs-on: ubuntu-latest\n"
         "    permissions:\n"
         "      pages: write\n"
         "      id-token: write\n"
         "    environment:\n"
         "      name: github-pages\n"
         "      url: ${{ steps.deployment.outputs.page_url }}\n"
         "    steps:\n"
         "      - name: Deploy to GitHub Pages\n"
         "        id: deployment\n"
         "        uses: actions/deploy-pages@v4\n";
    return y.str();
}

}  // namespace pbrlab
