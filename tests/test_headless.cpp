// End to end without a display or GPU: OSMesa context, module plugins, shaders, G-buffer,
// view, CPU reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <sstream>

#include "assets/image_io.h"
#include "gl/context.h"
#include "gl/objects.h"
#include "grading/grade_step.h"
#include "ibl/precompute.h"
#include "pbrlab/ibl_reference.h"
#include "render/evaluate.h"
#include "render/input_digest.h"
#include "test_support.h"
#include "util/error.h"
#include "util/log.h"

using namespace pbrlab;

namespace {

struct Headless {
    std::unique_ptr<GlContext> context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};

    // A renderer of its own whose cache is `cache`: nothing from, or into, the user's cache.
    LabRenderer rendererCachedIn(const test::TempDir& cache) const {
        RendererOptions options;
        options.cacheRoot = cache.path;
        return LabRenderer{paths, options};
    }

    StepResult check(const std::string& id, const StudentSource& source = {}) {
        return gradeStep(renderer, modules.find(id), paths, source, GradeSettings{});
    }
    static const CheckReport& named(const StepResult& r, const std::string& name) {
        for (const CheckReport& c : r.checks)
            if (c.name == name) return c;
        throw std::runtime_error("no check named " + name);
    }
};

}  // namespace

TEST(Headless, ContextIsOpenGL45Core) {
    auto context = createHeadlessContext();
    EXPECT_NE(context->description().find("4.5"), std::string::npos) << context->description();
}

TEST(Headless, NdotlSolutionMatchesCpuReference) {
    Headless h;
    StepResult r = h.check("ndotl");
    EXPECT_TRUE(r.passed) << r.message;
    // the sphere covers a good part of the frame
    EXPECT_GT(Headless::named(r, "scene sphere").points, 96 * 96 / 3);
    EXPECT_EQ(Headless::named(r, "probe").points, 65 * 17);
}

TEST(Headless, StudentWithoutClampIsCaught) {
    Headless h;
    test::TempDir kit;
    kit.write("ndotl.glsl", "float lambertCosine(vec3 N, vec3 L) { return dot(N, L); }\n");
    StepResult r = h.check("ndotl", {kit.path});
    EXPECT_FALSE(r.passed);
    // the half of the probe where L is below the surface
    EXPECT_GT(Headless::named(r, "probe").negative, 0);
}

TEST(Headless, StudentFileWithSyntaxErrorNamesFileAndLine) {
    Headless h;
    test::TempDir kit;
    auto file = kit.write("ndotl.glsl",
                          "// my answer\nfloat lambertCosine(vec3 N, vec3 L) {\n"
                          "    return max(dot(N, L), 0.0)\n}\n");
    try {
        h.check("ndotl", {kit.path});
        FAIL() << "compiled a broken file";
    } catch (const ShaderError& e) {
        std::string m = e.what();
        // Mesa reports the missing ';' on the line of the closing brace.
        EXPECT_NE(m.find(file.string() + ":4"), std::string::npos) << m;
    }
}

TEST(Headless, ProgramsAreCachedByDefineSet) {
    Headless h;
    h.check("ndotl");
    int compiles = h.renderer.programs().compileCount();
    h.check("ndotl");
    EXPECT_EQ(h.renderer.programs().compileCount(), compiles);
    // G-buffer; scene views for one and four lights (the lesson's grid); probe views for one,
    // three and seven (does it read the scene's lights? NUM_LIGHTS graded at two values) and
    // five (the stability sweep's) lights; the kit's stub on the first passed values check
    // (does the grade show work? assignment.h); reflectance's view, which calls lambertCosine
    // (the inputs its callers produce), compiled once: a second check compiles nothing.
    EXPECT_EQ(compiles, 9);
}

TEST(Headless, NdotlLoadsNoTextures) {
    resetCounters();
    Headless h;
    h.check("ndotl");
    EXPECT_EQ(eventCount(Counter::TextureLoads), 0);
    EXPECT_EQ(eventCount(Counter::PrecomputePasses), 0);
}

TEST(Headless, HotReloadKeepsTheLastGoodProgramWhenAnEditBreaksIt) {
    Headless h;
    test::TempDir kit;
    auto file = kit.write("ndotl.glsl",
                          "float lambertCosine(vec3 N, vec3 L) { return max(dot(N, L), 0.0); }\n");
    const LoadedModule& m = h.modules.find("ndotl");
    Scene scene = loadScene(h.paths.scene("sphere"));
    ParamValues params(m.desc->params);
    Image good = h.renderer.renderScene(m, params, scene, {kit.path}, 64, 64, false).value;

    // The student saves a broken file (a newer time stamp than the good one).
    kit.write("ndotl.glsl", "float lambertCosine(vec3 N, vec3 L) {\n  return oops;\n}\n");
    std::filesystem::last_write_time(
        file, std::filesystem::last_write_time(file) + std::chrono::seconds(2));
    try {
        h.renderer.renderScene(m, params, scene, {kit.path}, 64, 64, false);
        FAIL() << "broken file compiled";
    } catch (const ShaderError& e) {
        EXPECT_NE(std::string(e.what()).find(file.string() + ":2"), std::string::npos) << e.what();
    }
    // The next frame renders with the last good program: the same image as before.
    Image again = h.renderer.renderScene(m, params, scene, {kit.path}, 64, 64, false).value;
    EXPECT_EQ(again.pixels, good.pixels);

    // A fixed file is picked up again.
    kit.write("ndotl.glsl", "float lambertCosine(vec3 N, vec3 L) { return 0.5; }\n");
    std::filesystem::last_write_time(
        file, std::filesystem::last_write_time(file) + std::chrono::seconds(4));
    Image fixed = h.renderer.renderScene(m, params, scene, {kit.path}, 64, 64, false).value;
    EXPECT_NE(fixed.pixels, good.pixels);
}

