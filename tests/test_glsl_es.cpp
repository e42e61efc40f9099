// The lab in a browser runs the same programs as GLSL ES 3.00 (WebGL 2): every program the
// renderer builds, written in GlslDialect::Es300, compiles, links and computes what the
// desktop program computes. Checked on Mesa's desktop context, which compiles `#version 300 es`
// with ES's rules (ARB_ES3_compatibility, core since 4.3); Chromium's ANGLE is the other
// compiler (issue 24's measurements: all of them compile there too, docs/web.md), and this test
// is what CI can run without a browser.
#include <gtest/gtest.h>

#include <cmath>

#include "course/autograder.h"
#include "gl/context.h"
#include "grading/grade_step.h"
#include "render/renderer.h"
#include "steps/contract.h"
#include "steps/plugin_host.h"
#include "test_support.h"
#include "util/fs.h"

using namespace pbrlab;

namespace {

// Equal values, a NaN equal to a NaN (a planted mistake may divide by zero: it must do so in
// both dialects).
bool sameValues(const Image& a, const Image& b) {
    if (a.pixels.size() != b.pixels.size()) return false;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        if (a.pixels[i] != b.pixels[i] && !(std::isnan(a.pixels[i]) && std::isnan(b.pixels[i])))
            return false;
    return true;
}

struct Renderers {
    std::unique_ptr<GlContext> context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    test::TempDir desktopCache, esCache;
    LabRenderer desktop{paths, RendererOptions{desktopCache.path, {}, GlslDialect::Desktop450}};
    LabRenderer es{paths, RendererOptions{esCache.path, {}, GlslDialect::Es300}};

    // The step's probe (every point of its contract's input ranges) in one renderer.
    Image probe(LabRenderer& renderer, const LoadedModule& m, const StudentSource& source) {
        const ModuleDesc& d = *m.desc;
        const Scene scene = loadScene(paths.scene(d.scene));
        const ParamValues params(d.params);
        const std::vector<Surface> surfaces = probeSurfaces(d.probe);
        RenderRequest request{&m,        &params,       &scene,        source,
                              &surfaces, d.probe.width, d.probe.height};
        request.seamlessCubes = false;
        request.ibl = test::smallMaps();
        return renderer.render(request).value;
    }
};

}  // namespace

TEST(GlslEs, EveryStepsProgramsComputeTheSameInGlslEs300) {
    // Every step's view and probe programs with the reference solutions, and the precompute
    // passes of the IBL steps: the probe's values are the desktop program's to the bit (the
    // same compiler and float arithmetic; highp is IEEE single precision in both, and the
    // two built-ins' replacements are exact). Not vacuous: every probe has values.
    Renderers r;
    int steps = 0;
    for (const LoadedModule& m : r.modules.modules()) {
        SCOPED_TRACE(m.desc->id);
        const Image desktop = r.probe(r.desktop, m, {});
        Image es;
        ASSERT_NO_THROW(es = r.probe(r.es, m, {}));
        ASSERT_FALSE(desktop.pixels.empty());
        EXPECT_TRUE(sameValues(es, desktop));
        ++steps;
    }
    EXPECT_EQ(steps, int(contractSteps().size()));  // every step folder's module loaded
}

TEST(GlslEs, EveryPlantedMistakeCompilesInGlslEs300AsOnTheDesktop) {
    // A student's file in the browser compiles where it compiles on the desktop: every
    // planted mistake of every step (labs/*/mistakes), as that step's student file, renders
    // its probe the same in both dialects.
    Renderers r;
    int mistakes = 0;
    for (const LoadedModule& m : r.modules.modules()) {
        const std::filesystem::path folder = m.sourceDir / "mistakes";
        if (!std::filesystem::is_directory(folder)) continue;
        for (const auto& entry : std::filesystem::directory_iterator(folder)) {
            if (entry.path().extension() != ".glsl") continue;
            SCOPED_TRACE(entry.path().string());
            test::TempDir submission;
            submission.write(m.desc->id + ".glsl", readFile(entry.path()));
            const StudentSource source{submission.path, false};
            const Image desktop = r.probe(r.desktop, m, source);
            Image es;
            ASSERT_NO_THROW(es = r.probe(r.es, m, source));
            EXPECT_TRUE(sameValues(es, desktop));
            ++mistakes;
        }
    }
    EXPECT_GE(mistakes, 70);
}

TEST(GlslEs, GradingAsWebGl2FiltersCubeMapsGivesNativeGradingsVerdicts) {
    // WebGL 2's cube maps are always filtered across face edges; grading turns that off on the
    // desktop (the GPU then reads the texels the per-face CPU sampler reads). A renderer that
    // cannot turn it off (seamlessCubesAlways, the page's) gives its CPU references a sampler
    // that filters across the edges too (CubeSampler's seamless mode). Graded that way, every
    // step that reads a cube map gets native `pbrlab grade`'s verdict on its reference
    // solutions and on each planted mistake (all fail in both). Measured before the seamless
    // sampler: split_sum's reference solutions failed (21 of 2145 probe points outside the
    // band where 0.1% may be, worst 3.4x the tolerance, at roughness 1, which reads the
    // prefiltered map's smallest mips, whose faces are a few texels wide).
    Renderers r;
    test::TempDir seamlessCache;
    RendererOptions seamlessOptions{seamlessCache.path, {}, GlslDialect::Es300};
    seamlessOptions.seamlessCubesAlways = true;
    LabRenderer seamless{r.paths, seamlessOptions};
    int graded = 0;
    std::vector<std::string> disagreements;
    for (const LoadedModule& m : r.modules.modules()) {
        if (!(m.desc->needs & NeedsEnvironment)) continue;
        std::vector<std::pair<std::string, StudentSource>> sources = {{"the reference", {}}};
        std::vector<std::unique_ptr<test::TempDir>> submissions;  // each folder kept
        const std::filesystem::path folder = m.sourceDir / "mistakes";
        if (std::filesystem::is_directory(folder))
            for (const auto& entry : std::filesystem::directory_iterator(folder)) {
                if (entry.path().extension() != ".glsl") continue;
                submissions.push_back(std::make_unique<test::TempDir>());
                submissions.back()->write(m.desc->id + ".glsl", readFile(entry.path()));
                sources.push_back(
                    {entry.path().stem().string(), {submissions.back()->path, false}});
            }
        for (const auto& [name, source] : sources) {
            SCOPED_TRACE(m.desc->id + " " + name);
            const StepResult native = gradeStep(r.desktop, m, r.paths, source, GradeSettings{});
            const StepResult browser = gradeStep(seamless, m, r.paths, source, GradeSettings{});
            EXPECT_EQ(native.passed, source.dir.empty()) << native.message;
            if (browser.passed != native.passed) disagreements.push_back(m.desc->id + ": " + name);
            ++graded;
        }
    }
    EXPECT_GE(graded, 15);
    EXPECT_EQ(disagreements, std::vector<std::string>{});
}
