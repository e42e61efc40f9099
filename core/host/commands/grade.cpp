// The commands about grading: grade, kit, mutants, new-step.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>

#include "course/autograder.h"
#include "course/batch.h"
#include "course/classroom.h"
#include "course/gradescope.h"
#include "course/kit.h"
#include "course/mutation_score.h"
#include "session.h"
#include "steps/contract.h"
#include "steps/new_step.h"
#include "table.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

int defaultJobs() {
    return usableCpus();
}

class GradeCommand : public Command {
public:
    GradeCommand()
        : Command("grade",
                  "Grade a submission folder: every module isolated, stepwise; exit 0 when "
                  "grading ran, whatever the score (unless --fail-unless-passed)") {
        options_.jobs = defaultJobs();
    }
    void declare(CLI::App& cmd) override {
        // Positional as in `pbrlab grade kit/`, or --submission as in every other command.
        cmd.add_option("submission,--submission", options_.submission,
                       "Folder with <id>.glsl files");
        cmd.add_option("--batch", batchDir_,
                       "Grade every sub-folder of this folder (one submission each)");
        cmd.add_option("--out", batchOut_, "With --batch or --merge: where the reports go");
        cmd.add_option("--shard", batchShard_,
                       "With --batch: grade only shard I of N (I/N, 0-based, by name)");
        cmd.add_option("--merge", mergeDirs_,
                       "Merge the outputs of --batch --shard runs into one class report");
        cmd.add_flag("--fail-unless-passed", failUnlessPassed_,
                     "Exit 1 unless every graded step passed (a CI points row per step)");
        cmd.add_option("--steps", options_.modules,
                       "Step ids, comma-separated or repeated (default: all)")
            ->delimiter(',');
        cmd.add_option("--json", jsonFile_, "Write pbrlab's JSON report here");
        cmd.add_option("--gradescope", gradescopeFile_, "Write Gradescope's results.json here");
        cmd.add_option("--html", options_.html, "Write an HTML report with images here");
        cmd.add_flag("--cumulative", options_.cumulative, help::cumulative);
        timeoutOption_ = cmd.add_option("--timeout", options_.timeoutSeconds,
                                        "Seconds per module (60; given, it wins over the "
                                        "assignment's time_limit_seconds)");
        cmd.add_option("--jobs", options_.jobs,
                       "Grading processes at once (default: one per core, or per core of a CPU "
                       "quota; --batch shares them between submissions)");
        cmd.add_option("--time-budget", options_.budgetSeconds,
                       "Seconds for the whole submission: steps unfinished then score 0 and "
                       "say so (run_autograder: within Gradescope's timeout)");
        cmd.add_option("--seed", options_.settings.seed,
                       "Seed of the random domain points (default 1: instructors may keep "
                       "their own)");
        cmd.add_option("--sun-environment", options_.settings.sunEnvironment, help::sunEnvironment);
        cmd.add_option("--assignment", assignmentFile_,
                       "Grade by this assignment file: its steps, points, partial credit and "
                       "time limit (docs/assignment.md)");
    }
    int run(const GlobalOptions& global) override {
        std::erase(options_.modules, std::string());  // "--steps a,,b"
        if (!mergeDirs_.empty()) return merge();
        return batchDir_.empty() ? gradeOne(global) : gradeClass(global);
    }

private:
    int gradeOne(const GlobalOptions& global) {
        if (options_.submission.empty())
            throw Error("grade: give a SUBMISSION folder, or --batch DIR --out DIR");
        Session session(global, false);  // no GL in the parent: each module forks its own
        const double timeout = options_.timeoutSeconds;
        const auto assignment = gradeAssignment(assignmentFile_, *session.modules, options_);
        if (timeoutOption_->count() > 0) options_.timeoutSeconds = timeout;
        if (!fs::is_directory(options_.submission))
            throw Error(options_.submission.string() + ": not a directory");
        options_.submission = fs::canonical(options_.submission);
        GradeReport report = gradeSubmission(*session.modules, session.paths, options_);
        // The points as every report has them (formatPoints: the micro-point, no rounding
        // of its own).
        for (const auto& g : report.modules)
            std::printf("%-12s %-14s %8s / %-8s %s\n", g.id.c_str(),
                        std::string(nameOf(g.status)).c_str(), formatPoints(g.score).c_str(),
                        formatPoints(g.maxScore).c_str(), g.message.substr(0, 160).c_str());
        std::printf("total %s / %s in %.1f s\n", formatPoints(report.score).c_str(),
                    formatPoints(report.maxScore).c_str(), report.seconds);
        if (!jsonFile_.empty()) writeFileAtomically(jsonFile_, jsonText(toJson(report)));
        if (!gradescopeFile_.empty())
            writeFileAtomically(gradescopeFile_, jsonText(gradescopeResults(report, assignment)));
        if (!options_.html.empty()) writeHtml(report, options_.html);
        if (failUnlessPassed_)
            for (const auto& g : report.modules)
                if (g.status != GradeStatus::Passed) return 1;
        return 0;
    }

