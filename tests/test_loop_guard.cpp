// Every loop of a student's file bounded (core/shader/loop_guard.h): a loop that never ends fails
// the same way whatever the compiler makes of it (Mesa deleted the issue's loop and the file
// passed; WebGL's compiler kept it and the page hung), with a message naming the file and the
// loop's line; the budget is exact, shared by every loop of an invocation and of every student's
// file linked, and never cuts a correct function at the largest counts the host allows.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <regex>

#include "course/autograder.h"
#include "gl/context.h"
#include "grading/grade_step.h"
#include "render/renderer.h"
#include "shader/loop_guard.h"
#include "shader/preprocess.h"
#include "steps/plugin_host.h"
#include "test_support.h"
#include "util/error.h"
#include "util/fs.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

std::string solutionOf(const std::string& id) {
    return readFile(fs::path(PBRLAB_SOURCE_DIR) / "labs" / id / "solution.glsl");
}

// The reference solution with `before` in front of its (last) `return`.
std::string withBeforeReturn(const std::string& id, const std::string& before) {
    std::string text = solutionOf(id);
    const size_t at = text.rfind("    return");
    text.insert(at, before);
    return text;
}

// The 1-based line of the first line of `text` holding `needle`.
int lineOf(const std::string& text, const std::string& needle) {
    const size_t at = text.find(needle);
    return at == std::string::npos
               ? 0
               : 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
}

struct Lab {
    std::unique_ptr<GlContext> context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    test::TempDir cache;
    LabRenderer renderer{paths, [this] {
                             RendererOptions o;
                             o.cacheRoot = cache.path;
                             return o;
                         }()};

    const LoadedModule& module(const std::string& id) {
        for (const LoadedModule& m : modules.modules())
            if (m.desc->id == id) return m;
        throw Error("no module " + id);
    }
    // The step's probe (or `count` of its points, spread) with these parameters and maps.
    RenderResult probe(const std::string& id, const StudentSource& source,
                       const ParamValues& params, const IblSettings& ibl, size_t count = 0) {
        const LoadedModule& m = module(id);
        const ModuleDesc& d = *m.desc;
        const Scene scene = loadScene(paths.scene(d.scene));
        std::vector<Surface> surfaces = probeSurfaces(d.probe);
        int width = d.probe.width, height = d.probe.height;
        if (count > 0) {
            std::vector<Surface> some;
            for (size_t k = 0; k < count; ++k)
                some.push_back(surfaces[k * surfaces.size() / count + surfaces.size() / count / 2]);
            surfaces = some;
            width = int(count);
            height = 1;
        }
        RenderRequest request{&m, &params, &scene, source, &surfaces, width, height};
        request.seamlessCubes = false;
        request.ibl = ibl;
        return renderer.render(request);
    }
};

int nanCount(const Image& value, int components) {
    int n = 0;
    for (size_t i = 0; i < value.pixels.size(); i += 4)
        for (int c = 0; c < components; ++c) n += std::isnan(value.pixels[i + size_t(c)]);
    return n;
}

// The largest relative difference of the covered values (alpha 1) of two renders.
double largestDifference(const Image& a, const Image& b, int components) {
    double worst = 0;
    for (size_t i = 0; i < a.pixels.size(); i += 4) {
        if (a.pixels[i + 3] != 1.0f) continue;
        for (int c = 0; c < components; ++c) {
            const double x = a.pixels[i + size_t(c)], y = b.pixels[i + size_t(c)];
            const double d = std::abs(x - y) / std::max(1e-6, std::abs(y));
            worst = std::max(worst, std::isfinite(d) ? d : 1e30);
        }
    }
    return worst;
}

}  // namespace

