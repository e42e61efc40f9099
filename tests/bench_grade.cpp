// Grading throughput (issue target: a full 21-module submission in <= 20 s wall on 2 cores).
// Reported as a ratio to a baseline measured in the same run: one `check` of one module
// (context, compile, G-buffer, view, read-back, CPU reference), the unit a grade repeats.
#include <benchmark/benchmark.h>

#include <chrono>

#include "check.h"
#include "gl/context.h"
#include "grade.h"
#include "kit.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

double secondsOfOneCheck() {
    auto start = std::chrono::steady_clock::now();
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR, paths.labs()};
    LabRenderer renderer{paths};
    const LoadedModule& m = modules.find("ndotl");
    Scene scene = loadScene(paths.scene(m.desc->scene));
    checkModule(renderer, m, ParamValues(m.desc->params), scene, {}, 96, 96);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_OneCheckBaseline(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(secondsOfOneCheck());
}
BENCHMARK(BM_OneCheckBaseline)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_GradeFullSubmission(benchmark::State& state) {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR, paths.labs()};
    fs::path kit = fs::temp_directory_path() / "pbrlab-bench-kit";
    fs::remove_all(kit);
    writeKit(modules, {kit, true, "", false});
    double baseline = 1e300;
    for (int i = 0; i < 3; ++i) baseline = std::min(baseline, secondsOfOneCheck());
    GradeOptions o;
    o.submission = fs::canonical(kit);
    double seconds = 0;
    for (auto _ : state) {
        GradeReport r = gradeSubmission(modules, paths, o);
        seconds = r.seconds;
        if (r.score != r.maxScore) state.SkipWithError("the reference solutions did not pass");
    }
    state.counters["modules"] = double(modules.modules().size());
    state.counters["seconds"] = seconds;
    state.counters["ratio_to_one_check"] = seconds / baseline;
    state.counters["target_seconds"] = 20;
    fs::remove_all(kit);
}
BENCHMARK(BM_GradeFullSubmission)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