namespace {

// split_sum's picture with small maps (the tests that use it are about the disk cache, not
// quality), each call by a fresh renderer (nothing in memory) that keeps its maps in `cache`.
struct CachedSplitSum {
    test::TempDir cache;
    Headless h;
    IblSettings small = [] {
        IblSettings s;
        s.environmentSize = 64;
        s.irradianceSize = 8;
        s.prefilterSize = 16;
        s.prefilterMips = 3;
        s.prefilterSamples = 16;
        s.lutWidth = s.lutHeight = 16;
        s.lutSamples = 32;
        return s;
    }();
    const LoadedModule& m = h.modules.find("split_sum");
    Scene scene = loadScene(h.paths.scene(m.desc->scene));
    const ParamValues params = ParamValues(m.desc->params);
    Image render() {
        RendererOptions options;
        options.cacheRoot = cache.path;
        LabRenderer r{h.paths, options};
        RenderRequest request{&m, &params, &scene, {}, nullptr, 48, 48};
        request.ibl = small;
        return r.render(request).value;
    }
};

}  // namespace

TEST(Headless, PrecomputedMapsAreCachedOnDiskAndReusedExactly) {
    CachedSplitSum t;
    IblSettings& small = t.small;
    auto render = [&] { return t.render(); };
    resetCounters();
    Image first = render();
    EXPECT_EQ(eventCount(Counter::PrecomputePasses), 4);  // cube, irradiance, prefilter, LUT
    resetCounters();
    Image again = render();
    EXPECT_EQ(eventCount(Counter::PrecomputePasses), 0);  // the environment cube too
    EXPECT_EQ(again.pixels, first.pixels);
    // Another setting is another key: computed again, the LUT apart from the maps that depend
    // on the environment (each is cached under what it depends on).
    small.lutWidth = small.lutHeight = 32;
    resetCounters();
    render();
    EXPECT_EQ(eventCount(Counter::PrecomputePasses), 1);  // the LUT
    small.bins = 8;
    resetCounters();
    render();
    EXPECT_EQ(eventCount(Counter::PrecomputePasses), 2);  // irradiance, prefilter
    // The cube depends on its size only (resampled on the CPU, no shader).
    small.environmentSize = 32;
    resetCounters();
    render();
    EXPECT_EQ(eventCount(Counter::PrecomputePasses), 3);  // cube, irradiance, prefilter
}

// Every cached file ends with a checksum of its payload: a file changed after it was written
// (a byte flipped on disk, a copy cut short) is not used, its maps are computed again.
TEST(Headless, ACachedMapChangedOnDiskIsComputedAgain) {
    CachedSplitSum t;
    const Image first = t.render();
    int changed = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(t.cache.path)) {
        if (!entry.is_regular_file() || entry.path().extension() != ".bin") continue;
        const std::string map = entry.path().stem().string();
        if (map != "environment" && map != "irradiance" && map != "prefilter" && map != "lut")
            continue;
        std::fstream file(entry.path(), std::ios::in | std::ios::out | std::ios::binary);
        const auto middle = std::streamoff(std::filesystem::file_size(entry.path()) / 2);
        file.seekg(middle);
        const char byte = char(file.get() ^ 0x10);
        file.seekp(middle);
        file.put(byte);
        ++changed;
    }
    ASSERT_EQ(changed, 4);  // cube, irradiance, prefilter, LUT
    resetCounters();
    const Image again = t.render();
    EXPECT_EQ(eventCount(Counter::PrecomputePasses), 4);
    EXPECT_EQ(again.pixels, first.pixels);
}

TEST(Headless, CachedMapsAreFoundWithoutReadingTheEnvironment) {
    test::TempDir cache;
    Headless h;
    IblSettings small;  // small maps: this test is about what is read, not quality
    small.environmentSize = 32;
    small.irradianceSize = 8;
    small.prefilterSize = 16;
    small.prefilterMips = 3;
    small.lutWidth = small.lutHeight = 16;
    IblPrecompute precompute(h.renderer.programs(), h.paths.shaders());
    IblDiskCache disk(cache.path);
    Image sky;
    sky.width = 64;
    sky.height = 32;
    sky.channels = 3;
    for (int i = 0; i < sky.width * sky.height; ++i)
        for (int c = 0; c < 3; ++c) sky.pixels.push_back(float(1 + (i * 7 + c * 3) % 11));
    int reads = 0;
    auto source = [&](const std::string& key) {
        return EquirectSource(key, [&] {
            ++reads;
            return sky;
        });
    };
    // First: nothing on disk, the pixels are read once for the cube and the derived maps.
    const EquirectSource first = source("test sky v1");
    auto maps = precompute.buildEnvironment(first, small, &disk);
    precompute.buildDerived(*maps, first, &disk);
    EXPECT_EQ(reads, 1);
    const auto cube = IblPrecompute::readCube(maps->environment.id(), 32, 6);
    const auto irradiance = IblPrecompute::readCube(maps->irradiance.id(), 8, 1);
    // The same key again: every map from disk, the pixels never read.
    const EquirectSource again = source("test sky v1");
    auto cached = precompute.buildEnvironment(again, small, &disk);
    precompute.buildDerived(*cached, again, &disk);
    EXPECT_EQ(reads, 1);
    EXPECT_EQ(IblPrecompute::readCube(cached->environment.id(), 32, 6)[0][2].pixels,
              cube[0][2].pixels);
    EXPECT_EQ(IblPrecompute::readCube(cached->irradiance.id(), 8, 1)[0][4].pixels,
              irradiance[0][4].pixels);
    // Another key is another environment: read and computed.
    const EquirectSource other = source("test sky v2");
    precompute.buildEnvironment(other, small, &disk);
    EXPECT_EQ(reads, 2);
}

