// The page's grader (web/CMakeLists.txt, docs/web.md "The badge in the page"): a second
// program of the site, run in a Web Worker (web/grader_worker.js), that grades one step as
// `pbrlab check` does (gradeModuleHere: gradeStep's checks, the message that names the
// mistake) in its own WebGL 2 context on an OffscreenCanvas, so that the page draws on while
// a step is graded. The worker copies the student's files into this program's /work and asks
// for a step; the answer is the report `pbrlab check --json` writes.
#include <emscripten.h>

#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "gl/context.h"
#include "grading/module_grade.h"
#include "render/renderer.h"
#include "steps/contract.h"
#include "steps/paths.h"
#include "steps/plugin_host.h"
#include "util/error.h"
#include "util/log.h"

namespace {

constexpr const char* kSubmission = "/work";
constexpr size_t kBandsKept = 64;

struct Grader {
    pbrlab::DataPaths paths = pbrlab::DataPaths::locate();
    // The steps linked in (a page loads no libraries).
    pbrlab::ModuleRegistry modules{std::vector<std::filesystem::path>()};
    std::unique_ptr<pbrlab::GlContext> context = pbrlab::createHeadlessContext();
    // The checks' bands, from grade to grade: a band is what the CPU reference says on inputs
    // the host draws (no student's file is in it), and the next file of a step is graded on
    // the same inputs. A grade of ndf builds 6, one of fresnel 9; each at most 0.9 MB (the
    // scene checks' 96 x 96 points): kBandsKept holds several steps' grades.
    pbrlab::BandCache bands{kBandsKept};
    Grader() { pbrlab::setWithheldStepsFolder(kSubmission); }  // as `check --submission`
};

}  // namespace

extern "C" {

// Step `id` of /work graded as `pbrlab check ID --submission /work --json` writes it. The
// caller frees it.
EMSCRIPTEN_KEEPALIVE char* pbrlab_grade(const char* id) {
    pbrlab::ModuleGrade grade;
    grade.id = id;
    try {
        static Grader grader;  // the steps and the context, made by the first grade
        // A renderer of its own, as each `pbrlab check` process has: programs compiled for an
        // earlier grade's files (the typical mistakes' and mutants' temporary files are read
        // at the same paths every time) are not this grade's.
        pbrlab::LabRenderer renderer(grader.paths, pbrlab::RendererOptions());
        pbrlab::GradeSettings settings;
        settings.bands = &grader.bands;
        // The feedback runs after the checks, on a failure only: from there on the verdict is
        // known, and the page says "fails" if naming the mistake runs past its time limit
        // (shell.html) instead of a timeout, which would say nothing about the file.
        settings.stage = [](const std::string& stage) {  // "<id>: <stage>"
            if (stage.ends_with(": feedback")) EM_ASM({ postMessage({namingTheMistake : true}); });
        };
        grade = pbrlab::gradeModuleHere(renderer, grader.modules.find(id), grader.paths,
                                        {kSubmission, false}, settings);
    } catch (const std::exception& e) {
        grade.status = pbrlab::GradeStatus::Failed;
        grade.message = pbrlab::validUtf8(std::string("the grader could not start: ") + e.what());
    }
    const nlohmann::json report = {{"submission", kSubmission},
                                   {"modules", nlohmann::json::array({gradeJson(grade)})}};
    return strdup(report.dump().c_str());
}

// What the grades so far compiled, loaded, precomputed and checked, with times (as `pbrlab
// check --stats` prints it); web/test/grade_probe.mjs reads it. The caller frees it.
EMSCRIPTEN_KEEPALIVE char* pbrlab_journal() {
    return strdup(pbrlab::journal().c_str());
}

}  // extern "C"

int main() {
    return 0;  // the worker calls pbrlab_grade (the runtime stays: EXIT_RUNTIME is off)
}
