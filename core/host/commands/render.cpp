// The commands about steps on screen: list, render, check, permutations.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <set>

#include "course/autograder.h"
#include "grading/grade_step.h"
#include "session.h"
#include "steps/contract.h"
#include "table.h"
#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

class ListCommand : public Command {
public:
    ListCommand() : Command("list", "List the modules, one a line, id first, lab order") {}
    void declare(CLI::App& cmd) override {
        cmd.add_flag("--order", withOrder_, "Also each step's order key and folder");
    }
    int run(const GlobalOptions& global) override {
        Session session(global, false);
        for (const auto& m : session.modules->modules()) {
            std::cout << m.desc->id << "\t" << m.desc->step << "\t" << m.desc->lab << "\t"
                      << m.desc->title;
            if (withOrder_)
                std::cout << "\t" << findContractStep(m.desc->id)->order << "\t"
                          << m.sourceDir.string();
            std::cout << "\n";
        }
        return 0;
    }

private:
    bool withOrder_ = false;
};

class RenderCommand : public Command {
public:
    RenderCommand() : Command("render", "Render a module's view to PNG or EXR") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("step", id_, help::step)->required();
        cmd.add_option("--submission", submission_, help::submission);
        cmd.add_flag("--cumulative", cumulative_, help::cumulative);
        cmd.add_option("--set", sets_, help::set);
        cmd.add_option("--size", size_, "Image size WxH or N (default 512x512)");
        cmd.add_option("--scene", scene_, help::scene);
        cmd.add_option("--model", model_, help::model);
        cmd.add_flag("--stats", stats_, help::stats);
        cmd.add_flag("--probe", probe_, "Render the probe grid instead of the scene");
        cmd.add_option("--out", out_, "Output .png (display-encoded) or .exr (linear)")->required();
    }
    int run(const GlobalOptions& global) override {
        Session session(global, true, id_);
        const LoadedModule& m = session.modules->find(id_);
        ParamValues values = parseSets(*m.desc, sets_);
        Size s = parseSize(size_);
        Scene scene = sceneFor(session, *m.desc, scene_, model_);
        StudentSource source = studentSource(submission_, cumulative_, id_);
        RenderResult r = probe_ ? session.renderer->renderProbe(m, values, scene, source)
                                : session.renderer->renderScene(m, values, scene, source, s.width,
                                                                s.height, false);
        writeOutput(*m.desc, r, out_);
        std::cout << "wrote " << out_ << " (" << r.value.width << "x" << r.value.height << ", view "
                  << r.milliseconds << " ms)\n";
        if (stats_) printStats(session);
        return 0;
    }

private:
    std::string id_, submission_, size_ = "512x512", scene_, model_, out_;
    std::vector<std::string> sets_;
    bool cumulative_ = false, probe_ = false, stats_ = false;
};

// Grades one step in this process, exactly as `pbrlab grade` does in its child (gradeModule,
// gradeStep inside), and prints every check; --json writes the grade as `grade --json` writes
// one module (the GUI's badges read it).
class CheckCommand : public Command {
public:
    CheckCommand()
        : Command("check",
                  "Grade one step here, exactly as `grade` does, and print every check (exit 0: "
                  "passed)") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("step", id_, help::step)->required();
        cmd.add_option("--submission", submission_, help::submission);
        cmd.add_flag("--cumulative", cumulative_, help::cumulative);
        cmd.add_option("--size", size_, "Side of the scene checks N or NxN (default 96)");
        cmd.add_option("--seed", seed_, help::seed);
        cmd.add_option("--sun-environment", sunEnvironment_, help::sunEnvironment);
        cmd.add_flag("--stats", stats_, help::stats);
        cmd.add_option("--json", json_, "Also write the grade here (as `grade --json` does)");
    }
    int run(const GlobalOptions& global) override {
        Session session(global, true, id_);
        const LoadedModule& m = session.modules->find(id_);
        const int side = parseSquareSize(size_);
        GradeOptions grade;
        const StudentSource source = studentSource(submission_, cumulative_, id_);
        grade.submission = source.dir;
        grade.cumulative = cumulative_;
        grade.settings.size = side;
        grade.settings.seed = seed_;
        grade.settings.sunEnvironment = sunEnvironment_;
        const ModuleGrade g = gradeModule(*session.renderer, m, session.paths, grade);
        for (const auto& c : g.checks) {
            const bool passed = c.value("passed", false), deducted = c.value("deducted", true);
            std::printf("%s %-12s %s: %s\n",
                        passed     ? "ok  "
                        : deducted ? "FAIL"
                                   : "note",
                        c.value("kind", "").c_str(), c.value("name", "").c_str(),
                        c.value("detail", "").c_str());
            const std::string at = c.value("worst_at", c.value("first_problem", ""));
            if (!passed && !at.empty()) std::printf("     worst at %s\n", at.c_str());
        }
        if (g.status != GradeStatus::Passed) std::printf("%s\n", g.message.c_str());
        std::printf("%s: %s (%.1f s)\n", id_.c_str(),
                    g.status == GradeStatus::Passed ? "PASS" : "FAIL", g.seconds);
        if (!json_.empty()) {
            GradeReport one;
            one.submission = grade.submission;
            one.modules = {g};
            writeFileAtomically(json_, jsonText(toJson(one)));
        }
        if (stats_) printStats(session);
        return g.status == GradeStatus::Passed ? 0 : 1;
    }