TEST(Headless, AnEnvironmentFileChangedOnDiskIsReadAgain) {
    // A file's source key is its path, size and time (no read): a new file under the same
    // name gives other maps, not the cached ones of the old file.
    test::TempDir cache, files;
    Headless h;
    const LoadedModule& m = h.modules.find("irradiance");
    Scene scene = loadScene(h.paths.scene(m.desc->scene));
    const std::filesystem::path file = files.path / "sky.hdr";
    scene.environment = file.string();
    const ParamValues params(m.desc->params);
    auto skyOf = [](float level) {
        Image sky;
        sky.width = 64;
        sky.height = 32;
        sky.channels = 3;
        sky.pixels.assign(size_t(64 * 32 * 3), level);
        return sky;
    };
    auto render = [&] {
        LabRenderer r = h.rendererCachedIn(cache);
        RenderRequest request{&m, &params, &scene, {}, nullptr, 32, 32};
        return r.render(request).value;
    };
    writeImage(file, skyOf(1.0f), FileDepth::Float32);
    const Image dim = render();
    EXPECT_EQ(render().pixels, dim.pixels);  // from the cache
    const auto time = std::filesystem::last_write_time(file);
    writeImage(file, skyOf(4.0f), FileDepth::Float32);
    std::filesystem::last_write_time(file, time + std::chrono::seconds(2));
    const Image bright = render();
    EXPECT_NE(bright.pixels, dim.pixels);
    double dimSum = 0, brightSum = 0;
    for (size_t i = 0; i < dim.pixels.size(); i += 4) dimSum += dim.pixels[i];
    for (size_t i = 0; i < bright.pixels.size(); i += 4) brightSum += bright.pixels[i];
    EXPECT_NEAR(brightSum, 4 * dimSum, 1e-3 * brightSum);  // irradiance is linear in radiance
}

TEST(Headless, ARenderIsAFunctionOfItsRequest) {
    // The renderer keeps no modes between calls: a request with other IBL settings in between
    // leaves the next render of a request exactly as it was. Not vacuous: the two settings do
    // reach the maps the view reads (their pictures differ).
    test::TempDir cache;
    Headless h;
    LabRenderer renderer = h.rendererCachedIn(cache);
    const IblSettings small = test::smallMaps();
    IblSettings smaller = small;
    smaller.irradianceSize = 4;
    smaller.prefilterSize = 8;
    const LoadedModule& m = h.modules.find("split_sum");
    const Scene scene = loadScene(h.paths.scene(m.desc->scene));
    const ParamValues params(m.desc->params);
    auto render = [&](const IblSettings& ibl) {
        RenderRequest request{&m, &params, &scene, {}, nullptr, 32, 32};
        request.ibl = ibl;
        return renderer.render(request).value;
    };
    const Image a = render(small);
    const Image b = render(smaller);
    EXPECT_NE(a.pixels, b.pixels);
    EXPECT_EQ(render(small).pixels, a.pixels);
    EXPECT_EQ(render(smaller).pixels, b.pixels);
}