    int merge() {
        if (batchOut_.empty()) throw Error("--merge needs --out DIR for the class report");
        mergeBatches({mergeDirs_.begin(), mergeDirs_.end()}, batchOut_);
        std::cout << "wrote " << (fs::path(batchOut_) / "class.html").string() << "\n";
        return 0;
    }

    int gradeClass(const GlobalOptions& global) {
        Session session(global, false);
        BatchOptions batch;
        batch.batch = batchDir_;
        batch.out = batchOut_;
        const double timeout = options_.timeoutSeconds;
        batch.assignment = gradeAssignment(assignmentFile_, *session.modules, options_);
        if (timeoutOption_->count() > 0) options_.timeoutSeconds = timeout;
        batch.grade = options_;
        if (!batchShard_.empty()) std::tie(batch.shard, batch.shards) = parseShard(batchShard_);
        BatchSummary done = gradeBatch(*session.modules, session.paths, batch);
        std::cout << done.students << " submissions: " << done.graded << " graded, " << done.skipped
                  << " unchanged, " << done.errors << " not graded; "
                  << (fs::path(batchOut_) / "class.html").string() << "\n";
        return 0;
    }

    GradeOptions options_;
    CLI::Option* timeoutOption_ = nullptr;
    std::string batchDir_, batchOut_, jsonFile_, gradescopeFile_, batchShard_, assignmentFile_;
    std::vector<std::string> mergeDirs_;
    bool failUnlessPassed_ = false;
};