TEST(LoopGuard, EveryLoopsConditionIsWrappedAndItsLineNoted) {
    const std::string text =
        "float f(float x) {\n"                                 // 1
        "    // while (x > 0.0) in a comment is no loop\n"     // 2
        "    for (int i = 0; i < 3; ++i) x += 1.0;\n"          // 3
        "    for (;;) { if (x > 9.0) break; x *= 2.0; }\n"     // 4
        "    do { x -= 1.0; } while (x > 5.0);\n"              // 5
        "    while ((x = x - 1.0) > 0.0) {\n"                  // 6
        "        for (int j = 0; j < 2 && x > 0.0; j++) {}\n"  // 7
        "    }\n"                                              // 8
        "    wh\\\nile (x < 0.0) x += 1.0;\n"                  // 9, 10 (a continuation)
        "    return x;\n"
        "}\n"
        "#define REPEAT(n) for (int k = 0; k < n; ++k)\n";  // 13
    std::vector<LoopSite> sites;
    const std::string guarded = guardLoops(text, "f.glsl", "f.glsl", sites);
    ASSERT_EQ(sites.size(), 7u) << guarded;
    const int lines[] = {3, 4, 5, 6, 7, 9, 13};
    for (size_t k = 0; k < sites.size(); ++k) {
        EXPECT_EQ(sites[k].line, lines[k]) << k;
        EXPECT_EQ(sites[k].file, "f.glsl");
    }
    EXPECT_TRUE(contains(guarded, "for (int i = 0;pbrlab_loop(1, ( i < 3)); ++i)")) << guarded;
    EXPECT_TRUE(contains(guarded, "for (; pbrlab_loop(2, true);)")) << guarded;
    EXPECT_TRUE(contains(guarded, "} while (pbrlab_loop(3, (x > 5.0)));")) << guarded;
    EXPECT_TRUE(contains(guarded, "while (pbrlab_loop(4, ((x = x - 1.0) > 0.0)))")) << guarded;
    EXPECT_TRUE(contains(guarded, "pbrlab_loop(5, ( j < 2 && x > 0.0))")) << guarded;
    EXPECT_TRUE(contains(guarded, "ile (pbrlab_loop(6, (x < 0.0)))")) << guarded;
    EXPECT_TRUE(contains(guarded, "for (int k = 0;pbrlab_loop(7, ( k < n)); ++k)")) << guarded;
    EXPECT_TRUE(contains(guarded, "// while (x > 0.0) in a comment")) << guarded;
    // No line added or removed: the compiler's lines are the file's.
    EXPECT_EQ(std::count(guarded.begin(), guarded.end(), '\n'),
              std::count(text.begin(), text.end(), '\n'));
}

TEST(LoopGuard, ALoopItCannotWrapIsRefusedAtItsLine) {
    const std::pair<const char*, const char*> refused[] = {
        {"#define while for\n", ":1: error: #define while"},
        {"float f() {\n#define UNTIL (x < 1.0)\n    float x = 2.0;\n    while UNTIL x -= 1.0;\n"
         "    return x;\n}\n",
         ":4: error: `while` without its parenthesis"},
        {"float f() {\n    float x = 2.0;\n    while (bool go = x > 1.0) x -= 1.0;\n    return "
         "x;\n}\n",
         ":3: error: a declaration as the loop's condition"},
        {"#define LOOP while\n", ":1: error: `while` without its parenthesis"},
    };
    for (const auto& [text, expected] : refused) {
        std::vector<LoopSite> sites;
        try {
            guardLoops(text, "f.glsl", "f.glsl", sites);
            ADD_FAILURE() << "not refused: " << text;
        } catch (const ShaderError& e) {
            EXPECT_TRUE(contains(e.what(), std::string("f.glsl") + expected)) << e.what();
        }
    }
    // A student's file may not name the guard.
    test::TempDir dir;
    dir.write("ndf.glsl",
              "float distributionGGX(vec3 N, vec3 H, float r) { pbrlab_loopsRun = 0; return 1.0; "
              "}\n");
    ShaderPart part(dir.path / "ndf.glsl");
    part.studentFolder = dir.path;
    EXPECT_THROW(ShaderPreprocessor({dir.path}).expand({part}, {}), ShaderError);
}

