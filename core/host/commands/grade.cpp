// The commands about grading: grade, kit, mutants, new-step.
#include "grade.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <thread>

#include "kit.h"
#include "mutation.h"
#include "new_step.h"
#include "pbrlab/contract.h"
#include "pbrlab/error.h"
#include "session.h"
#include "table.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

int defaultJobs() {
    return int(std::max(1u, std::thread::hardware_concurrency()));
}

class GradeCommand : public Command {
public:
    GradeCommand()
        : Command("grade",
                  "Grade a submission folder: every module isolated, stepwise; exit 0 when "
                  "grading ran, whatever the score") {
        options_.jobs = defaultJobs();
    }
    void declare(CLI::App& cmd) override {
        // Positional as in `pbrlab grade kit/`, or --submission as in every other command.
        cmd.add_option("submission,--submission", options_.submission,
                       "Folder with <id>.glsl files");
        cmd.add_option("--batch", batchDir_,
                       "Grade every sub-folder of this folder (one submission each)");
        cmd.add_option("--out", batchOut_, "With --batch: where the reports go");
        cmd.add_option("--steps", options_.modules,
                       "Step ids, comma-separated or repeated (default: all)")
            ->delimiter(',');
        cmd.add_option("--json", jsonFile_, "Write pbrlab's JSON report here");
        cmd.add_option("--gradescope", gradescopeFile_, "Write Gradescope's results.json here");
        cmd.add_option("--html", options_.html, "Write an HTML report with images here");
        cmd.add_flag("--cumulative", options_.cumulative, help::cumulative);
        cmd.add_option("--timeout", options_.timeoutSeconds, "Seconds per module (60)");
        cmd.add_option("--jobs", options_.jobs, "Modules graded at once (default: one per core)");
        cmd.add_option("--seed", options_.settings.seed,
                       "Seed of the random domain points (default 1: instructors may keep "
                       "their own)");
    }
    int run(const GlobalOptions& global) override {
        std::erase(options_.modules, std::string());  // "--steps a,,b"
        return batchDir_.empty() ? gradeOne(global) : gradeBatch(global);
    }

private:
    int gradeOne(const GlobalOptions& global) {
        if (options_.submission.empty())
            throw Error("grade: give a SUBMISSION folder, or --batch DIR --out DIR");
        Session session(global, false);  // no GL in the parent: each module forks its own
        if (!fs::is_directory(options_.submission))
            throw Error(options_.submission.string() + ": not a directory");
        options_.submission = fs::canonical(options_.submission);
        GradeReport report = gradeSubmission(*session.modules, session.paths, options_);
        for (const auto& g : report.modules)
            std::printf("%-12s %-14s %4.1f / %-4.1f %s\n", g.id.c_str(), g.status.c_str(), g.score,
                        g.maxScore, g.message.substr(0, 160).c_str());
        std::printf("total %.1f / %.1f in %.1f s\n", report.score, report.maxScore, report.seconds);
        if (!jsonFile_.empty()) writeFileAtomically(jsonFile_, jsonText(toJson(report)));
        if (!gradescopeFile_.empty())
            writeFileAtomically(gradescopeFile_, jsonText(toGradescope(report)));
        if (!options_.html.empty()) writeHtml(report, options_.html);
        return 0;
    }