class ClassroomCommand : public Command {
public:
    ClassroomCommand()
        : Command("classroom",
                  "Write .github/workflows/classroom.yml: GitHub Classroom's command grader, one "
                  "points row per step (student-controlled feedback, not a grade); --pages: "
                  "and pages.yml, the course's site on GitHub Pages") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("--assignment", assignment_, "Steps and points from this assignment.json");
        cmd.add_option("--steps", steps_,
                       "Without --assignment: comma-separated step ids (default: all)");
        cmd.add_option("--points", points_,
                       "Without --assignment: whole points per step (default 1)");
        cmd.add_option("--bundle-url", classroom_.bundleUrl,
                       "https URL of the grader bundle (.tar.gz, a top folder with bin/pbrlab) "
                       "that the workflow downloads instead of building pbrlab");
        cmd.add_option("--repository", classroom_.pbrlabRepository,
                       "GitHub repository of pbrlab's source (OWNER/NAME, e.g. "
                       "my-course/pbrlab), built in a debian:bookworm container: required "
                       "without --bundle-url, and with --pages");
        cmd.add_option("--ref", classroom_.pbrlabRef,
                       "Branch or tag of --repository to build (default: its default branch)");
        cmd.add_flag("--pages", pages_,
                     "Also write .github/workflows/pages.yml, which publishes the course's site "
                     "(needs --assignment, copied to " +
                         std::string(kPagesAssignmentPath) + ")");
        cmd.add_option("--out", out_, "Folder that gets .github/workflows/classroom.yml")
            ->required();
    }
    int run(const GlobalOptions& global) override {
        Session session(global, false);
        if (pages_ && assignment_.empty())
            throw Error(
                "classroom --pages: pass --assignment FILE; the site withholds the solutions "
                "that assignment has not released (a site without one carries every solution)");
        classroom_.steps = assignment_.empty() ? listedSteps(*session.modules, steps_, points_)
                                               : assignmentSteps(*session.modules, assignment_);
        // Both texts first: nothing is written when either is refused.
        const std::string classroom = classroomWorkflow(classroom_),
                          pages = pages_ ? pagesWorkflow(classroom_) : "";
        const fs::path workflows = fs::path(out_) / ".github/workflows";
        writeFileAtomically(workflows / "classroom.yml", classroom);
        std::cout << "wrote " << (workflows / "classroom.yml").string() << " ("
                  << classroom_.steps.size() << " steps, pbrlab "
                  << (classroom_.bundleUrl.empty() ? "built from " + classroom_.pbrlabRepository
                                                   : "from the grader bundle")
                  << ")\n";
        if (pages_) {
            writeFileAtomically(workflows / "pages.yml", pages);
            const fs::path copy = fs::path(out_) / kPagesAssignmentPath;
            fs::create_directories(copy.parent_path());
            fs::copy_file(assignment_, copy, fs::copy_options::overwrite_existing);
            std::cout << "wrote " << (workflows / "pages.yml").string() << " and "
                      << (fs::path(out_) / kPagesAssignmentPath).string() << "\n";
        }
        return 0;
    }

private:
    ClassroomOptions classroom_;
    std::string assignment_, steps_, out_;
    int points_ = 1;
    bool pages_ = false;
};

class KitCommand : public Command {
public:
    KitCommand() : Command("kit", "Write the student kit (stubs, handouts, README)") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("--out", kit_.out, "Output folder")->required();
        cmd.add_flag("--with-solutions", kit_.withSolutions,
                     "Write the reference solutions instead of stubs (instructors, tests)");
        cmd.add_option("--release-through", kit_.releaseThrough,
                       "Give the solutions of the steps up to this id (after due dates)");
        cmd.add_flag("--force", kit_.force, "Write into a non-empty folder");
        cmd.add_option("--assignment", assignment_,
                       "Only the assignment's steps released by --date (docs/assignment.md)");
        cmd.add_option("--date", date_, "With --assignment: YYYY-MM-DD (default: today, UTC)");
        cmd.add_flag("--site-steps", siteSteps_,
                     "Write the step folders of the browser site for these steps instead, "
                     "without the solutions the kit does not give (web/, docs/web.md)");
    }
    int run(const GlobalOptions& global) override {
        Session session(global, false);
        if (!assignment_.empty())
            applyAssignment(loadAssignment(assignment_, stepIds(*session.modules)),
                            date_.empty() ? todayUtc() : date_, kit_);
        else if (!date_.empty())
            throw Error("kit: --date goes with --assignment");
        if (siteSteps_) {
            const std::vector<std::string> withheld = writeSiteSteps(*session.modules, kit_);
            std::string ids;
            for (const std::string& id : withheld) ids += (ids.empty() ? "" : ", ") + id;
            std::cout << "wrote the site's step folders to " << kit_.out.string()
                      << "; solutions withheld: " << (ids.empty() ? "none" : ids) << "\n";
            return 0;
        }
        int n = writeKit(*session.modules, kit_);
        std::cout << "wrote " << n << " module files and handouts to " << kit_.out.string() << "\n";
        return 0;
    }

private:
    KitOptions kit_;
    std::string assignment_, date_;
    bool siteSteps_ = false;
};