TEST(LoopGuard, ACompilerMessageNeverNamesTheGuard) {
    // A condition that is not a bool: the compiler sees it passed to pbrlab_loop; the student
    // reads what is wrong with their condition.
    Lab lab;
    test::TempDir dir;
    dir.write("ndf.glsl", withBeforeReturn("ndf", "    int i = 3;\n    while (i) i -= 1;\n"));
    const ParamValues params(lab.module("ndf").desc->params);
    try {
        lab.probe("ndf", {dir.path, false}, params, test::smallMaps());
        ADD_FAILURE() << "compiled";
    } catch (const ShaderError& e) {
        EXPECT_TRUE(contains(e.what(), "a loop's condition must be a bool")) << e.what();
        EXPECT_FALSE(contains(e.what(), "pbrlab_loop")) << e.what();
    }
}

TEST(LoopGuard, TheBudgetIsExactAndSharedByEveryLoopOfAnInvocation) {
    // A loop of exactly the budget's iterations runs to its end; one more and the value is NaN.
    // Nested loops count every iteration, the outer's too: 64 outer iterations of B/64 - 1 inner
    // ones are B in all.
    Lab lab;
    const ParamValues params(lab.module("ndf").desc->params);
    auto render = [&](const std::string& loop) {
        test::TempDir dir;
        dir.write("ndf.glsl", withBeforeReturn("ndf", "    float x = 0.0;\n    " + loop +
                                                          "\n    a2 *= min(x, 1.0);\n"));
        return lab.probe("ndf", {dir.path, false}, params, test::smallMaps());
    };
    const RenderResult first = render("for (int i = 0; i < 1; ++i) x += 1.0;");
    const int budget = first.loopBudget;
    ASSERT_GT(budget, 0);
    EXPECT_EQ(budget, loopBudget(viewLoopLimits(*lab.module("ndf").desc, params, 1,
                                                test::smallMaps().environmentSize)));
    ASSERT_EQ(budget % 64, 0);
    const RenderResult reference = lab.probe("ndf", {}, params, test::smallMaps());
    const std::string n = std::to_string(budget);
    const std::string inner = std::to_string(budget / 64 - 1);
    for (const std::string& within :
         {"for (int i = 0; i < " + n + "; ++i) x += 1.0;",
          "int i = 0;\n    do { x += 1.0; } while (++i < " + n + ");",
          "for (int i = 0; i < 64; ++i) for (int j = 0; j < " + inner + "; ++j) x += 1.0;"}) {
        SCOPED_TRACE(within);
        const RenderResult r = render(within);
        EXPECT_EQ(nanCount(r.value, 1), 0);
        EXPECT_EQ(largestDifference(r.value, reference.value, 1), 0.0);
    }
    for (const std::string& beyond :
         {"for (int i = 0; i < " + n + " + 1; ++i) x += 1.0;",
          "for (int i = 0; i < 64; ++i) for (int j = 0; j < " + inner + " + 1; ++j) x += 1.0;",
          "for (int i = 0; i < 2; ++i) x += 1.0;\n    for (int i = 0; i < " + n +
              " - 1; ++i) x += 1.0;"}) {
        SCOPED_TRACE(beyond);
        const RenderResult r = render(beyond);
        EXPECT_EQ(nanCount(r.value, 1), int(r.value.pixels.size() / 4));
    }
}