private:
    std::string id_, submission_, size_ = "96", json_, sunEnvironment_;
    bool cumulative_ = false, stats_ = false;
    std::uint64_t seed_ = 1;
};

// Which shader permutations each module compiles for a scene (rendered small, so the list is
// what really compiled), then every distinct program with its compile time.
class PermutationsCommand : public Command {
public:
    PermutationsCommand()
        : Command("permutations", "List the shader permutations each module compiles for a scene") {
    }
    void declare(CLI::App& cmd) override {
        cmd.add_option("steps", ids_, help::steps);
        cmd.add_option("--scene", scene_, "Scene name or .json (default: each module's own)");
        cmd.add_option("--model", model_, help::model);
    }
    int run(const GlobalOptions& global) override {
        Session session(global);
        if (ids_.empty())
            for (const auto& m : session.modules->modules()) ids_.push_back(m.desc->id);
        std::printf("%-12s %-20s %s\n", "module", "program", "defines");
        for (const std::string& id : ids_) {
            const LoadedModule& m = session.modules->find(id);
            Scene scene = applyParamBindings(sceneFor(session, *m.desc, scene_, model_), *m.desc,
                                             ParamValues(m.desc->params));
            session.renderer->renderScene(m, ParamValues(m.desc->params), scene, {}, 32, 32, false);
            std::set<std::string> gbuffers;
            for (const DrawItem& item : drawItems(scene))
                gbuffers.insert(definesText(
                    session.renderer
                        ->gbufferRecipe(scene.materials.at(size_t(item.material)), m.desc->needs)
                        .defines));
            for (const std::string& d : gbuffers)
                std::printf("%-12s %-20s {%s}\n", id.c_str(), "G-buffer", d.c_str());
            std::printf(
                "%-12s %-20s {%s}\n", "", ("view " + id).c_str(),
                definesText(
                    session.renderer->viewRecipe(m, {}, false, int(scene.lights.size())).defines)
                    .c_str());
        }
        const auto& compiled = session.renderer->programs().compiled();
        std::printf("\n%zu programs compiled:\n", compiled.size());
        for (const CompiledProgram& p : compiled)
            std::printf("  %-30s {%s} %.1f ms\n", p.label.c_str(), p.defines.c_str(),
                        p.milliseconds);
        std::printf("textures loaded: %d, precompute passes: %d\n",
                    eventCount(Counter::TextureLoads), eventCount(Counter::PrecomputePasses));
        return 0;
    }

private:
    std::vector<std::string> ids_;
    std::string scene_, model_;
};

}  // namespace

std::unique_ptr<Command> listCommand() {
    return std::make_unique<ListCommand>();
}
std::unique_ptr<Command> renderCommand() {
    return std::make_unique<RenderCommand>();
}
std::unique_ptr<Command> checkCommand() {
    return std::make_unique<CheckCommand>();
}
std::unique_ptr<Command> permutationsCommand() {
    return std::make_unique<PermutationsCommand>();
}

}  // namespace pbrlab