TEST(Headless, ADrawInBandsShadesEveryPixelAsOneDrawDoes) {
    // The evaluation thread draws in bands (gl::setDrawBudgetOnThisThread) so that the
    // window's context, which shares llvmpipe's rasterizer, waits one band, not a whole view
    // pass. The pictures must not change: split_sum's precompute passes (irradiance,
    // prefilter, LUT) and its view, and prefilter's, are the same to the bit with bands of
    // two rows and with one draw.
    Headless h;
    const IblSettings small = test::smallMaps();
    auto render = [&](const std::string& id, double budgetMs) {
        test::TempDir cache;  // the maps precomputed again, under this budget
        RendererOptions options;
        options.cacheRoot = cache.path;
        LabRenderer renderer{h.paths, options};
        const LoadedModule& m = h.modules.find(id);
        const Scene scene = loadScene(h.paths.scene(m.desc->scene));
        const ParamValues params(m.desc->params);
        RenderRequest request{&m, &params, &scene, {}, nullptr, 96, 96};
        request.ibl = small;
        gl::setDrawBudgetOnThisThread(budgetMs);
        Image value = renderer.render(request).value;
        gl::setDrawBudgetOnThisThread(0);
        return value;
    };
    for (const char* id : {"prefilter", "split_sum"}) {
        // 1e-6 ms: every band is the smallest, two rows.
        const Image banded = render(id, 1e-6), whole = render(id, 0);
        ASSERT_FALSE(whole.pixels.empty());
        EXPECT_EQ(banded.pixels, whole.pixels) << id;
    }
    // The bands did happen, and leave the scissor test as they found it.
    gl::RenderTarget target(32, 96, 1, false);
    target.bind();
    gl::Viewport(0, 0, 32, 96);
    const gl::FullscreenTriangle triangle;
    gl::setDrawBudgetOnThisThread(1e-6);
    EXPECT_EQ(triangle.draw(), 1 + (96 - 16) / 2);  // a first band of 16 rows, then 2 each
    // A generous budget: the bands grow from the first (16, 24, 36, then the 20 rows left).
    gl::setDrawBudgetOnThisThread(1e6);
    EXPECT_EQ(triangle.draw(), 4);
    // The next band fits the budget at the last one's cost, grows at most 1.5 times, and
    // grows back from the smallest (a band slowed once does not leave the rest at 2 rows).
    EXPECT_EQ(gl::nextBandRows(16, 16, 8), 8);
    EXPECT_EQ(gl::nextBandRows(16, 1, 8), 24);
    EXPECT_EQ(gl::nextBandRows(16, 1000, 8), 2);
    EXPECT_EQ(gl::nextBandRows(2, 0.1, 8), 4);
    EXPECT_EQ(gl::nextBandRows(4, 0.1, 8), 6);
    gl::setDrawBudgetOnThisThread(0);
    EXPECT_EQ(triangle.draw(), 1);
    EXPECT_FALSE(gl::IsEnabled(GL_SCISSOR_TEST));
}

TEST(Headless, AReusedGBufferIsOnlyEverTheSceneOnScreen) {
    // The GUI's evaluation thread reuses the G-buffer it holds when the scene's key is the
    // same (an edit of a light or a parameter). Every picture equals a fresh renderer's: a
    // light's edit, then the camera's (a new key: drawn again), then back.
    Headless h;
    const LoadedModule& m = h.modules.find("ndf");
    Scene scene = loadScene(h.paths.scene("sphere-grid"));
    const ParamValues params(m.desc->params);
    LabRenderer reusing{h.paths, RendererOptions{{}, {}}};
    auto render = [&](LabRenderer& renderer, bool reuse) {
        RenderRequest request{&m, &params, &scene, {}, nullptr, 64, 64};
        request.reuseGBuffer = reuse;
        request.readSurfaces = true;
        const RenderResult r = renderer.render(request);
        return std::make_pair(r.value.pixels, r.surfaces.size());
    };
    auto fresh = [&] {
        LabRenderer renderer{h.paths, RendererOptions{{}, {}}};
        return render(renderer, false);
    };
    EXPECT_EQ(render(reusing, true), fresh());
    scene.lights[0].position += glm::dvec3(1, 0, 0);
    EXPECT_EQ(render(reusing, true), fresh());
    const glm::dvec3 camera = scene.camera.position;
    scene.camera.position += glm::dvec3(0.5, 0.2, 0);
    EXPECT_EQ(render(reusing, true), fresh());
    scene.camera.position = camera;
    EXPECT_EQ(render(reusing, true), fresh());
}

TEST(Headless, StudentFilesCannotIncludeTheReferenceSolutions) {
    Headless h;
    test::TempDir kit;
    // Resolvable from the labs root for the host's own files, but not for a student's.
    auto file = kit.write("ndotl.glsl", "#include \"ndotl/solution.glsl\"\n");
    try {
        h.check("ndotl", {kit.path});
        FAIL() << "a student file read the reference solution";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(file.string() + ":1"), std::string::npos) << e.what();
    }
    // Their own helpers next to the file are fine.
    kit.write("my_helpers.glsl", "float myClamp(float x) { return max(x, 0.0); }\n");
    kit.write("ndotl.glsl",
              "#include \"my_helpers.glsl\"\n"
              "float lambertCosine(vec3 N, vec3 L) { return myClamp(dot(N, L)); }\n");
    EXPECT_TRUE(h.check("ndotl", {kit.path}).passed);
}

TEST(Headless, ASceneAtTheLightLimitRenders) {
    // Every light is a uniform array element in every program: at the limit it still compiles,
    // in the step that sums all the lights and in one that reads the first.
    Headless h;
    test::TempDir dir;
    std::string lights;
    for (size_t i = 0; i < kMaxSceneLights; ++i)
        lights += std::string(i ? ", " : "") + R"({"position": [)" + std::to_string(double(i) / 8) +
                  R"(, 3, 5], "color": [0.5, 0.5, 0.5]})";
    const Scene scene = loadScene(dir.write(
        "lights.json", R"({"lights": [)" + lights +
                           R"(], "objects": [{"material": {"albedo": [0.5, 0.5, 0.5]}}]})"));
    ASSERT_EQ(scene.lights.size(), kMaxSceneLights);
    for (const char* id : {"ndotl", "reflectance"}) {
        const LoadedModule& m = h.modules.find(id);
        const RenderResult r =
            h.renderer.renderScene(m, ParamValues(m.desc->params), scene, {}, 16, 16, false);
        float brightest = 0;  // of the colour channels (alpha is 1 wherever evaluated)
        for (size_t i = 0; i < r.value.pixels.size(); ++i)
            if (int(i % size_t(r.value.channels)) < 3)
                brightest = std::max(brightest, r.value.pixels[i]);
        EXPECT_GT(brightest, 0.0f) << id;
    }
}