TEST(LoopGuard, CorrectFunctionsAtTheHostsLargestCountsAreNeverCut) {
    // Correct functions at the most the host allows render what the reference solutions render:
    // the estimators at 65536 samples (the GUI's and the grader's largest count: a loop of
    // 65536 iterations, past llvmpipe's 65535, which drops the last one for the reference
    // solution alike); with every step's file the student's (--cumulative), Hammersley's
    // radical inverse bit by bit (32 iterations per sample) under prefilter's 1024 samples
    // and in the discrepancy view's 1024 points, irradiance's texel sum over 64^2 texels a
    // face of LearnOpenGL's 512^2 environment (the largest the host builds), the reflectance
    // sum over 64 lights (kMaxSceneLights) with a Fresnel power by a loop.
    Lab lab;
    test::TempDir stepwise, cumulative;
    for (const LoadedModule& m : lab.modules.modules()) {
        stepwise.write(m.desc->id + ".glsl", solutionOf(m.desc->id));
        cumulative.write(m.desc->id + ".glsl", solutionOf(m.desc->id));
    }
    const std::string bitLoop =
        "vec2 hammersley(uint i, uint n)\n{\n    uint bits = i, reversed = 0u;\n"
        "    for (int b = 0; b < 32; ++b) {\n        reversed = (reversed << 1u) | (bits & 1u);\n"
        "        bits >>= 1u;\n    }\n"
        "    return vec2(float(i) / float(max(n, 1u)), float(reversed) * "
        "2.3283064365386963e-10);\n}\n";
    stepwise.write("hammersley.glsl", bitLoop);
    cumulative.write("hammersley.glsl", bitLoop);
    cumulative.write("fresnel.glsl",
                     "vec3 fresnelSchlick(float cosTheta, vec3 F0)\n{\n    float x = clamp(1.0 - "
                     "cosTheta, 0.0, 1.0), p = 1.0;\n    for (int k = 0; k < 5; ++k) p *= x;\n"
                     "    return F0 + (1.0 - F0) * p;\n}\n");
    std::string irradiance = solutionOf("irradiance");
    const std::string mip = "int lod = max(findMSB(baseSize) - 5, 0);";
    const size_t lod = irradiance.find(mip);
    ASSERT_NE(lod, std::string::npos);
    irradiance.replace(lod, mip.size(), "int lod = max(findMSB(baseSize) - 6, 0);");
    stepwise.write("irradiance.glsl", irradiance);
    IblSettings large = test::smallMaps();
    large.environmentSize = 512;
    struct Case {
        std::string id, set;
        bool cumulative;
        size_t points;
        // The same arithmetic: float rounding. Irradiance: a sum over 4 times the texels, of
        // another mip (measured 0.6% apart at most).
        double tolerance;
    };
    for (const Case& c : std::vector<Case>{{"prefilter", "samples=65536", false, 6, 1e-5},
                                           {"mc_specular", "samples=65536", false, 6, 1e-5},
                                           {"brdf_lut", "samples=65536", false, 6, 1e-5},
                                           {"prefilter", "samples=1024", true, 6, 1e-5},
                                           {"hammersley", "samples=1024", false, 0, 0},
                                           {"irradiance", "", false, 6, 0.02},
                                           {"reflectance", "", true, 0, 1e-5}}) {
        SCOPED_TRACE(c.id + " " + c.set);
        const ModuleDesc& d = *lab.module(c.id).desc;
        ParamValues params(d.params);
        if (!c.set.empty()) applyAssignment(d.params, params, c.set);
        const StudentSource student{c.cumulative ? cumulative.path : stepwise.path, c.cumulative};
        RenderResult mine, reference;
        if (c.id == "reflectance") {
            Scene scene = loadScene(lab.paths.scene(d.scene));
            ASSERT_FALSE(scene.lights.empty());
            while (scene.lights.size() < kMaxSceneLights) scene.lights.push_back(scene.lights[0]);
            mine =
                lab.renderer.renderScene(lab.module(c.id), params, scene, student, 48, 48, false);
            reference =
                lab.renderer.renderScene(lab.module(c.id), params, scene, {}, 48, 48, false);
        } else {
            mine = lab.probe(c.id, student, params, large, c.points);
            reference = lab.probe(c.id, {}, params, large, c.points);
        }
        EXPECT_FALSE(mine.loops.empty());
        EXPECT_EQ(nanCount(mine.value, d.components), 0);
        EXPECT_LE(largestDifference(mine.value, reference.value, d.components), c.tolerance);
        std::printf("[ measured ] %s %s: budget %d, %g apart\n", c.id.c_str(), c.set.c_str(),
                    mine.loopBudget, largestDifference(mine.value, reference.value, d.components));
    }
}

TEST(LoopGuard, ALoopInAnEarlierStepsFileIsBoundedToo) {
    // --cumulative links the student's files of the earlier steps: their loops share the
    // graded step's budget, and a cut there marks the graded step's value.
    Lab lab;
    test::TempDir dir;
    dir.write("ndf.glsl", withBeforeReturn("ndf",
                                           "    int i = 0;\n    while (i >= 0) { i = (i + "
                                           "1) & 0x3fffffff; }\n"));
    const ParamValues params(lab.module("specular").desc->params);
    const RenderResult r = lab.probe("specular", {dir.path, true}, params, test::smallMaps());
    EXPECT_GT(nanCount(r.value, 3), 0);
    ASSERT_EQ(r.loops.size(), 1u);
    EXPECT_EQ(r.loops[0].file, "ndf.glsl");
}