class AutograderCommand : public Command {
public:
    AutograderCommand()
        : Command("autograder",
                  "Write Gradescope's autograder.zip: setup.sh, run_autograder, the assignment "
                  "and the grader bundle (docs/assignment.md)") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("--assignment", options_.assignment, "The assignment file")->required();
        cmd.add_option("--out", options_.out, "Folder for autograder.zip")->required();
        cmd.add_option("--bundle", options_.bundle,
                       "The grader bundle (default: the one this pbrlab runs from, else "
                       "grader-bundle/ beside it: scripts/grader-bundle.sh)");
        cmd.add_option("--gradescope-timeout", options_.gradescopeTimeoutSeconds,
                       "The assignment's autograder timeout on Gradescope in seconds (600, "
                       "Gradescope's default): grading stops in time to write results.json");
    }
    int run(const GlobalOptions& global) override {
        Session session(global, false);
        const fs::path zip = writeAutograderBundle(options_, *session.modules);
        std::cout << "wrote " << zip.string() << " (" << fs::file_size(zip)
                  << " bytes): upload it as the autograder of a Gradescope programming "
                     "assignment\n";
        return 0;
    }

private:
    AutograderOptions options_;
};

// The mutation score: every mutant of each reference solution graded as a submission.
class MutantsCommand : public Command {
public:
    MutantsCommand()
        : Command("mutants",
                  "Mutation score: grade mechanical and semantic mutants of each reference "
                  "solution as submissions; exit 1 when one that is not equivalent survives") {
        options_.jobs = defaultJobs();
    }
    void declare(CLI::App& cmd) override {
        cmd.add_option("steps", options_.modules, help::steps);
        cmd.add_option("--json", jsonFile_, "Write every mutant's outcome here");
        cmd.add_option("--kind", kind_,
                       "mechanical (one token changed), semantic (a change of meaning: "
                       "nonlinear reads, capped counts, fewer bits, hard-coded host values) or "
                       "all (default)")
            ->check(CLI::IsMember({"all", "mechanical", "semantic"}));
        cmd.add_option("--every", options_.every,
                       "Grade every n-th mutant of each kind only (default 1)");
        cmd.add_option("--jobs", options_.jobs, "Mutants graded at once (default: cores)");
        cmd.add_flag("--feedback", options_.feedback,
                     "Grade fully and count the mutants whose mistake the feedback names");
    }
    int run(const GlobalOptions& global) override {
        Session session(global, false);  // no GL here: the grades fork, the comparisons too
        options_.every = std::max(options_.every, 1);
        options_.mechanical = kind_ != "semantic";
        options_.semantic = kind_ != "mechanical";
        options_.progress = [](const std::string& line) { std::cerr << line << "\n"; };
        const bool feedback = options_.feedback;
        const auto start = std::chrono::steady_clock::now();
        const std::vector<ModuleMutation> result =
            runMutants(*session.modules, session.paths, options_);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf(
            "| step | kind | mutants | do not compile | killed | survived: equivalent | "
            "survived: NOT equivalent |%s seconds |\n",
            feedback ? " mistake named |" : "");
        std::printf("|---|---|---|---|---|---|---|%s---|\n", feedback ? "---|" : "");
        // One row per step and kind, then the totals of each kind.
        struct Row {
            size_t made = 0;
            int stillborn = 0, killed = 0, equivalent = 0, notEquivalent = 0;
            int byPattern = 0, byAny = 0, failed = 0;
            double seconds = 0;
        };
        auto print = [&](const std::string& step, const std::string& kind, const Row& x) {
            std::string named;
            if (feedback)
                named = " " + std::to_string(x.byPattern) + " / " + std::to_string(x.byAny) +
                        " of " + std::to_string(x.failed) + " |";
            std::printf("| %s | %s | %zu | %d | %d | %d | %d |%s %.0f |\n", step.c_str(),
                        kind.c_str(), x.made, x.stillborn, x.killed, x.equivalent, x.notEquivalent,
                        named.c_str(), x.seconds);
        };
        std::map<std::string, Row> totals;
        int bad = 0;
        for (const ModuleMutation& r : result) {
            Row x;
            x.made = r.mutants.size();
            x.stillborn = r.count(MutantStatus::Stillborn);
            x.killed = r.count(MutantStatus::Killed) + r.count(MutantStatus::Timeout) +
                       r.count(MutantStatus::Crashed);
            x.notEquivalent = r.nonEquivalentSurvivors();
            x.equivalent = r.count(MutantStatus::Survived) - x.notEquivalent;
            x.seconds = r.seconds;
            for (const MutantOutcome& m : r.mutants)
                if (m.status == MutantStatus::Killed)
                    ++x.failed, x.byAny += !m.mistake.empty(),
                        x.byPattern += m.namedBy == NamedBy::Pattern;
            bad += x.notEquivalent;
            if (x.made > 0) print(r.id, r.kind, x);  // (a family that fits nowhere in a step)
            Row& t = totals[r.kind];
            t.made += x.made, t.stillborn += x.stillborn, t.killed += x.killed;
            t.equivalent += x.equivalent, t.notEquivalent += x.notEquivalent;
            t.byPattern += x.byPattern, t.byAny += x.byAny, t.failed += x.failed;
            t.seconds += x.seconds;
        }
        for (const auto& [kind, t] : totals) print("**all**", kind, t);
        for (const ModuleMutation& r : result)
            for (const MutantOutcome& x : r.mutants)
                if (x.status == MutantStatus::Survived)
                    std::printf("%s %s [%s] %s\n    %s\n", r.id.c_str(),
                                x.equivalence == "equivalent" ? "equivalent" : "SURVIVOR",
                                x.mutant.family.c_str(), x.mutant.description.c_str(),
                                x.evidence.c_str());
        std::printf("%d non-equivalent survivors; %.0f s\n", bad, seconds);
        if (!jsonFile_.empty()) writeFileAtomically(jsonFile_, jsonText(toJson(result)));
        return bad ? 1 : 0;
    }

private:
    MutationOptions options_;
    std::string kind_ = "all";
    std::string jsonFile_;
};

