// Grading throughput (issue target: a full 21-module submission in <= 20 s wall on 2 cores).
// Reported as a ratio to a baseline measured in the same run: grading one module (ndotl, the
// cheapest: fork, context, compile, checks, robustness sweep), the unit a grade repeats.
// No GL context may exist in this process: the grader forks, and llvmpipe's threads do not
// survive a fork (a child would wait forever on a lock held by a thread it does not have).
#include <benchmark/benchmark.h>

#include <chrono>

#include "grade.h"
#include "kit.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

struct Kit {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR, paths.labs()};
    fs::path dir = fs::temp_directory_path() / "pbrlab-bench-kit";
    Kit() {
        fs::remove_all(dir);
        writeKit(modules, {dir, true, "", false});
        dir = fs::canonical(dir);
    }
    ~Kit() { fs::remove_all(dir); }
    GradeReport grade(std::vector<std::string> ids) {
        GradeOptions o;
        o.submission = dir;
        o.modules = std::move(ids);
        return gradeSubmission(modules, paths, o);
    }
};

void BM_GradeOneModuleBaseline(benchmark::State& state) {
    Kit kit;
    for (auto _ : state) benchmark::DoNotOptimize(kit.grade({"ndotl"}).seconds);
}
BENCHMARK(BM_GradeOneModuleBaseline)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_GradeFullSubmission(benchmark::State& state) {
    Kit kit;
    double baseline = 1e300;
    for (int i = 0; i < 3; ++i) baseline = std::min(baseline, kit.grade({"ndotl"}).seconds);
    double seconds = 0;
    for (auto _ : state) {
        GradeReport r = kit.grade({});
        seconds = r.seconds;
        if (r.score != r.maxScore) state.SkipWithError("the reference solutions did not pass");
    }
    state.counters["modules"] = double(kit.modules.modules().size());
    state.counters["seconds"] = seconds;
    state.counters["ratio_to_one_module"] = seconds / baseline;
    state.counters["target_seconds"] = 20;
}
BENCHMARK(BM_GradeFullSubmission)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
