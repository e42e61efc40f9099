// A browser page's side of the GUI's platform (gui/platform.h): the page's JavaScript
// (web/shell.html's pbrlabPage) grades in a Web Worker, tells of input and counts frames; the
// browser calls each frame. A page starts no processes and has no priorities.
#include <emscripten.h>

#include <cstdio>
#include <cstdlib>

#include "gui/platform.h"

namespace fs = std::filesystem;

namespace pbrlab::platform {

namespace {

// The page's grader (shell.html, web/grader_worker.js), given the workspace's files when asked;
// it orders the grades itself, so every step whose file changed is asked for at once.
class PageGrades final : public StepGrades {
public:
    Start start(const std::string& id) override {
        return EM_ASM_INT({ return pbrlabPage.grade(UTF8ToString($0)) ? 1 : 0; }, id.c_str())
                   ? Start::Started
                   : Start::NotHere;
    }
    std::optional<std::string> report(const std::string& id) override {
        char* text = reinterpret_cast<char*>(EM_ASM_INT(
            {
                const report = pbrlabPage.gradeResult(UTF8ToString($0));
                return report ? allocateUTF8(report) : 0;
            },
            id.c_str()));
        if (!text) return std::nullopt;
        std::string report(text);
        std::free(text);
        return report;
    }
    bool oneAtATime() const override { return false; }
};

}  // namespace

std::unique_ptr<StepGrades> stepGrades(std::vector<fs::path>, fs::path) {
    return std::make_unique<PageGrades>();
}

std::unique_ptr<PbrlabProcess> startPbrlab(const std::vector<std::string>&,
                                           std::function<void(const std::string&)> output) {
    output("error: a page starts no processes\n");
    return nullptr;
}

bool runFrames(const std::function<bool()>& frame,
               const std::function<void(const std::exception&)>& failed) {
    struct Loop {
        std::function<bool()> frame;
        std::function<void(const std::exception&)> failed;
    };
    static Loop loop;  // the page's, for as long as it is open
    loop = {frame, failed};
    emscripten_set_main_loop_arg(
        [](void* arg) {
            Loop& l = *static_cast<Loop*>(arg);
            try {
                l.frame();
            } catch (const std::exception& e) {
                std::fprintf(stderr, "pbrlab: %s\n", e.what());
                l.failed(e);
            }
        },
        &loop, 0, false);
    return false;
}

bool windowKeepsItsPixels() {
    return EM_ASM_INT({
               const gl = Module.ctx;
               return gl && gl.getContextAttributes().preserveDrawingBuffer ? 1 : 0;
           }) != 0;
}
bool skipsQuietFrames() {
    return true;
}
bool inputArrived() {
    return EM_ASM_INT({ return pbrlabPage.takeInput() ? 1 : 0; }) != 0;
}
void frameDrawn() {
    EM_ASM({ pbrlabPage.frameDrawn(); });
}
std::function<bool()> inputPending() {
    // isInputPending is Chromium's; in other browsers the evaluation never yields.
    return [] {
        return EM_ASM_INT({
                   const s = navigator.scheduling;
                   return s && s.isInputPending && s.isInputPending() ? 1 : 0;
               }) != 0;
    };
}

void backgroundPriorityForThisThread() {}
void backgroundPriorityForThreadsStartedBy(const std::function<void()>& start) {
    start();
}

}  // namespace pbrlab::platform
