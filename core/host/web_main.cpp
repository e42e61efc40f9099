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
#include <sstream>
#include <string>

#include "gui/gui.h"
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
    options.view = queryValue("view");
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