class NewStepCommand : public Command {
public:
    NewStepCommand()
        : Command("new-step",
                  "Write a step folder to build outside the source tree (find_package(pbrlab))") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("step", options_.id, "The step's id: the student's file is <id>.glsl")
            ->required();
        cmd.add_option("--out", options_.out, "Folder for CMakeLists.txt and <id>/")->required();
        cmd.add_option("--lab", options_.lab, "Its lab (default: the lab of the step before it)");
        cmd.add_option("--order", options_.order,
                       "Its order key: between two steps' keys to insert it there (default: "
                       "after the last; `pbrlab list --order` shows them)");
    }
    int run(const GlobalOptions& global) override {
        for (const fs::path& dir : modulesDirs(global)) addStepRoot(dir);
        writeStepTemplate(options_);
        const fs::path build = options_.out / "build";
        std::cout << "wrote " << (options_.out / options_.id).string() << "/ and "
                  << (options_.out / "CMakeLists.txt").string() << "\nbuild: cmake -S "
                  << options_.out.string() << " -B " << build.string()
                  << " -DCMAKE_PREFIX_PATH=<pbrlab's install prefix> && cmake --build "
                  << build.string() << "\nuse:   pbrlab --modules " << (build / "modules").string()
                  << " list\n";
        return 0;
    }

private:
    NewStepOptions options_;
};

}  // namespace

std::unique_ptr<Command> gradeCommand() {
    return std::make_unique<GradeCommand>();
}
std::unique_ptr<Command> classroomCommand() {
    return std::make_unique<ClassroomCommand>();
}

std::unique_ptr<Command> autograderCommand() {
    return std::make_unique<AutograderCommand>();
}

std::unique_ptr<Command> kitCommand() {
    return std::make_unique<KitCommand>();
}
std::unique_ptr<Command> mutantsCommand() {
    return std::make_unique<MutantsCommand>();
}
std::unique_ptr<Command> newStepCommand() {
    return std::make_unique<NewStepCommand>();
}

}  // namespace pbrlab