// The white furnace (docs/ibl.md): split_sum's solution on the scene `furnace`, white metal
// spheres (F0 = 1) in radiance 1, shows what single-scattering GGX loses. Where a sphere faces
// the camera the picture is the LUT's A + B at that N.V, from 0.99 at roughness 0.25 to 0.31 at
// 1, against the background's 1. Tolerance 0.02 of the exact A + B: the host's LUT is within
// 0.0196 of it (docs/ibl.md, "Error of the maps"); measured here 0.0144 at roughness 1, where
// the LUT's last row lies at roughness 0.98, and 0.0065 at 0.25.
TEST(Headless, TheWhiteFurnaceShowsWhatTheSplitSumLoses) {
    Headless h;
    const Scene scene = loadScene(h.paths.scene("furnace"));
    const LoadedModule& m = h.modules.find("split_sum");
    const RenderResult r =
        h.renderer.renderScene(m, ParamValues(m.desc->params), scene, {}, 256, 256, true);
    std::map<double, size_t> facing;  // per roughness, the pixel whose N.V is the largest
    for (size_t i = 0; i < r.surfaces.size(); ++i) {
        const Surface& s = r.surfaces[i];
        if (!s.covered) continue;
        auto [it, added] = facing.try_emplace(s.roughness, i);
        const Surface& best = r.surfaces[it->second];
        if (glm::dot(s.normal, s.view) > glm::dot(best.normal, best.view)) it->second = i;
    }
    ASSERT_EQ(facing.size(), 5u);
    for (const auto& [roughness, i] : facing) {
        const Surface& s = r.surfaces[i];
        const double NdotV = glm::dot(s.normal, s.view);
        EXPECT_GT(NdotV, 0.999) << "roughness " << roughness;
        const glm::dvec2 ab = ref::brdfLutExact(NdotV, roughness);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(r.value.pixels[i * 4 + size_t(c)], ab.x + ab.y, 0.02)
                << "roughness " << roughness;
    }
    // The loss is the lesson: the rougher, the darker; the roughest keeps a third at normal view.
    double before = 2;
    for (const auto& [roughness, i] : facing) {
        EXPECT_LT(r.value.pixels[i * 4], before) << "roughness " << roughness;
        before = r.value.pixels[i * 4];
    }
    EXPECT_LT(before, 0.34);
}

// What GLSL leaves undefined and a student's code reaches is defined in every program, so that
// a grade does not depend on the GPU: a light read past NUM_LIGHTS is a black light at the
// last light's position (Mesa read zeros there, WebGL the last light), and pow of a negative
// base is NaN (Mesa's answer; SwiftShader, the browser's, gave a number).
TEST(Headless, WhatGlslLeavesUndefinedReadsTheSameOnEveryGpu) {
    Headless h;
    test::TempDir dir;
    const Scene scene = loadScene(
        dir.write("lights.json", R"({"lights": [{"position": [1, 3, 5], "color": [0.5, 0.5, 0.5]},
                                      {"position": [-2, 4, 6], "color": [1, 1, 1]}],
                           "objects": [{"material": {"albedo": [0.5, 0.5, 0.5]}}]})"));
    const LoadedModule& m = h.modules.find("ndotl");
    auto centre = [&](const std::string& body) {
        test::TempDir kit;
        kit.write("ndotl.glsl", "float lambertCosine(vec3 N, vec3 L)\n{\n" + body + "\n}\n");
        const RenderResult r =
            h.renderer.renderScene(m, ParamValues(m.desc->params), scene, {kit.path}, 8, 8, false);
        return r.value.pixels[(4 * 8 + 4) * size_t(r.value.channels)];
    };
    // A loop with a hard-coded count: the index is not a constant, as in a loop.
    const std::string past = "    int i = NUM_LIGHTS + 5 + int(0.0 * N.x);\n";
    EXPECT_EQ(centre(past + "    return length(uLightColors[i]);"), 0.0f);
    EXPECT_EQ(centre(past + "    return distance(uLightPositions[i], vec3(-2, 4, 6));"), 0.0f);
    EXPECT_EQ(centre("    return length(uLightColors[1]);"), float(std::sqrt(3.0)));
    EXPECT_TRUE(std::isnan(centre("    return pow(-0.5 + 0.0 * N.x, 2.0);")));
    EXPECT_TRUE(
        std::isnan(centre("    return pow(vec3(1.0, -0.5 + 0.0 * N.x, 1.0), vec3(2.0)).y;")));
    EXPECT_EQ(centre("    return pow(0.5 + 0.0 * N.x, 2.0);"), 0.25f);
}

