// pbrlab: the command line. Sub-commands share one vocabulary of options with the GUI
// (--module/--submission/--set/--size/--scene), so what a student does in the window can be
// repeated in a script.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <set>
#include <thread>

#include "converge.h"
#include "evaluate.h"
#include "gl/context.h"
#include "grade.h"
#include "gradescope.h"
#include "grading.h"
#include "gui/gui.h"
#include "ibl.h"
#include "kit.h"
#include "mutation.h"
#include "new_step.h"
#include "pbrlab/contract.h"
#include "pbrlab/display.h"
#include "pbrlab/envgen.h"
#include "pbrlab/error.h"
#include "pbrlab/gltf.h"
#include "pbrlab/ibl_reference.h"
#include "pbrlab/log.h"
#include "pbrlab/texgen.h"
#include "plugins.h"
#include "renderer.h"
#include "stability.h"

namespace fs = std::filesystem;
using namespace pbrlab;

namespace {

struct Options {
    std::vector<std::string> modulesDirs;  // --modules, after the built-in and $PBRLAB_MODULES
    bool verbose = false;
    bool stats = false;
};

std::vector<fs::path> modulesDirs(const Options& o) {
    return moduleDirs(std::vector<fs::path>(o.modulesDirs.begin(), o.modulesDirs.end()));
}

// Progress of the precompute passes, on stderr.
void printPrecomputePass(const std::string& pass) {
    std::cerr << "precompute " << pass << "\n";
}

// What every command that renders needs, made in the right order (context before GL use).
struct Session {
    std::unique_ptr<GlContext> context;
    DataPaths paths = DataPaths::locate();
    std::unique_ptr<ModuleRegistry> modules;
    std::unique_ptr<LabRenderer> renderer;