    int gradeBatch(const GlobalOptions& global) {
        Session session(global, false);
        if (batchOut_.empty()) throw Error("--batch needs --out DIR for the reports");
        std::vector<fs::path> subs;
        for (const auto& e : fs::directory_iterator(batchDir_)) {
            std::error_code ec;
            if (e.is_directory(ec)) subs.push_back(e.path());
        }
        std::sort(subs.begin(), subs.end());
        fs::create_directories(batchOut_);
        std::string table = "submission,score,max_score,seconds\n";
        for (size_t i = 0; i < subs.size(); ++i) {
            // A progress bar on stderr: [#####.....] 5/10 name
            const int width = 30;
            int filled = int(width * i / std::max<size_t>(subs.size(), 1));
            std::cerr << "\r[" << std::string(size_t(filled), '#')
                      << std::string(size_t(width - filled), '.') << "] " << i << "/" << subs.size()
                      << " " << subs[i].filename().string() << "   " << std::flush;
            GradeOptions each = options_;
            fs::path out = fs::path(batchOut_) / subs[i].filename();
            each.html = out / "html";
            try {
                each.submission = fs::canonical(subs[i]);
                GradeReport report = gradeSubmission(*session.modules, session.paths, each);
                writeFileAtomically(out / "report.json", jsonText(toJson(report)));
                writeFileAtomically(out / "results.json", jsonText(toGradescope(report)));
                writeHtml(report, each.html);
                table += subs[i].filename().string() + "," + std::to_string(report.score) + "," +
                         std::to_string(report.maxScore) + "," + std::to_string(report.seconds) +
                         "\n";
            } catch (const std::exception& e) {
                // One unreadable submission folder stops nothing: it is listed with why.
                std::cerr << "\nerror: " << subs[i].string() << ": " << e.what() << "\n";
                table += subs[i].filename().string() + ",0,0,0\n";
            }
        }
        std::cerr << "\r[" << std::string(30, '#') << "] " << subs.size() << "/" << subs.size()
                  << " done" << std::string(20, ' ') << "\n";
        writeFileAtomically(fs::path(batchOut_) / "summary.csv", table);
        std::cout << table;
        return 0;
    }

    GradeOptions options_;
    std::string batchDir_, batchOut_, jsonFile_, gradescopeFile_;
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
    }
    int run(const GlobalOptions& global) override {
        Session session(global, false);
        int n = writeKit(*session.modules, kit_);
        std::cout << "wrote " << n << " module files and handouts to " << kit_.out.string() << "\n";
        return 0;
    }

private:
    KitOptions kit_;
};

// The mutation score: every mutant of each reference solution graded as a submission.
class MutantsCommand : public Command {
public:
    MutantsCommand()
        : Command("mutants",
                  "Mutation score: grade mechanical mutants of each reference solution as "
                  "submissions; exit 1 when one that is not equivalent survives") {
        options_.jobs = defaultJobs();
    }
    void declare(CLI::App& cmd) override {
        cmd.add_option("steps", options_.modules, help::steps);
        cmd.add_option("--json", jsonFile_, "Write every mutant's outcome here");
        cmd.add_option("--every", options_.every, "Grade every n-th mutant only (default 1)");
        cmd.add_option("--jobs", options_.jobs, "Mutants graded at once (default: cores)");
        cmd.add_flag("--feedback", options_.feedback,
                     "Grade fully and count the mutants whose mistake the feedback names");
    }
    int run(const GlobalOptions& global) override {
        Session session(global, false);  // no GL here: the grades fork, the comparisons too
        options_.every = std::max(options_.every, 1);
        options_.progress = [](const std::string& line) { std::cerr << line << "\n"; };
        const bool feedback = options_.feedback;
        const auto start = std::chrono::steady_clock::now();
        const std::vector<ModuleMutation> result =
            runMutants(*session.modules, session.paths, options_);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf(
            "| step | mutants | do not compile | killed | survived: equivalent | survived: "
            "NOT equivalent |%s seconds |\n",
            feedback ? " mistake named |" : "");
        std::printf("|---|---|---|---|---|---|%s---|\n", feedback ? "---|" : "");
        int bad = 0;
        for (const ModuleMutation& r : result) {
            const int survived = r.count("survived"), notEquivalent = r.nonEquivalentSurvivors();
            const int killed = r.count("killed") + r.count("timeout") + r.count("crashed");
            bad += notEquivalent;
            std::string named;
            if (feedback) {
                int byPattern = 0, byAny = 0, failed = 0;
                for (const MutantOutcome& x : r.mutants)
                    if (x.status == "killed")
                        ++failed, byAny += !x.mistake.empty(), byPattern += x.namedBy == "pattern";
                named = " " + std::to_string(byPattern) + " / " + std::to_string(byAny) + " of " +
                        std::to_string(failed) + " |";
            }
            std::printf("| %s | %zu | %d | %d | %d | %d |%s %.0f |\n", r.id.c_str(),
                        r.mutants.size(), r.count("stillborn"), killed, survived - notEquivalent,
                        notEquivalent, named.c_str(), r.seconds);
        }
        for (const ModuleMutation& r : result)
            for (const MutantOutcome& x : r.mutants)
                if (x.status == "survived")
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
