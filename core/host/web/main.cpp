// The page's main (web/CMakeLists.txt): the same lab GUI (gui.h) in the browser's canvas. The
// project's shaders, assets and step folders are the page's preloaded data at /pbrlab; the
// student's files live in /work, kept in the browser's IndexedDB between visits (the page's
// editor writes them there; shell.html). The query string takes the desktop's options:
// ?step=ndf&view=difference&scene=sphere-grid&set=roughness=0.3&command=...
#include <emscripten.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "gui/gui.h"
#include "gui/source_watch.h"
#include "steps/contract.h"
#include "steps/solution_stub.h"
#include "util/error.h"

namespace {

// Every value of `name` in the page's query string, in order.
std::vector<std::string> queryValues(const char* name) {
    char* joined = reinterpret_cast<char*>(EM_ASM_INT(
        {
            const values = new URLSearchParams(location.search).getAll(UTF8ToString($0));
            return allocateUTF8(values.join("\n"));
        },
        name));
    std::vector<std::string> values;
    std::stringstream lines(joined);
    for (std::string line; std::getline(lines, line);) values.push_back(line);
    std::free(joined);
    return values;
}

std::string queryValue(const char* name) {
    const std::vector<std::string> values = queryValues(name);
    return values.empty() ? std::string() : values.back();
}

// What pbrlabPage.<method>(argument) returns, as a string (shell.html).
std::string pageString(const char* method, const std::string& argument) {
    char* text = reinterpret_cast<char*>(EM_ASM_INT(
        {
            const value = pbrlabPage[UTF8ToString($0)](UTF8ToString($1));
            return allocateUTF8(value == null ? "" : String(value));
        },
        method, argument.c_str()));
    std::string value(text);
    std::free(text);
    return value;
}

constexpr const char* kWorkspace = "/work";

}  // namespace

extern "C" {

// Called by main's IndexedDB load (below) once /work holds the student's saved files.
EMSCRIPTEN_KEEPALIVE void pbrlab_start(int width, int height) {
    pbrlab::GuiOptions options;
    options.modulesDirs = {"/pbrlab/modules"};
    options.submission = "/work";
    // Where an assignment's site withholds a solution, programs take the student's file.
    pbrlab::setWithheldStepsFolder(options.submission);
    options.module = queryValue("step");
    // Else the step the student was on (the page remembers it across visits and reloads).
    if (options.module.empty()) {
        const std::string remembered = pageString("remembered", "step");
        if (pbrlab::findContractStep(remembered)) options.module = remembered;
    }
    options.view = queryValue("view");
    // The view the student chose per step, remembered by the page; each choice goes to it.
    try {
        const nlohmann::json views = nlohmann::json::parse(pageString("remembered", "views"));
        for (const auto& [id, view] : views.items())
            if (view.is_string()) options.chosenViews[id] = view.get<std::string>();
    } catch (const std::exception&) {
        // Nothing remembered, or not ours: every step shows its default.
    }
    options.viewChosen = [](const std::string& id, const std::string& view) {
        EM_ASM({ pbrlabPage.viewChosen(UTF8ToString($0), UTF8ToString($1)); }, id.c_str(),
               view.c_str());
    };
    // The page's watchdog (shell.html): the window runs a version of a student's file only once
    // the page has noted, where a hang would leave it, that it runs; a file that did not finish
    // last time runs again once edited.
    options.studentFileGate = [](const std::string& id) { return pageString("gate", id); };
    options.studentFileCameBack = [](const std::string& id) {
        EM_ASM({ pbrlabPage.cameBack(UTF8ToString($0)); }, id.c_str());
    };
    options.scene = queryValue("scene");
    options.sets = queryValues("set");
    options.commands = queryValues("command");
    options.width = width;
    options.height = height;
    try {
        pbrlab::runGui(options);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "pbrlab: %s\n", e.what());
        EM_ASM({ pbrlabPage.failed(UTF8ToString($0)); }, e.what());
    }
}

