// What lazy work saves on a glTF model, as ratios to baselines measured in the same run:
// - loading: loadGltf (geometry, materials, images kept encoded) against the baseline of
//   loading and decoding every image, which is what an eager loader does;
// - rendering: a warm frame (programs and textures cached) against the first frame of a
//   fresh renderer (compiles and texture loads), for ndotl (reads no map) and reflectance
//   (reads four maps of three images).
// A separate program from bench_grade: this one holds a GL context, which a grader that forks
// must not inherit.
#include <benchmark/benchmark.h>

#include <chrono>

#include "assets/gltf.h"
#include "gl/context.h"
#include "render/renderer.h"
#include "util/log.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

const fs::path kModel = fs::path(PBRLAB_SOURCE_DIR) / "assets/models/textured-sphere.glb";

double secondsOf(const std::function<void()>& f) {
    auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The project's model (4 images of 128^2), and the real-world one beside the repository
// when present (4 images of 2048^2, external files).
fs::path modelFor(int which) {
    return which == 0
               ? kModel
               : fs::path(PBRLAB_SOURCE_DIR) / "../shared/data/gltf/WaterBottle/WaterBottle.gltf";
}

double loadAndDecode(const fs::path& file) {
    return secondsOf([&] {
        ModelData model = loadGltf(file);
        for (const TextureSource& image : model.images)
            benchmark::DoNotOptimize(readTexture(image).pixels.data());
    });
}

void BM_LoadModelLazily(benchmark::State& state) {
    const fs::path file = modelFor(int(state.range(0)));
    if (!fs::exists(file)) {
        state.SkipWithError("../shared/data absent");
        for (auto _ : state) {
        }
        return;
    }
    double eager = 1e300, lazy = 0;
    for (int i = 0; i < 3; ++i) eager = std::min(eager, loadAndDecode(file));
    for (auto _ : state) lazy = secondsOf([&] { benchmark::DoNotOptimize(loadGltf(file)); });
    state.SetLabel(file.filename().string());
    state.counters["eager_ms"] = eager * 1e3;
    state.counters["ratio_to_eager_load"] = lazy / eager;
}
BENCHMARK(BM_LoadModelLazily)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(10);

struct Session {
    std::unique_ptr<GlContext> context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    Scene scene = sceneForModel(loadScene(paths.scene("sphere")), kModel);
};

Session& session() {
    static Session s;
    return s;
}

void renderWarmAgainstFirstFrame(benchmark::State& state, const std::string& id) {
    Session& s = session();
    const LoadedModule& m = s.modules.find(id);
    const ParamValues params(m.desc->params);
    double first = 0;
    int textures = 0;
    {
        LabRenderer fresh(s.paths);
        resetCounters();
        first = secondsOf([&] { fresh.renderScene(m, params, s.scene, {}, 256, 256, false); });
        textures = eventCount(Counter::TextureLoads);
    }
    LabRenderer renderer(s.paths);
    renderer.renderScene(m, params, s.scene, {}, 256, 256, false);
    double warm = 0;
    for (auto _ : state)
        warm = secondsOf([&] { renderer.renderScene(m, params, s.scene, {}, 256, 256, false); });
    state.counters["first_frame_ms"] = first * 1e3;
    state.counters["ratio_to_first_frame"] = warm / first;
    state.counters["textures_loaded"] = textures;
}

void BM_NdotlWarmFrame(benchmark::State& state) {
    renderWarmAgainstFirstFrame(state, "ndotl");
}
BENCHMARK(BM_NdotlWarmFrame)->Unit(benchmark::kMillisecond)->Iterations(10);

void BM_ReflectanceWarmFrame(benchmark::State& state) {
    renderWarmAgainstFirstFrame(state, "reflectance");
}
BENCHMARK(BM_ReflectanceWarmFrame)->Unit(benchmark::kMillisecond)->Iterations(10);

}  // namespace

BENCHMARK_MAIN();
