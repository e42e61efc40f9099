// Grading throughput (issue 12 on 2 cores, llvmpipe: a correct 21-step submission in <= 8 s,
// any submission in <= 20 s). Three submissions:
//   correct    the reference solutions (`pbrlab kit --with-solutions`)
//   stub       the kit as students get it (every step still its neutral stub)
//   all-wrong  every step one typical mistake (labs/<id>/mistakes, the first by name)
// each graded in turn with a baseline, pair by pair, so a machine that slows down during the
// run slows both: grading one module (ndotl, the cheapest: fork, context, compiles, checks,
// robustness sweep), the unit a grade repeats. Reported: the medians of the submission's
// seconds, of the baseline's and of the pairs' ratios. The caches (IBL maps, converged
// integrals) are warm after an uncounted first grade, as on a grader that has graded once;
// "correct, empty caches" gives every grade an empty cache folder of its own.
// No GL context may exist in this process: the grader forks, and llvmpipe's threads do not
// survive a fork (a child would wait forever on a lock held by a thread it does not have).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>

#include "course/autograder.h"
#include "course/kit.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

constexpr int kPairs = 5;  // medians of five

struct Submissions {
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    fs::path root = fs::temp_directory_path() / "pbrlab-bench-grade";
    fs::path correct = root / "correct", stub = root / "stub", wrong = root / "all-wrong";
    Submissions() {
        fs::remove_all(root);
        writeKit(modules, {correct, true, "", false});
        writeKit(modules, {stub, false, "", false});
        fs::create_directories(wrong);
        for (const LoadedModule& m : modules.modules()) {
            std::vector<fs::path> mistakes;
            for (const auto& e : fs::directory_iterator(m.sourceDir / "mistakes"))
                if (e.path().extension() == ".glsl") mistakes.push_back(e.path());
            std::sort(mistakes.begin(), mistakes.end());
            if (!mistakes.empty()) fs::copy_file(mistakes.front(), wrong / (m.desc->id + ".glsl"));
        }
        correct = fs::canonical(correct);
        stub = fs::canonical(stub);
        wrong = fs::canonical(wrong);
    }
    ~Submissions() { fs::remove_all(root); }
    GradeReport grade(const fs::path& dir, std::vector<std::string> ids = {}) {
        GradeOptions o;
        o.submission = dir;
        o.modules = std::move(ids);
        return gradeSubmission(modules, paths, o);
    }
};

Submissions& submissions() {
    static Submissions s;
    return s;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty()      ? 0
           : v.size() % 2 ? v[v.size() / 2]
                          : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// Grades `dir` and the one-module baseline in turn, kPairs times. `passes`: every step is
// expected to pass (else none).
void gradeAgainstBaseline(benchmark::State& state, const fs::path& dir, bool passes,
                          bool emptyCaches) {
    Submissions& s = submissions();
    const fs::path caches = s.root / "caches";
    auto useCache = [&](int round) {
        if (emptyCaches) setenv("PBRLAB_CACHE", (caches / std::to_string(round)).c_str(), 1);
    };
    if (!emptyCaches) s.grade(dir);  // uncounted: warms the caches
    std::vector<double> seconds, baseline, ratios;
    int round = 0;
    for (auto _ : state) {
        for (int pair = 0; pair < kPairs; ++pair) {
            useCache(round++);
            const GradeReport r = s.grade(dir);
            useCache(round++);
            const double one = s.grade(s.correct, {"ndotl"}).seconds;
            if (r.score != (passes ? r.maxScore : 0))
                state.SkipWithError("the submission did not get its expected score");
            seconds.push_back(r.seconds);
            baseline.push_back(one);
            ratios.push_back(r.seconds / one);
        }
        state.SetIterationTime(median(seconds));
    }
    if (emptyCaches) {
        unsetenv("PBRLAB_CACHE");
        fs::remove_all(caches);
    }
    state.counters["seconds"] = median(seconds);
    state.counters["one_module_seconds"] = median(baseline);
    state.counters["ratio_to_one_module"] = median(ratios);
}

void BM_GradeCorrect(benchmark::State& state) {
    gradeAgainstBaseline(state, submissions().correct, true, false);
}
void BM_GradeStub(benchmark::State& state) {
    gradeAgainstBaseline(state, submissions().stub, false, false);
}
void BM_GradeAllWrong(benchmark::State& state) {
    gradeAgainstBaseline(state, submissions().wrong, false, false);
}
void BM_GradeCorrectEmptyCaches(benchmark::State& state) {
    gradeAgainstBaseline(state, submissions().correct, true, true);
}
BENCHMARK(BM_GradeCorrect)->Unit(benchmark::kSecond)->Iterations(1)->UseManualTime();
BENCHMARK(BM_GradeStub)->Unit(benchmark::kSecond)->Iterations(1)->UseManualTime();
BENCHMARK(BM_GradeAllWrong)->Unit(benchmark::kSecond)->Iterations(1)->UseManualTime();
BENCHMARK(BM_GradeCorrectEmptyCaches)->Unit(benchmark::kSecond)->Iterations(1)->UseManualTime();

}  // namespace

BENCHMARK_MAIN();