TEST(Headless, ABandIsReusedOnlyForTheInputsItWasBuiltFrom) {
    // The GUI's evaluation keeps its last band (BandCache): a student's edit changes GLSL only,
    // and the band it needs is the one already built. Every input the band reads (a parameter,
    // the camera, a material, the environment's maps) builds it again, and a band taken from
    // the cache is exactly the band built afresh for the same request.
    test::TempDir cache;
    Headless h;
    LabRenderer renderer = h.rendererCachedIn(cache);
    BandCache bands;
    auto evaluateBoth = [&](const LoadedModule& m, const ParamValues& params, const Scene& scene,
                            const StudentSource& source, const IblSettings& ibl) {
        EvalRequest request;
        request.render = {&m, &params, &scene, source, nullptr, 32, 32};
        request.render.ibl = ibl;
        request.bandCache = &bands;
        const Evaluation cached = evaluate(renderer, request);
        request.bandCache = nullptr;
        const Evaluation fresh = evaluate(renderer, request);
        EXPECT_EQ(cached.band.expected, fresh.band.expected);
        EXPECT_EQ(cached.band.lo, fresh.band.lo);
        EXPECT_EQ(cached.band.hi, fresh.band.hi);
        EXPECT_EQ(cached.band.slack, fresh.band.slack);
        EXPECT_EQ(cached.comparison.outside, fresh.comparison.outside);
        EXPECT_EQ(cached.comparison.worstExcess, fresh.comparison.worstExcess);
        return cached;
    };
    auto counts = [&] { return std::make_pair(bands.built(), bands.reused()); };
    using Counts = std::pair<int, int>;

    const LoadedModule& ndf = h.modules.find("ndf");
    Scene scene = loadScene(h.paths.scene(ndf.desc->scene));
    ParamValues params(ndf.desc->params);
    const IblSettings ibl = test::smallMaps();
    const Evaluation solution = evaluateBoth(ndf, params, scene, {}, ibl);
    EXPECT_EQ(solution.comparison.outside, 0);
    EXPECT_EQ(counts(), Counts(1, 0));
    // A student's edit: another picture, the same band.
    test::TempDir kit;
    kit.write("ndf.glsl",
              "float distributionGGX(vec3 N, vec3 H, float roughness) {\n"
              "    float a2 = roughness * roughness * roughness * roughness;\n"
              "    float d = max(dot(N, H), 0.0) * max(dot(N, H), 0.0) * (a2 - 1.0) + 1.0;\n"
              "    return a2 / (d * d);\n"  // without pi
              "}\n");
    const Evaluation student = evaluateBoth(ndf, params, scene, {kit.path}, ibl);
    EXPECT_GT(student.comparison.outside, 0);
    EXPECT_EQ(counts(), Counts(1, 1));
    // Each input the band reads.
    params.set("light_dir", glm::normalize(glm::dvec3(-3, 4, 6)));
    evaluateBoth(ndf, params, scene, {kit.path}, ibl);
    EXPECT_EQ(counts(), Counts(2, 1));
    scene.camera.position += glm::dvec3(0.25, 0, 0);
    evaluateBoth(ndf, params, scene, {kit.path}, ibl);
    EXPECT_EQ(counts(), Counts(3, 1));
    ASSERT_FALSE(scene.materials.empty());
    scene.materials[0].roughness = 0.8;
    evaluateBoth(ndf, params, scene, {kit.path}, ibl);
    EXPECT_EQ(counts(), Counts(4, 1));
    evaluateBoth(ndf, params, scene, {}, ibl);
    EXPECT_EQ(counts(), Counts(4, 2));

    // The environment's maps, for a step that reads them.
    const LoadedModule& splitSum = h.modules.find("split_sum");
    const Scene sky = loadScene(h.paths.scene(splitSum.desc->scene));
    const ParamValues splitSumParams(splitSum.desc->params);
    IblSettings smaller = ibl;
    smaller.irradianceSize = 4;
    smaller.prefilterSize = 8;
    evaluateBoth(splitSum, splitSumParams, sky, {}, ibl);
    EXPECT_EQ(counts(), Counts(5, 2));
    evaluateBoth(splitSum, splitSumParams, sky, {}, smaller);
    EXPECT_EQ(counts(), Counts(6, 2));
    evaluateBoth(splitSum, splitSumParams, sky, {}, smaller);
    EXPECT_EQ(counts(), Counts(6, 3));
}

// The keys of what is kept of a render and of a band (render/input_digest.h): each input
// changed on its own changes the key; a student's files give no key.
TEST(InputDigest, EveryDoubleOfASurfaceIsInItsKey) {
    auto key = [](const Surface& s) {
        Digest d;
        addInputs(d, s);
        return d.h;
    };
    Surface base;
    base.covered = true;
    const std::uint64_t baseKey = key(base);
    Surface uncovered = base;
    uncovered.covered = false;
    EXPECT_NE(key(uncovered), baseKey);
    // Every double after `covered`, found by its place, not by a list of names: a field added
    // to Surface is checked here without a change.
    const size_t first = offsetof(Surface, position) / sizeof(double);
    const size_t count = sizeof(Surface) / sizeof(double);
    ASSERT_GT(count, first + 30);
    for (size_t i = first; i < count; ++i) {
        Surface changed = base;
        double* slots = reinterpret_cast<double*>(&changed);
        slots[i] += 0.125;
        EXPECT_NE(key(changed), baseKey) << "double " << i << " of Surface";
    }
}