// The starter file of step `id` (the solution with its body taken out), for the page's editor
// when the student has none yet. The caller frees it.
EMSCRIPTEN_KEEPALIVE char* pbrlab_starter(const char* id) {
    try {
        const pbrlab::ContractStep* step = pbrlab::findContractStep(id);
        if (!step) throw pbrlab::Error(std::string("no step '") + id + "'");
        const bool withheld = pbrlab::solutionWithheld(*step);  // an assignment's site
        std::ifstream in(step->folder / (withheld ? "starter.glsl" : "solution.glsl"));
        std::stringstream text;
        text << in.rdbuf();
        if (withheld) return strdup(text.str().c_str());
        const std::string stub =
            pbrlab::stubSolution(text.str(), step->function, std::string(id) + ".glsl");
        return strdup(stub.c_str());
    } catch (const std::exception& e) {
        return strdup((std::string("// ") + e.what() + "\n").c_str());
    }
}

// The files of the workspace a grade of step `id` reads, one name a line: its file and the
// files it includes, and on an assignment's site every withheld step's (a program links the
// student's file in the solution's place: contract.h), with theirs. The page keeps a report
// under these files' contents: a file the grade does not read changes nothing. The caller
// frees it.
EMSCRIPTEN_KEEPALIVE char* pbrlab_grade_reads(const char* id) {
    std::set<std::string> names;
    auto add = [&](const std::string& step) {
        pbrlab::SourceWatch watch;
        watch.changed(std::filesystem::path(kWorkspace) / (step + ".glsl"), kWorkspace);
        for (const auto& [file, stamp] : watch.current())
            if (file.parent_path() == kWorkspace) names.insert(file.filename().string());
        names.insert(step + ".glsl");  // (missing: its absence is what the grade reads)
    };
    add(id);
    for (const pbrlab::ContractStep& step : pbrlab::contractSteps())
        if (step.id != id && pbrlab::solutionWithheld(step)) add(step.id);
    std::string text;
    for (const std::string& name : names) text += name + "\n";
    return strdup(text.c_str());
}

// The step on screen, for the editor to follow. The caller frees it.
EMSCRIPTEN_KEEPALIVE char* pbrlab_step_on_screen() {
    return strdup(pbrlab::guiStepOnScreen().c_str());
}

// A line for the GUI's console, as typed there (the page's tests drive the lab with it).
EMSCRIPTEN_KEEPALIVE void pbrlab_console(const char* line) {
    pbrlab::guiSubmitConsoleLine(line);
}

// GuiOptions::checkRedraw, on (1) or off (0): the site test's check that the frames drawn over
// the last one are the frames drawn whole (the status's "redraw").
EMSCRIPTEN_KEEPALIVE void pbrlab_check_redraw(int on) {
    pbrlab::guiCheckRedraw(on != 0);
}

// The page's canvas has a new size.
EMSCRIPTEN_KEEPALIVE void pbrlab_resize(int width, int height) {
    pbrlab::guiResize(width, height);
}

// The status lines under the picture, as JSON (gui.h). The caller frees it.
EMSCRIPTEN_KEEPALIVE char* pbrlab_status() {
    return strdup(pbrlab::guiStatusJson().c_str());
}

// The settled solution picture as `pbrlab render --out file.png` writes it; an empty string on
// success, else why not (the caller frees it).
EMSCRIPTEN_KEEPALIVE char* pbrlab_save_solution_picture(const char* file) {
    try {
        pbrlab::guiSaveSolutionPicture(file);
        return strdup("");
    } catch (const std::exception& e) {
        return strdup(e.what());
    }
}

}  // extern "C"

int main() {
    // /pbrlab/modules: where the registry looks for step libraries (the steps are linked in).
    EM_ASM({
        FS.mkdir('/pbrlab/modules');
        FS.mkdir('/work');
        FS.mount(IDBFS, {}, '/work');
        FS.syncfs(
            true, function(error) {
                if (error) console.warn('pbrlab: the saved work could not be read: ' + error);
                pbrlabPage.started();
            });
    });
    return 0;
}