    // `onlyId`: the command is about that one module (see ModuleRegistry).
    explicit Session(const Options& o, bool needGl = true, const std::string& onlyId = {}) {
        modules = std::make_unique<ModuleRegistry>(modulesDirs(o), onlyId);
        for (const auto& f : modules->failures())
            std::cerr << "warning: module " << f.library.string() << " not loaded: " << f.reason
                      << "\n";
        if (!needGl) return;
        context = createHeadlessContext();
        logLine("gl", context->description());
        RendererOptions options;
        options.onPrecomputePass = printPrecomputePass;
        renderer = std::make_unique<LabRenderer>(paths, options);
    }
};

struct Size {
    int width = 512, height = 512;
};

Size parseSize(const std::string& text) {
    Size s;
    char x = 0;
    std::istringstream in(text);
    if (!(in >> s.width >> x >> s.height) || x != 'x' || s.width < 2 || s.height < 2 ||
        s.width > 8192 || s.height > 8192 || !in.eof())
        throw Error("--size " + text + ": expected WxH, e.g. 512x512 (2..8192)");
    return s;
}

ParamValues parseSets(const ModuleDesc& m, const std::vector<std::string>& sets) {
    ParamValues values(m.params);
    for (const auto& s : sets) applyAssignment(m.params, values, s);
    return values;
}

StudentSource studentSource(const std::string& dir, bool cumulative, const std::string& id) {
    StudentSource s{dir, cumulative};
    if (!dir.empty()) {
        if (!fs::is_directory(dir)) throw Error("--submission " + dir + ": not a directory");
        if (!fs::exists(fs::path(dir) / (id + ".glsl")))
            std::cerr << "note: " << (fs::path(dir) / (id + ".glsl")).string()
                      << " does not exist; using the reference solution\n";
    }
    return s;
}

void writeOutput(const ModuleDesc& m, const RenderResult& r, const fs::path& out) {
    std::string ext = out.extension().string();
    if (ext == ".exr") {
        writeImage(out, r.value, FileDepth::Float32);
    } else if (ext == ".png") {
        writeImage(out, displayImage(r.value, m.display, m.components), FileDepth::Uint8, true);
    } else {
        throw Error("--out " + out.string() + ": use a .png (display) or .exr (linear) file");
    }
}

// The scene a command renders: --model frames a glTF model lit like the module's (or
// --scene's) scene; otherwise --scene, else the module's own scene.
Scene sceneFor(const Session& session, const ModuleDesc& m, const std::string& sceneName,
               const std::string& model) {
    Scene scene = loadScene(session.paths.scene(sceneName.empty() ? m.scene : sceneName));
    if (!model.empty()) scene = sceneForModel(scene, model);
    for (const auto& model : scene.models)
        for (const auto& w : model.data->warnings)
            std::cerr << "note: " << model.data->file.string() << ": " << w << "\n";
    return scene;
}

// What the run loaded, compiled and precomputed, with times (the journal keeps the lines).
void printStats(const Session& session) {
    for (int c = 0; c < int(Counter::Count); ++c)
        std::cout << counterName(Counter(c)) << ": " << eventCount(Counter(c)) << "\n";
    if (session.renderer)
        for (const CompiledProgram& p : session.renderer->programs().compiled())
            std::printf("  program %-30s {%s} %.1f ms\n", p.label.c_str(), p.defines.c_str(),
                        p.milliseconds);
    std::cout << journal();
}

int runList(const Options& o, bool withOrder) {
    Session session(o, false);
    for (const auto& m : session.modules->modules()) {
        std::cout << m.desc->id << "\t" << m.desc->step << "\t" << m.desc->lab << "\t"
                  << m.desc->title;
        if (withOrder)
            std::cout << "\t" << findContractStep(m.desc->id)->order << "\t"
                      << m.sourceDir.string();
        std::cout << "\n";
    }
    return 0;
}

int runRender(const Options& o, const std::string& id, const std::string& submission,
              bool cumulative, const std::vector<std::string>& sets, const std::string& size,
              const std::string& sceneName, const std::string& model, bool probe,
              const std::string& out) {
    Session session(o, true, id);
    const LoadedModule& m = session.modules->find(id);
    ParamValues values = parseSets(*m.desc, sets);
    Size s = parseSize(size);
    Scene scene = sceneFor(session, *m.desc, sceneName, model);
    StudentSource source = studentSource(submission, cumulative, id);
    RenderResult r =
        probe ? session.renderer->renderProbe(*&m, values, scene, source)
              : session.renderer->renderScene(m, values, scene, source, s.width, s.height, false);
    writeOutput(*m.desc, r, out);
    std::cout << "wrote " << out << " (" << r.value.width << "x" << r.value.height << ", view "
              << r.milliseconds << " ms)\n";
    if (o.stats) printStats(session);
    return 0;
}

// Grades one step in this process, exactly as `pbrlab grade` does in its child (gradeModule,
// gradeStep inside), and prints every check; --json writes the grade as `grade --json` writes
// one module (the GUI's badges read it).
int runCheck(const Options& o, const std::string& id, const std::string& submission,
             bool cumulative, const std::string& size, std::uint64_t seed,
             const std::string& jsonFile) {
    Session session(o, true, id);
    const LoadedModule& m = session.modules->find(id);
    Size s = parseSize(size);
    GradeOptions grade;
    const StudentSource source = studentSource(submission, cumulative, id);
    grade.submission = source.dir;
    grade.cumulative = cumulative;
    grade.settings.size = std::min(s.width, s.height);
    grade.settings.seed = seed;
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
    if (g.status != "passed") std::printf("%s\n", g.message.c_str());
    std::printf("%s: %s (%.1f s)\n", id.c_str(), g.status == "passed" ? "PASS" : "FAIL", g.seconds);
    if (!jsonFile.empty()) {
        GradeReport one;
        one.submission = grade.submission;
        one.modules = {g};
        writeFileAtomically(jsonFile, jsonText(toJson(one)));
    }
    if (o.stats) printStats(session);
    return g.status == "passed" ? 0 : 1;
}

int runStability(const Options& o, const std::vector<std::string>& ids,
                 const std::string& submission) {
    Session session(o);
    std::printf("%-12s %8s %8s %8s %8s %12s  %s\n", "module", "gpu NaN", "gpu Inf", "gpu neg",
                "ref bad", "worst/tol", "first problem");
    int bad = 0;
    for (const auto& m : session.modules->modules()) {
        if (!ids.empty() && std::find(ids.begin(), ids.end(), m.desc->id) == ids.end()) continue;
        Scene scene = loadScene(session.paths.scene(m.desc->scene));
        StudentSource source{submission, false};
        if (!submission.empty() && !fs::exists(fs::path(submission) / (m.desc->id + ".glsl")))
            continue;  // nothing of the student's to sweep for this step
        StabilityResult r = stabilitySweep(*session.renderer, m, scene, source);
        int negatives = m.desc->nonNegative ? r.gpu.negativeCount : 0;
        int refBad = r.referenceNonFinite + r.referenceNegative;
        bad += r.gpu.nonFinite() + negatives + refBad;
        std::printf("%-12s %8d %8d %8d %8d %12.3g  %s\n", m.desc->id.c_str(), r.gpu.nanCount,
                    r.gpu.infCount, negatives, refBad, r.gpu.worstExcess,
                    r.firstProblem.empty() ? "-" : r.firstProblem.c_str());
    }
    std::printf(
        "(%zu extreme inputs per module; worst/tol: the largest distance outside the "
        "reference's band, in tolerances)\n",
        extremeSurfaces().labels.size());
    return bad ? 1 : 0;
}

// Which shader permutations each module compiles for a scene (rendered small, so the list is
// what really compiled), then every distinct program with its compile time.
int runPermutations(const Options& o, std::vector<std::string> ids, const std::string& sceneName,
                    const std::string& model) {
    Session session(o);
    if (ids.empty())
        for (const auto& m : session.modules->modules()) ids.push_back(m.desc->id);
    std::printf("%-12s %-20s %s\n", "module", "program", "defines");
    for (const std::string& id : ids) {
        const LoadedModule& m = session.modules->find(id);
        Scene scene = applyParamBindings(sceneFor(session, *m.desc, sceneName, model), *m.desc,
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
        std::printf("  %-30s {%s} %.1f ms\n", p.label.c_str(), p.defines.c_str(), p.milliseconds);
    std::printf("textures loaded: %d, precompute passes: %d\n", eventCount(Counter::TextureLoads),
                eventCount(Counter::PrecomputePasses));
    return 0;
}

// What `pbrlab precompute` was asked (besides the settings).
struct PrecomputeOptions {
    std::vector<std::string> envFiles;
    std::string outDir;
    double errorBudget = 0;  // > 0: choose the settings (--error-budget)
    bool bench = false;      // compare with LearnOpenGL's sizes (--bench)
    int runs = 3;            // --bench: timed runs of each configuration
    bool noCache = false;
    bool baseline = false;  // LearnOpenGL's sizes and sample counts
};

int runPrecompute(const PrecomputeOptions& p, IblSettings settings) {
    auto context = createHeadlessContext();
    logLine("gl", context->description());
    const DataPaths paths = DataPaths::locate();
    if (p.bench) return benchPrecompute(paths, {p.envFiles, p.runs, p.outDir}) ? 0 : 1;
    if (p.envFiles.size() != 1 || p.outDir.empty())
        throw Error("precompute: give one --env FILE and --out DIR (or --bench)");
    const Image equirect = loadEnvironmentImage(p.envFiles[0]);
    if (p.baseline) settings = IblSettings::learnOpenGl();
    ProgramCache programs(ShaderPreprocessor({paths.shaders(), paths.labs()}));
    IblPrecompute precompute(programs, paths.shaders());
    precompute.onPass = [](const std::string& pass) { logLine("precompute", pass); };
    const IblDiskCache cache(IblDiskCache::defaultRoot());
    IblRun run;
    if (p.errorBudget > 0) {
        IblTruth truth(equirect);
        IblChoice choice = chooseIblSettings(precompute, equirect, truth, p.errorBudget,
                                             p.noCache ? nullptr : &cache);
        std::printf(
            "error budget %g (every map's mean error): %s after measuring %d of %zu "
            "settings\n",
            p.errorBudget, choice.met ? "met" : "NOT met, the most accurate settings", choice.tried,
            iblLadder().size());
        run = std::move(choice.run);
    } else {
        run = precomputeWithErrors(precompute, equirect, settings, p.noCache ? nullptr : &cache);
    }
    std::cout << "precomputed " << p.envFiles[0] << ": " << run.maps->settings.describe() << "\n";
    writePrecompute(run, equirect, p.outDir);
    return 0;
}

int runGallery(const Options& o, const std::string& outDir, const std::string& size) {
    Session session(o);
    Size s = parseSize(size);
    fs::create_directories(outDir);
    std::ofstream html(fs::path(outDir) / "index.html");
    html << "<!doctype html><meta charset=utf-8><title>pbrlab gallery</title>"
            "<style>body{font-family:sans-serif;background:#222;color:#ddd}"
            "figure{display:inline-block;margin:8px}</style><h1>pbrlab: every step</h1>\n";
    int failures = 0;
    for (const auto& m : session.modules->modules()) {
        std::string name = findContractStep(m.desc->id)->numbered() + ".png";
        try {
            Scene scene = loadScene(session.paths.scene(m.desc->scene));
            auto r = session.renderer->renderScene(m, ParamValues(m.desc->params), scene, {},
                                                   s.width, s.height, false);
            writeOutput(*m.desc, r, fs::path(outDir) / name);
            html << "<figure><img src=\"" << name << "\" width=256><figcaption>" << m.desc->step
                 << ". " << m.desc->title << "</figcaption></figure>\n";
            std::cout << "wrote " << (fs::path(outDir) / name).string() << "\n";
        } catch (const Error& e) {
            ++failures;
            std::cerr << "error: " << m.desc->id << ": " << e.what() << "\n";
        }
    }
    // The views the steps add (step.json "gallery"): generated models, scenes placing them.
    html << "<h2>glTF models and scenes</h2>\n";
    for (const auto& m : session.modules->modules())
        for (const ContractStep::GalleryView& v : findContractStep(m.desc->id)->gallery) {
            const std::string name = "model-" + m.desc->id + "-" +
                                     fs::path(v.model.empty() ? v.scene : v.model).stem().string() +
                                     ".png";
            const std::string caption =
                m.desc->id + (v.model.empty() ? ", scene " + v.scene + ".json" : " on " + v.model);
            try {
                Scene scene = sceneFor(
                    session, *m.desc, v.scene,
                    v.model.empty() ? "" : (session.paths.assets() / "models" / v.model).string());
                auto r = session.renderer->renderScene(m, ParamValues(m.desc->params), scene, {},
                                                       s.width, s.height, false);
                writeOutput(*m.desc, r, fs::path(outDir) / name);
                html << "<figure><img src=\"" << name << "\" width=256><figcaption>" << caption
                     << "</figcaption></figure>\n";
                std::cout << "wrote " << (fs::path(outDir) / name).string() << "\n";
            } catch (const Error& e) {
                ++failures;
                std::cerr << "error: " << caption << ": " << e.what() << "\n";
            }
        }
    std::cout << "gallery: " << (fs::path(outDir) / "index.html").string() << "\n";
    return failures ? 1 : 0;
}

// The mutation score: every mutant of each reference solution graded as a submission.
int runMutants(const Options& o, const std::vector<std::string>& ids, const std::string& jsonFile,
               int every, int jobs, bool feedback) {
    Session session(o, false);  // no GL here: the grades fork, the comparisons too
    MutationOptions m;
    m.modules = ids;
    m.every = std::max(every, 1);
    m.jobs = jobs;
    m.feedback = feedback;
    m.progress = [](const std::string& line) { std::cerr << line << "\n"; };
    const auto start = std::chrono::steady_clock::now();
    const std::vector<ModuleMutation> result = runMutants(*session.modules, session.paths, m);
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
        std::printf("| %s | %zu | %d | %d | %d | %d |%s %.0f |\n", r.id.c_str(), r.mutants.size(),
                    r.count("stillborn"), killed, survived - notEquivalent, notEquivalent,
                    named.c_str(), r.seconds);
    }
    for (const ModuleMutation& r : result)
        for (const MutantOutcome& x : r.mutants)
            if (x.status == "survived")
                std::printf("%s %s [%s] %s\n    %s\n", r.id.c_str(),
                            x.equivalence == "equivalent" ? "equivalent" : "SURVIVOR",
                            x.mutant.family.c_str(), x.mutant.description.c_str(),
                            x.evidence.c_str());
    std::printf("%d non-equivalent survivors; %.0f s\n", bad, seconds);
    if (!jsonFile.empty()) writeFileAtomically(jsonFile, jsonText(toJson(result)));
    return bad ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"pbrlab: a step-by-step lab for physically based rendering"};
    app.require_subcommand(1);
    Options o;
    app.add_option("--modules", o.modulesDirs,
                   "A folder of step libraries (pbrlab-<id>.so) and step folders, loaded after the "
                   "built-in steps and $PBRLAB_MODULES (colon-separated); repeatable");
    app.add_flag("--verbose,-v", o.verbose, "Log compiles, texture loads and passes to stderr");

    auto* list = app.add_subcommand("list", "List the modules, one a line, id first, lab order");
    bool listOrder = false;
    list->add_flag("--order", listOrder, "Also each step's order key and folder");

    std::string id, submission, size = "512x512", scene, model, out;
    std::vector<std::string> sets;
    bool cumulative = false, probe = false;
    auto addCommon = [&](CLI::App* cmd) {
        cmd->add_option("id", id, "Module id (see `pbrlab list`)")->required();
        cmd->add_option("--submission", submission,
                        "Folder with the student's <id>.glsl files (replaces the solution)");
        cmd->add_flag("--cumulative", cumulative,
                      "Also use the student's files for the other steps (default: stepwise)");
        cmd->add_option("--set", sets, "Parameter name=value (repeatable)");
        cmd->add_option("--size", size, "Image size WxH (default 512x512)");
        cmd->add_option("--scene", scene, "Scene name in assets/scenes or a .json file");
        cmd->add_option("--model", model,
                        "A glTF model (.glb/.gltf) to view instead, framed and lit like the "
                        "scene");
        cmd->add_flag("--stats", o.stats,
                      "Print what was compiled (each permutation), loaded and precomputed, "
                      "with times");
    };
    auto* render = app.add_subcommand("render", "Render a module's view to PNG or EXR");
    addCommon(render);
    render->add_flag("--probe", probe, "Render the probe grid instead of the scene");
    render->add_option("--out", out, "Output .png (display-encoded) or .exr (linear)")->required();
    std::string checkSize = "96x96";
    std::uint64_t gradeSeed = 1;
    auto* check = app.add_subcommand(
        "check",
        "Grade one step here, exactly as `grade` does, and print every check (exit 0: passed)");
    check->add_option("id", id, "Module id (see `pbrlab list`)")->required();
    check->add_option("--submission", submission,
                      "Folder with the student's <id>.glsl (default: the reference solution)");
    check->add_flag("--cumulative", cumulative, "Also use the student's files for the other steps");
    check->add_option("--size", checkSize, "Side of the scene checks WxH (default 96x96)");
    check->add_option("--seed", gradeSeed, "Seed of the random domain points (default 1)");
    check->add_flag("--stats", o.stats, "Print what was compiled, loaded and precomputed");
    std::string checkJson;
    check->add_option("--json", checkJson, "Also write the grade here (as `grade --json` does)");
    GuiOptions gui;
    std::string guiSize = "1600x960";
    auto* guiCmd = app.add_subcommand("gui", "Open the interactive lab (needs a display)");
    guiCmd->add_option("--submission", gui.submission,
                       "Student folder with <id>.glsl files (default: the current directory "
                       "when it holds any)");
    guiCmd->add_option("--module", gui.module, "Start on this module id");
    guiCmd->add_option("--view", gui.view,
                       "student|solution|reference|difference|split, or a term view (albedo, "
                       "roughness, metallic, ao, normal, N.L, D, G, F, kS, kD, diffuse, specular)");
    guiCmd->add_option("--scene", gui.scene, "Scene name in assets/scenes");
    guiCmd->add_option("--model", gui.model,
                       "A glTF model (.glb/.gltf) to view, framed and lit like the step's scene "
                       "(or --scene)");
    guiCmd->add_option("--tab", gui.tab, "Open this side tab: handout|plot|log|programs");
    guiCmd->add_option("--set", gui.sets, "Parameter name=value for the start module (repeatable)");
    guiCmd->add_option("--frames", gui.frames, "Render this many frames, then exit");
    guiCmd->add_option("--screenshot", gui.screenshot,
                       "With --frames: save the window to this PNG");
    guiCmd->add_option("--size", guiSize, "Window size WxH (default 1600x960)");
    guiCmd->add_option("--error-budget", gui.errorBudget,
                       "Compute each environment's maps with the cheapest settings whose mean "
                       "errors stay within this (as precompute --error-budget)");
    guiCmd->add_flag("--orbit", gui.orbit,
                     "With --frames: orbit the camera a step each frame (as dragging does) and "
                     "print the frame times, median and 95th percentile");
    std::vector<std::string> permutationIds;
    auto* permutationsCmd = app.add_subcommand(
        "permutations", "List the shader permutations each module compiles for a scene");
    permutationsCmd->add_option("ids", permutationIds, "Module ids (default: all)");
    permutationsCmd->add_option("--scene", scene,
                                "Scene name or .json (default: each module's own)");
    permutationsCmd->add_option("--model", model, "A glTF model, framed and lit like the scene");
    std::string modelsDir;
    auto* modelsCmd = app.add_subcommand(
        "models",
        "Write the project's own glTF test assets (deterministic): sphere-grid.glb, "
        "textured-sphere.glb");
    modelsCmd->add_option("--out", modelsDir, "Output folder")->required();
    std::string envOut;
    int envWidth = 512;
    auto* envCmd = app.add_subcommand(
        "environment", "Write the project's own HDR sky (equirectangular, deterministic)");
    envCmd->add_option("--out", envOut, "Output .exr or .hdr")->required();
    envCmd->add_option("--width", envWidth, "Width in texels (height = width / 2)");
    GradeOptions gradeOptions;
    std::string gradeJsonFile, gradescopeFile, gradeModules;
    auto* gradeCmd = app.add_subcommand(
        "grade",
        "Grade a submission folder: every module isolated, stepwise; exit 0 when "
        "grading ran, whatever the score");
    std::string batchDir, batchOut;
    gradeCmd->add_option("submission", gradeOptions.submission, "Folder with <id>.glsl files");
    gradeCmd->add_option("--batch", batchDir,
                         "Grade every sub-folder of this folder (one submission each)");
    gradeCmd->add_option("--out", batchOut, "With --batch: where the reports go");
    gradeCmd->add_option("--steps", gradeModules, "Comma-separated step ids (default: all)");
    gradeCmd->add_option("--json", gradeJsonFile, "Write pbrlab's JSON report here");
    gradeCmd->add_option("--gradescope", gradescopeFile, "Write Gradescope's results.json here");
    gradeCmd->add_option("--html", gradeOptions.html, "Write an HTML report with images here");
    gradeCmd->add_flag("--cumulative", gradeOptions.cumulative,
                       "Use the student's own earlier steps too (default: stepwise)");
    gradeCmd->add_option("--timeout", gradeOptions.timeoutSeconds, "Seconds per module (60)");
    gradeOptions.jobs = int(std::max(1u, std::thread::hardware_concurrency()));
    gradeCmd->add_option("--jobs", gradeOptions.jobs,
                         "Modules graded at once (default: one per core)");
    std::string gradeAssignmentFile;
    gradeCmd->add_option("--assignment", gradeAssignmentFile,
                         "Grade by this assignment file: its steps, points, partial credit and "
                         "time limit (docs/assignment.md)");
    gradeCmd->add_option("--seed", gradeOptions.settings.seed,
                         "Seed of the random domain points (default 1: instructors may keep "
                         "their own)");
    ConvergeOptions converge;
    auto* convergeCmd = app.add_subcommand(
        "converge", "Error against run time of the IBL approximations: CSV, table and plot");
    convergeCmd->add_option("--out", converge.out, "Output folder (default: converge)");
    convergeCmd->add_option("--size", converge.size, "Image side in pixels (default 96)");
    convergeCmd->add_option("--truth-samples", converge.truthSamples,
                            "Samples per pixel of the CPU Monte Carlo truth (default 16384)");
    convergeCmd->add_option("--scene", converge.scene, "Scene (default sphere-grid)");
    convergeCmd->add_flag("--quick", converge.quick, "Fewer settings (for tests)");
    KitOptions kit;
    auto* kitCmd = app.add_subcommand("kit", "Write the student kit (stubs, handouts, README)");
    kitCmd->add_option("--out", kit.out, "Output folder")->required();
    kitCmd->add_flag("--with-solutions", kit.withSolutions,
                     "Write the reference solutions instead of stubs (instructors, tests)");
    kitCmd->add_option("--release-through", kit.releaseThrough,
                       "Give the solutions of the steps up to this id (after due dates)");
    kitCmd->add_flag("--force", kit.force, "Write into a non-empty folder");
    std::string kitAssignment, kitDate;
    kitCmd->add_option("--assignment", kitAssignment,
                       "Only the assignment's steps released by --date (docs/assignment.md)");
    kitCmd->add_option("--date", kitDate, "With --assignment: YYYY-MM-DD (default: today, UTC)");
    AutograderOptions autograder;
    auto* autograderCmd = app.add_subcommand(
        "autograder",
        "Write Gradescope's autograder.zip: setup.sh, run_autograder, the assignment and "
        "pbrlab's .deb (docs/assignment.md)");
    autograderCmd->add_option("--assignment", autograder.assignment, "The assignment file")
        ->required();
    autograderCmd->add_option("--out", autograder.out, "Folder for autograder.zip")->required();
    autograderCmd->add_option("--deb", autograder.deb,
                              "pbrlab_*.deb (default: the one cpack -G DEB wrote in the current "
                              "folder or beside pbrlab)");
    NewStepOptions newStep;
    auto* newStepCmd = app.add_subcommand(
        "new-step", "Write a step folder to build outside the source tree (find_package(pbrlab))");
    newStepCmd->add_option("id", newStep.id, "The step's id: the student's file is <id>.glsl")
        ->required();
    newStepCmd->add_option("--out", newStep.out, "Folder for CMakeLists.txt and <id>/")->required();
    newStepCmd->add_option("--lab", newStep.lab,
                           "Its lab (default: the lab of the step before it)");
    newStepCmd->add_option("--order", newStep.order,
                           "Its order key: between two steps' keys to insert it there (default: "
                           "after the last; `pbrlab list --order` shows them)");
    PrecomputeOptions precomputeOptions;
    IblSettings ibl;
    bool filteredSampling = false;
    auto* precompute = app.add_subcommand(
        "precompute",
        "Split-sum maps of an environment (EXR), each pass's time and its map's error against "
        "the CPU reference (errors.csv); --bench compares with LearnOpenGL's sizes");
    precompute->add_option("--env", precomputeOptions.envFiles,
                           "Equirectangular .hdr or .exr (--bench: one or more; default the "
                           "project's sky and ../shared/data/hdr when present)");
    precompute->add_option("--out", precomputeOptions.outDir, "Output folder");
    precompute->add_option("--error-budget", precomputeOptions.errorBudget,
                           "Choose the cheapest settings whose maps' mean errors stay within "
                           "this (e.g. 0.02)");
    precompute->add_flag("--bench", precomputeOptions.bench,
                         "Time LearnOpenGL's sizes and sample counts against the default, both "
                         "through pbrlab's passes, and compare their maps' errors");
    precompute->add_option("--runs", precomputeOptions.runs, "--bench: runs of each (default 3)");
    precompute->add_flag("--learnopengl", precomputeOptions.baseline,
                         "LearnOpenGL's sizes and sample counts (the --bench baseline)");
    precompute->add_flag("--no-cache", precomputeOptions.noCache,
                         "Compute every map (no disk cache)");
    precompute->add_option("--env-size", ibl.sourceSize,
                           "Size of the cube the GPU passes read (default: the prefilter's)");
    precompute->add_option("--bins", ibl.bins,
                           "Bins per cube face side for irradiance and prefilter (default 16)");
    precompute->add_option("--irradiance-size", ibl.irradianceSize, "Irradiance cube face size");
    precompute->add_option("--prefilter-size", ibl.prefilterSize, "Prefiltered cube mip 0 size");
    precompute->add_option("--prefilter-mips", ibl.prefilterMips, "Prefiltered mip count");
    precompute->add_option("--prefilter-samples", ibl.prefilterSamples,
                           "Samples per texel (with --filtered-sampling)");
    precompute->add_option("--lut-size", ibl.lutWidth, "BRDF LUT width (N.V)");
    precompute->add_option("--lut-height", ibl.lutHeight, "BRDF LUT height (roughness)");
    precompute->add_option("--filtered-sampling", filteredSampling,
                           "Prefilter by filtered importance sampling instead of bins");
    std::vector<std::string> stabilityIds;
    auto* stability = app.add_subcommand(
        "stability",
        "Run every module (or the given ids) on the extreme inputs: NaN/Inf/negatives");
    stability->add_option("ids", stabilityIds, "Module ids (default: all)");
    std::string stabilitySubmission;
    stability->add_option("--submission", stabilitySubmission,
                          "Sweep the student's <id>.glsl files instead of the solutions");
    std::string texturesDir;
    int textureSize = 256;
    auto* textures = app.add_subcommand(
        "textures", "Write the project's procedural metal-plates texture set (deterministic)");
    textures->add_option("--out", texturesDir, "Output folder")->required();
    textures->add_option("--size", textureSize, "Width and height in texels (16..4096)");
    std::vector<std::string> mutantIds;
    std::string mutantsJson;
    int mutantsEvery = 1, mutantsJobs = int(std::max(1u, std::thread::hardware_concurrency()));
    bool mutantsFeedback = false;
    auto* mutantsCmd = app.add_subcommand(
        "mutants",
        "Mutation score: grade mechanical mutants of each reference solution as submissions; "
        "exit 1 when one that is not equivalent survives");
    mutantsCmd->add_option("ids", mutantIds, "Module ids (default: all)");
    mutantsCmd->add_option("--json", mutantsJson, "Write every mutant's outcome here");
    mutantsCmd->add_option("--every", mutantsEvery, "Grade every n-th mutant only (default 1)");
    mutantsCmd->add_option("--jobs", mutantsJobs, "Mutants graded at once (default: cores)");
    mutantsCmd->add_flag("--feedback", mutantsFeedback,
                         "Grade fully and count the mutants whose mistake the feedback names");
    std::string galleryDir = "gallery";
    auto* gallery = app.add_subcommand("gallery", "Render every module's default view");
    gallery->add_option("--out", galleryDir, "Output folder (default: gallery)");
    gallery->add_option("--size", size, "Image size WxH (default 512x512)");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    setVerbose(o.verbose);
    try {
        if (*list) return runList(o, listOrder);
        if (*render)
            return runRender(o, id, submission, cumulative, sets, size, scene, model, probe, out);
        if (*check) return runCheck(o, id, submission, cumulative, checkSize, gradeSeed, checkJson);
        if (*permutationsCmd) return runPermutations(o, permutationIds, scene, model);
        if (*gallery) return runGallery(o, galleryDir, size);
        if (*mutantsCmd)
            return runMutants(o, mutantIds, mutantsJson, mutantsEvery, mutantsJobs,
                              mutantsFeedback);
        if (*stability) return runStability(o, stabilityIds, stabilitySubmission);
        if (*modelsCmd) {
            const fs::path grid = fs::path(modelsDir) / "sphere-grid.glb",
                           textured = fs::path(modelsDir) / "textured-sphere.glb";
            writeSphereGridGlb(grid);
            writeTexturedSphereGlb(textured);
            for (const fs::path& file : {grid, textured}) {
                ModelData check = loadGltf(file);
                std::cout << "wrote " << file.string() << " (" << check.primitives.size()
                          << " primitives, " << check.vertexCount() << " vertices, "
                          << check.materials.size() << " materials, " << check.images.size()
                          << " images)\n";
            }
            return 0;
        }
        if (*envCmd) {
            Image sky = generateSkyEnvironment(envWidth);
            writeImage(envOut, sky, FileDepth::Float32);
            std::cout << "wrote " << envOut << " (" << sky.width << "x" << sky.height << ")\n";
            return 0;
        }
        if (*gradeCmd) {
            std::stringstream ids(gradeModules);
            for (std::string id; std::getline(ids, id, ',');)
                if (!id.empty()) gradeOptions.modules.push_back(id);
        }
        if (*gradeCmd && !batchDir.empty()) {
            Session session(o, false);
            if (batchOut.empty()) throw Error("--batch needs --out DIR for the reports");
            const auto assignment =
                gradeAssignment(gradeAssignmentFile, *session.modules, gradeOptions);
            std::vector<fs::path> subs;
            for (const auto& e : fs::directory_iterator(batchDir)) {
                std::error_code ec;
                if (e.is_directory(ec)) subs.push_back(e.path());
            }
            std::sort(subs.begin(), subs.end());
            std::ofstream summary;
            fs::create_directories(batchOut);
            std::string table = "submission,score,max_score,seconds\n";
            for (size_t i = 0; i < subs.size(); ++i) {
                // A progress bar on stderr: [#####.....] 5/10 name
                const int width = 30;
                int filled = int(width * i / std::max<size_t>(subs.size(), 1));
                std::cerr << "\r[" << std::string(size_t(filled), '#')
                          << std::string(size_t(width - filled), '.') << "] " << i << "/"
                          << subs.size() << " " << subs[i].filename().string() << "   "
                          << std::flush;
                GradeOptions each = gradeOptions;
                fs::path out = fs::path(batchOut) / subs[i].filename();
                each.html = out / "html";
                try {
                    each.submission = fs::canonical(subs[i]);
                    GradeReport report = gradeSubmission(*session.modules, session.paths, each);
                    writeFileAtomically(out / "report.json", jsonText(toJson(report)));
                    writeFileAtomically(out / "results.json",
                                        jsonText(gradescopeResults(report, assignment)));
                    writeHtml(report, each.html);
                    table += subs[i].filename().string() + "," + std::to_string(report.score) +
                             "," + std::to_string(report.maxScore) + "," +
                             std::to_string(report.seconds) + "\n";
                } catch (const std::exception& e) {
                    // One unreadable submission folder stops nothing: it is listed with why.
                    std::cerr << "\nerror: " << subs[i].string() << ": " << e.what() << "\n";
                    table += subs[i].filename().string() + ",0,0,0\n";
                }
            }
            std::cerr << "\r[" << std::string(30, '#') << "] " << subs.size() << "/" << subs.size()
                      << " done" << std::string(20, ' ') << "\n";
            writeFileAtomically(fs::path(batchOut) / "summary.csv", table);
            std::cout << table;
            return 0;
        }
        if (*gradeCmd) {
            if (gradeOptions.submission.empty())
                throw Error("grade: give a SUBMISSION folder, or --batch DIR --out DIR");
            Session session(o, false);  // no GL in the parent: each module forks its own
            const auto assignment =
                gradeAssignment(gradeAssignmentFile, *session.modules, gradeOptions);
            if (!fs::is_directory(gradeOptions.submission))
                throw Error(gradeOptions.submission.string() + ": not a directory");
            gradeOptions.submission = fs::canonical(gradeOptions.submission);
            GradeReport report = gradeSubmission(*session.modules, session.paths, gradeOptions);
            for (const auto& g : report.modules)
                std::printf("%-12s %-14s %4.1f / %-4.1f %s\n", g.id.c_str(), g.status.c_str(),
                            g.score, g.maxScore, g.message.substr(0, 160).c_str());
            std::printf("total %.1f / %.1f in %.1f s\n", report.score, report.maxScore,
                        report.seconds);
            if (!gradeJsonFile.empty())
                writeFileAtomically(gradeJsonFile, jsonText(toJson(report)));
            if (!gradescopeFile.empty())
                writeFileAtomically(gradescopeFile,
                                    jsonText(gradescopeResults(report, assignment)));
            if (!gradeOptions.html.empty()) writeHtml(report, gradeOptions.html);
            return 0;
        }
        if (*convergeCmd) {
            Session session(o);
            setVerbose(true);
            converge.onPrecomputePass = printPrecomputePass;
            auto rows = runConverge(session.paths, converge);
            writeConvergeReport(rows, converge.out);
            std::printf("%-9s %-20s %-26s %8s %10s %14s %11s %11s %13s\n", "term", "method",
                        "setting", "samples", "ms", "precompute ms", "rmse", "max error",
                        "display rmse");
            for (const auto& r : rows)
                std::printf("%-9s %-20s %-26s %8d %10.2f %14.1f %11.3g %11.3g %13.3g\n",
                            r.term.c_str(), r.method.c_str(), r.setting.c_str(), r.samples, r.ms,
                            r.precomputeMs, r.rmse, r.maxError, r.displayRmse);
            std::cout << "wrote " << (converge.out / "converge.csv").string() << " and "
                      << (converge.out / "converge.png").string() << "\n";
            return 0;
        }
        if (*kitCmd) {
            Session session(o, false);
            if (!kitAssignment.empty())
                applyAssignment(loadAssignment(kitAssignment, stepIds(*session.modules)),
                                kitDate.empty() ? todayUtc() : kitDate, kit);
            else if (!kitDate.empty())
                throw Error("kit: --date goes with --assignment");
            int n = writeKit(*session.modules, kit);
            std::cout << "wrote " << n << " module files and handouts to " << kit.out.string()
                      << "\n";
            return 0;
        }
        if (*autograderCmd) {
            Session session(o, false);
            const fs::path zip = writeAutograderBundle(autograder, *session.modules);
            std::cout << "wrote " << zip.string() << " (" << fs::file_size(zip)
                      << " bytes): upload it as the autograder of a Gradescope programming "
                         "assignment\n";
            return 0;
        }
        if (*newStepCmd) {
            for (const fs::path& dir : modulesDirs(o)) addStepRoot(dir);
            writeStepTemplate(newStep);
            std::cout << "wrote " << (newStep.out / newStep.id).string() << "/ and "
                      << (newStep.out / "CMakeLists.txt").string() << "\nbuild: cmake -S "
                      << newStep.out.string() << " -B " << (newStep.out / "build").string()
                      << " -DCMAKE_PREFIX_PATH=<pbrlab's install prefix> && cmake --build "
                      << (newStep.out / "build").string() << "\nuse:   pbrlab --modules "
                      << (newStep.out / "build" / "modules").string() << " list\n";
            return 0;
        }
        if (*precompute) {
            if (filteredSampling) ibl.prefilter = PrefilterMethod::Filtered;
            return runPrecompute(precomputeOptions, ibl);
        }
        if (*guiCmd) {
            Size s = parseSize(guiSize);
            gui.width = s.width;
            gui.height = s.height;
            gui.modulesDirs = modulesDirs(o);
            return runGui(gui);
        }
        if (*textures) {
            generateMetalPlates(texturesDir, textureSize);
            std::cout << "wrote albedo, roughness, metallic, ao and normal maps to " << texturesDir
                      << "\n";
            return 0;
        }
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}