TEST(InputDigest, EveryInputOfARenderIsInItsKey) {
    Headless h;
    const LoadedModule& ndf = h.modules.find("ndf");
    const Scene scene = loadScene(h.paths.scene("sphere-grid"));
    const ParamValues params(ndf.desc->params);
    ASSERT_FALSE(scene.lights.empty());
    ASSERT_FALSE(scene.materials.empty());
    ASSERT_FALSE(scene.objects.empty());
    const RenderRequest base{&ndf, &params, &scene, {}, nullptr, 32, 32};
    const std::optional<std::uint64_t> baseKey = renderInputs(h.renderer, base);
    ASSERT_TRUE(baseKey.has_value());
    EXPECT_EQ(renderInputs(h.renderer, base), baseKey);  // a function of the request

    auto changedScene = [&](const char* what, const std::function<void(Scene&)>& change) {
        Scene s = scene;
        change(s);
        RenderRequest r = base;
        r.scene = &s;
        EXPECT_NE(renderInputs(h.renderer, r), baseKey) << what;
    };
    changedScene("camera position", [](Scene& s) { s.camera.position.x += 0.1; });
    changedScene("camera target", [](Scene& s) { s.camera.target.y += 0.1; });
    changedScene("field of view", [](Scene& s) { s.camera.fovY += 1; });
    changedScene("light position", [](Scene& s) { s.lights[0].position.z += 0.1; });
    changedScene("light colour", [](Scene& s) { s.lights[0].color.r += 0.1; });
    changedScene("one light more", [](Scene& s) { s.lights.push_back(s.lights[0]); });
    changedScene("material albedo", [](Scene& s) { s.materials[0].albedo.g += 0.1; });
    changedScene("metallic", [](Scene& s) { s.materials[0].metallic += 0.1; });
    changedScene("roughness", [](Scene& s) { s.materials[0].roughness += 0.1; });
    changedScene("ao", [](Scene& s) { s.materials[0].ao -= 0.1; });
    changedScene("occlusion strength", [](Scene& s) { s.materials[0].occlusionStrength -= 0.1; });
    changedScene("normal scale", [](Scene& s) { s.materials[0].normalScale += 0.1; });
    changedScene("emissive", [](Scene& s) { s.materials[0].emissive.b += 0.1; });
    changedScene("a map", [](Scene& s) { s.materials[0].normalMap.key = "other.png"; });
    changedScene("a map's wrap",
                 [](Scene& s) { s.materials[0].albedoMap.wrapU = TextureSource::Wrap::Mirror; });
    changedScene("object place", [](Scene& s) { s.objects[0].translate.x += 0.1; });
    changedScene("object scale", [](Scene& s) { s.objects[0].scale += 0.1; });
    changedScene("object material", [](Scene& s) { s.objects[0].material += 1; });
    changedScene("object model", [](Scene& s) { s.objects[0].model += 1; });
    changedScene("environment", [](Scene& s) { s.environment = "other.hdr"; });

    auto changedRequest = [&](const char* what, const std::function<void(RenderRequest&)>& change) {
        RenderRequest r = base;
        change(r);
        EXPECT_NE(renderInputs(h.renderer, r), baseKey) << what;
    };
    ParamValues turned = params;
    turned.set("light_dir", glm::normalize(glm::dvec3(-3, 4, 6)));
    changedRequest("a parameter", [&](RenderRequest& r) { r.params = &turned; });
    changedRequest("width", [](RenderRequest& r) { r.width = 33; });
    changedRequest("height", [](RenderRequest& r) { r.height = 31; });
    changedRequest("view", [](RenderRequest& r) { r.view = "other"; });
    changedRequest("coarse spheres", [](RenderRequest& r) { r.coarseSpheres = true; });
    changedRequest("seamless cubes", [](RenderRequest& r) { r.seamlessCubes = false; });
    changedRequest("isolated points", [](RenderRequest& r) { r.isolatePoints = true; });
    changedRequest("read surfaces", [](RenderRequest& r) { r.readSurfaces = true; });
    changedRequest("IBL settings", [](RenderRequest& r) { r.ibl.irradianceSize *= 2; });
    changedRequest("another module", [&](RenderRequest& r) { r.module = &h.modules.find("g1"); });
    const std::vector<Surface> points(4);
    changedRequest("given surfaces", [&](RenderRequest& r) { r.surfaces = &points; });
    // Not inputs: where a G-buffer comes from (drawn, on disk, kept) returns the same values.
    RenderRequest cached = base;
    cached.cacheGBuffer = cached.reuseGBuffer = true;
    EXPECT_EQ(renderInputs(h.renderer, cached), baseKey);
    // A student's files are read, not digested: no key.
    RenderRequest student = base;
    student.source.dir = "/nonexistent";
    EXPECT_FALSE(renderInputs(h.renderer, student).has_value());
}