TEST(LoopGuard, LoopsThatNeverEndFailNamingTheLoopInBoundedTime) {
    // Each file: a loop that never ends for some or every input, of a kind the static check
    // cannot read. The grade fails with the file and the loop's line first.
    Lab lab;
    struct Endless {
        std::string id, file, text, loopLine;
    };
    const std::vector<Endless> files = {
        // The issue's: Mesa deleted it (no side effect) and the file passed.
        {"ndf", "ndf.glsl",
         withBeforeReturn("ndf",
                          "    int i = 0;\n    while (i >= 0) { i = (i + 1) & 0x3fffffff; "
                          "}\n"),
         "while (i >= 0)"},
        // A for loop whose counter its body resets.
        {"g1", "g1.glsl",
         withBeforeReturn("g1",
                          "    float s = 0.0;\n    for (int i = 0; i < 4; ++i) {\n"
                          "        s += x;\n        if (i == 2) i = 0;\n    }\n"
                          "    k += 0.0 * s;\n"),
         "for (int i = 0; i < 4; ++i)"},
        // A do-while whose condition its body never makes false.
        {"fresnel", "fresnel.glsl",
         "vec3 fresnelSchlick(float cosTheta, vec3 F0)\n{\n    float x = clamp(1.0 - cosTheta, "
         "0.0, 1.0), p = 1.0;\n    int n = 0;\n    do {\n        p *= x;\n"
         "        n = (n + 1) % 5;\n    } while (n != 5);\n    return F0 + (1.0 - F0) * p;\n}\n",
         "} while (n != 5);"},
        // Nested: the inner loop never ends (its counter stays 0); the outer one would.
        {"ndotl", "ndotl.glsl",
         "float lambertCosine(vec3 N, vec3 L)\n{\n    float c = 0.0;\n"
         "    for (int k = 0; k < 3; ++k) {\n        int j = 0;\n"
         "        while (j < 10) { c += 0.001; j = j * 2; }\n    }\n"
         "    return max(dot(N, L), 0.0) + 0.0 * c;\n}\n",
         "while (j < 10)"},
        // Nested: the outer loop never ends, around a short inner one that runs most of the
        // iterations.
        {"f0", "f0.glsl",
         "vec3 baseReflectivity(vec3 albedo, float metallic)\n{\n    vec3 f = vec3(0.04);\n"
         "    int rounds = 0;\n    while (rounds >= 0) {\n"
         "        for (int c = 0; c < 3; ++c) f[c] += 0.0;\n"
         "        rounds = (rounds + 1) & 0xffff;\n    }\n"
         "    return mix(f, albedo, metallic);\n}\n",
         "while (rounds >= 0)"},
        // An estimator that reads the environment: its budget is the most llvmpipe runs, so
        // the guard ends the loop there before llvmpipe's silent stop.
        {"prefilter", "prefilter.glsl",
         withBeforeReturn("prefilter",
                          "    int i = 0;\n    while (i >= 0) { i = (i + 1) & "
                          "0x3fffffff; }\n"),
         "while (i >= 0)"},
        // Endless only above 1000 samples: the probe at the default 64 passes, and the values
        // checks at 1024 and more name the loop from the NaN they see.
        {"prefilter", "prefilter.glsl",
         withBeforeReturn("prefilter",
                          "    int i = 0;\n    while (sampleCount > 1000u && i >= 0) "
                          "{ i = (i + 1) & 0x3fffffff; }\n"),
         "while (sampleCount > 1000u"},
        // In a helper of the student's, in a file the step's file includes.
        {"halfway", "slow.glsl",
         "float slowLength(vec3 v)\n{\n    float len = 0.0;\n"
         "    for (float t = 0.0; t < 1.0; t += 0.0) len = length(v);\n    return len;\n}\n",
         "for (float t = 0.0;"},
    };
    for (const Endless& e : files) {
        SCOPED_TRACE(e.id);
        test::TempDir dir;
        dir.write(e.file, e.text);
        if (e.file != e.id + ".glsl")
            dir.write(e.id + ".glsl",
                      "#include \"" + e.file +
                          "\"\nvec3 halfwayVector(vec3 L, vec3 V)\n{\n    vec3 h = L + V;\n"
                          "    return h / max(slowLength(h), 1e-7);\n}\n");
        const auto start = std::chrono::steady_clock::now();
        const StepResult r = gradeStep(lab.renderer, lab.module(e.id), lab.paths, {dir.path, false},
                                       GradeSettings{});
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        EXPECT_FALSE(r.passed);
        const std::string first = e.file + " line " + std::to_string(lineOf(e.text, e.loopLine)) +
                                  ": this loop did not end within ";
        EXPECT_EQ(r.message.rfind(first, 0), 0u) << r.message;
        EXPECT_TRUE(
            std::regex_search(r.message, std::regex(" within \\d+ iterations: a loop that never "
                                                    "ends\\? ")))
            << r.message;
        std::printf("[ measured ] %s: failed in %.1f s\n", e.id.c_str(), seconds);
        EXPECT_LT(seconds, 120);
    }
}

TEST(LoopGuard, TheBrowsersGlslGivesTheSameVerdictAndMessage) {
    // The page's programs are GLSL ES 3.00 (WebGL 2): the guard and its diagnosis build in that
    // dialect grade the issue's file and a nested loop as the desktop's programs do, message for
    // message (Mesa compiles `#version 300 es` with ES's rules; tests/test_glsl_es.cpp).
    Lab lab;
    test::TempDir esCache;
    RendererOptions esOptions;
    esOptions.cacheRoot = esCache.path;
    esOptions.dialect = GlslDialect::Es300;
    LabRenderer es{lab.paths, esOptions};
    const std::pair<const char*, std::string> files[] = {
        {"ndf", withBeforeReturn("ndf",
                                 "    int i = 0;\n    while (i >= 0) { i = (i + 1) & "
                                 "0x3fffffff; }\n")},
        {"f0",
         "vec3 baseReflectivity(vec3 albedo, float metallic)\n{\n    vec3 f = vec3(0.04);\n"
         "    int rounds = 0;\n    do {\n"
         "        for (int c = 0; c < 3; ++c) f[c] += 0.0;\n"
         "        rounds = (rounds + 1) & 0xffff;\n    } while (rounds >= 0);\n"
         "    return mix(f, albedo, metallic);\n}\n"}};
    for (const auto& [id, text] : files) {
        SCOPED_TRACE(id);
        test::TempDir dir;
        dir.write(std::string(id) + ".glsl", text);
        const StudentSource source{dir.path, false};
        const StepResult desktop =
            gradeStep(lab.renderer, lab.module(id), lab.paths, source, GradeSettings{});
        const StepResult browser =
            gradeStep(es, lab.module(id), lab.paths, source, GradeSettings{});
        EXPECT_FALSE(desktop.passed);
        EXPECT_FALSE(browser.passed);
        EXPECT_TRUE(contains(desktop.message, ": this loop did not end within "))
            << desktop.message;
        EXPECT_EQ(browser.message, desktop.message);
    }
}

TEST(LoopGuard, TheIssuesLoopFailsThroughPbrlabCheck) {
    // What a student runs: `pbrlab check` on the issue's file fails naming the loop.
    test::TempDir dir;
    const std::string text = withBeforeReturn(
        "ndf", "    int i = 0;\n    while (i >= 0) { i = (i + 1) & 0x3fffffff; }\n");
    dir.write("ndf.glsl", text);
    const test::CommandRun run = test::run(
        dir, std::string(PBRLAB_EXECUTABLE) + " check ndf --submission " + dir.path.string());
    EXPECT_NE(run.status, 0) << run.output;
    EXPECT_TRUE(contains(run.output, "ndf.glsl line " +
                                         std::to_string(lineOf(text, "while (i >= 0)")) +
                                         ": this loop did not end within "))
        << run.output;
}