TEST(InputDigest, EveryInputOfABandIsInItsKey) {
    Headless h;
    const ModuleDesc& ndf = *h.modules.find("ndf").desc;
    const Scene scene = loadScene(h.paths.scene("sphere"));
    const ParamValues params(ndf.params);
    const IblSettings ibl = test::smallMaps();
    std::vector<Surface> surfaces(3);
    const ReferenceContext context{params, {{glm::dvec3(1, 2, 3), glm::dvec3(1)}}, glm::dvec3(0)};
    const std::uint64_t baseKey = bandInputs(h.renderer, ndf, scene, context, ibl, surfaces);
    EXPECT_EQ(bandInputs(h.renderer, ndf, scene, context, ibl, surfaces), baseKey);
    ParamValues other = params;
    other.set("light_dir", glm::normalize(glm::dvec3(-3, 4, 6)));
    EXPECT_NE(bandInputs(h.renderer, ndf, scene, {other, context.lights, context.cameraPosition},
                         ibl, surfaces),
              baseKey);
    EXPECT_NE(
        bandInputs(h.renderer, ndf, scene,
                   {params, {{glm::dvec3(1, 2, 4), glm::dvec3(1)}}, glm::dvec3(0)}, ibl, surfaces),
        baseKey);
    EXPECT_NE(bandInputs(h.renderer, ndf, scene, {params, {}, glm::dvec3(0)}, ibl, surfaces),
              baseKey);
    EXPECT_NE(bandInputs(h.renderer, ndf, scene, {params, context.lights, glm::dvec3(0, 0, 1)}, ibl,
                         surfaces),
              baseKey);
    std::vector<Surface> moved = surfaces;
    moved[2].roughness = 0.9;
    EXPECT_NE(bandInputs(h.renderer, ndf, scene, context, ibl, moved), baseKey);
    moved.pop_back();
    EXPECT_NE(bandInputs(h.renderer, ndf, scene, context, ibl, moved), baseKey);
    // The module: another, or the same one with another tolerance (a grader's altered copy).
    EXPECT_NE(bandInputs(h.renderer, *h.modules.find("g1").desc, scene, context, ibl, surfaces),
              baseKey);
    ModuleDesc altered = ndf;
    altered.tolerance.relative *= 2;
    const std::uint64_t alteredKey = bandInputs(h.renderer, altered, scene, context, ibl, surfaces);
    ModuleDesc alteredAgain = altered;
    alteredAgain.tolerance.relative *= 2;
    EXPECT_NE(bandInputs(h.renderer, alteredAgain, scene, context, ibl, surfaces), alteredKey);
    // The environment's maps, for a module that reads them: other settings, another key.
    const ModuleDesc& splitSum = *h.modules.find("split_sum").desc;
    const Scene sky = loadScene(h.paths.scene(splitSum.scene));
    IblSettings smaller = ibl;
    smaller.irradianceSize = 4;
    EXPECT_NE(bandInputs(h.renderer, splitSum, sky, context, ibl, surfaces),
              bandInputs(h.renderer, splitSum, sky, context, smaller, surfaces));
}

TEST(Headless, BandCacheKeepsTheMostRecentlyUsed) {
    BandCache bands(2);
    Band a, b, c;
    a.resize(1);
    b.resize(2);
    c.resize(3);
    bands.keep(1, a);
    bands.keep(2, b);
    ASSERT_NE(bands.find(1), nullptr);  // 1 is now the most recently used
    bands.keep(3, c);                   // and 2 goes
    EXPECT_EQ(bands.find(2), nullptr);
    ASSERT_NE(bands.find(1), nullptr);
    EXPECT_EQ(bands.find(1)->expected.size(), 1u);
    ASSERT_NE(bands.find(3), nullptr);
    EXPECT_EQ(bands.find(3)->expected.size(), 3u);
    EXPECT_EQ(bands.built(), 3);
    EXPECT_EQ(bands.reused(), 5);  // the five finds that found
}

TEST(Headless, GradesThatShareTheirBandsGradeAsGradesAlone) {
    // The page's grader keeps the checks' bands from one file to the next (GradeSettings::
    // bands): every grade of a file must be the grade it gets alone, check by check, and the
    // files after the first build few bands or none.
    Headless h;
    BandCache bands(64);
    GradeSettings shared;
    shared.bands = &bands;
    namespace fs = std::filesystem;
    const fs::path root = PBRLAB_SOURCE_DIR;
    for (const std::string id : {"ndf", "fresnel"}) {
        std::vector<fs::path> files = {root / "labs" / id / "solution.glsl"};
        for (const auto& entry : fs::directory_iterator(root / "labs" / id / "mistakes"))
            files.push_back(entry.path());
        std::sort(files.begin() + 1, files.end());
        for (const fs::path& file : files) {
            test::TempDir kit;
            std::ifstream in(file, std::ios::binary);
            std::stringstream text;
            text << in.rdbuf();
            kit.write(id + ".glsl", text.str());
            const int builtBefore = bands.built();
            const StepResult alone =
                gradeStep(h.renderer, h.modules.find(id), h.paths, {kit.path}, GradeSettings{});
            const StepResult after =
                gradeStep(h.renderer, h.modules.find(id), h.paths, {kit.path}, shared);
            SCOPED_TRACE(file.string());
            EXPECT_EQ(after.passed, alone.passed);
            EXPECT_EQ(after.message, alone.message);
            EXPECT_EQ(after.mistakeGroup, alone.mistakeGroup);
            ASSERT_EQ(after.checks.size(), alone.checks.size());
            for (size_t i = 0; i < alone.checks.size(); ++i) {
                EXPECT_EQ(after.checks[i].name, alone.checks[i].name);
                EXPECT_EQ(after.checks[i].passed, alone.checks[i].passed);
                EXPECT_EQ(after.checks[i].outside, alone.checks[i].outside);
                EXPECT_EQ(after.checks[i].worstExcess, alone.checks[i].worstExcess);
            }
            if (file != files.front()) {
                EXPECT_EQ(bands.built(), builtBefore) << "new bands";
            }
        }
    }
    EXPECT_GT(bands.reused(), 0);
}
