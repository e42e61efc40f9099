// Start-up, as ratios to baselines measured in the same run (docs/architecture.md, "Start-up"):
// - whole processes (spawn to exit, wall time): `pbrlab --help`, `pbrlab list` and
//   `pbrlab render ndotl --size 256x256`, each paired run by run with the same command started
//   with libpbrlab_oiio.so preloaded, i.e. with OpenImageIO's libraries loaded and initialised
//   before main as they were when pbrlab linked OpenImageIO (the old executable also paid
//   OpenImageIO's first-use set-up when it wrote the PNG, which this baseline leaves out);
// - the in-process codecs against OpenImageIO on the hot formats: writing a 512^2 PNG and a
//   512^2 float EXR, reading the 8- and 16-bit PNG textures, the 2048^2 WaterBottle PNG and the
//   shipped 1k HDRs (the last two from ../shared/data beside the repository, when present).
#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "assets/image_codecs.h"
#include "assets/image_io.h"

extern char** environ;

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

const fs::path kExecutable = PBRLAB_EXECUTABLE;
const fs::path kOiioLibrary = kExecutable.parent_path() / "libpbrlab_oiio.so";
const fs::path kShared = fs::path(PBRLAB_SOURCE_DIR) / "../shared/data";

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n == 0 ? 0.0 : n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double secondsOf(const std::function<void()>& f) {
    const auto start = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct ProcessTimes {
    double wall = 0, cpu = 0;  // seconds; cpu = the child's user + system
};

// Runs `args` (stdout and stderr to /dev/null), with LD_PRELOAD=`preload` when given.
ProcessTimes runProcess(const std::vector<std::string>& args, const std::string& preload) {
    std::vector<std::string> env;
    for (char** e = environ; *e; ++e)
        if (std::string(*e).rfind("LD_PRELOAD=", 0) != 0) env.push_back(*e);
    if (!preload.empty()) env.push_back("LD_PRELOAD=" + preload);
    std::vector<char*> argv, envp;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    for (const auto& e : env) envp.push_back(const_cast<char*>(e.c_str()));
    argv.push_back(nullptr);
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
    ProcessTimes t;
    const auto start = std::chrono::steady_clock::now();
    pid_t pid = 0;
    if (posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), envp.data()) != 0) pid = -1;
    int status = 0;
    rusage usage{};
    if (pid > 0) wait4(pid, &status, 0, &usage);
    t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    posix_spawn_file_actions_destroy(&actions);
    if (pid <= 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) t.wall = -1;
    t.cpu = double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
            1e-6 * double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
    return t;
}

// The command and the same with OpenImageIO preloaded, alternately; medians and the median of
// the pairs' ratios.
void processAgainstPreloadedOpenImageIo(benchmark::State& state,
                                        const std::vector<std::string>& args) {
    std::vector<double> walls, cpus, baseWalls, ratios;
    for (auto _ : state) {
        const ProcessTimes now = runProcess(args, "");
        const ProcessTimes before = runProcess(args, kOiioLibrary.string());
        if (now.wall < 0 || before.wall < 0) {
            state.SkipWithError("the command failed");
            break;
        }
        state.SetIterationTime(now.wall);
        walls.push_back(now.wall);
        cpus.push_back(now.cpu);
        baseWalls.push_back(before.wall);
        ratios.push_back(now.wall / before.wall);
    }
    state.counters["wall_ms"] = median(walls) * 1e3;
    state.counters["cpu_ms"] = median(cpus) * 1e3;
    state.counters["with_openimageio_ms"] = median(baseWalls) * 1e3;
    state.counters["ratio_to_with_openimageio"] = median(ratios);
}

const fs::path& scratch() {
    static const fs::path dir = [] {
        fs::path d =
            fs::temp_directory_path() / ("pbrlab-bench-startup-" + std::to_string(getpid()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

void BM_Help(benchmark::State& state) {
    processAgainstPreloadedOpenImageIo(state, {kExecutable.string(), "--help"});
}
void BM_List(benchmark::State& state) {
    processAgainstPreloadedOpenImageIo(state, {kExecutable.string(), "list"});
}
void BM_RenderNdotl(benchmark::State& state) {
    processAgainstPreloadedOpenImageIo(
        state, {kExecutable.string(), "render", "ndotl", "--size", "256x256", "--out",
                (scratch() / "ndotl.png").string()});
}
BENCHMARK(BM_Help)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(9);
BENCHMARK(BM_List)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(9);
BENCHMARK(BM_RenderNdotl)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);

// ------------------------------------------------------------------ codecs

// Ours and OpenImageIO's alternately (OpenImageIO already loaded: its start-up is not counted).
void codecAgainstOpenImageIo(benchmark::State& state, const std::function<void(ImageCodecs)>& f) {
    f(ImageCodecs::OpenImageIO);  // loads and sets up OpenImageIO outside the timing
    std::vector<double> ours, theirs, ratios;
    for (auto _ : state) {
        const double a = secondsOf([&] { f(ImageCodecs::Default); });
        const double b = secondsOf([&] { f(ImageCodecs::OpenImageIO); });
        state.SetIterationTime(a);
        ours.push_back(a);
        theirs.push_back(b);
        ratios.push_back(a / b);
    }
    state.counters["openimageio_ms"] = median(theirs) * 1e3;
    state.counters["ratio_to_openimageio"] = median(ratios);
}

// A 512^2 RGBA picture like a render: a shaded disc on a flat background, 8-bit codes.
Image renderLike(int size) {
    Image image;
    image.width = image.height = size;
    image.channels = 4;
    image.pixels.resize(size_t(size) * size * 4);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const double u = (x + 0.5) / size * 2 - 1, v = (y + 0.5) / size * 2 - 1;
            const double r2 = u * u + v * v;
            const double shade = r2 < 0.7 ? std::sqrt(0.7 - r2) * (0.6 - 0.4 * u - 0.3 * v) : 0.12;
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(std::clamp(shade, 0.0, 1.0));
            image.at(x, y, 3) = 1.0f;
        }
    }
    return image;
}

void BM_WritePng512(benchmark::State& state) {
    const Image image = renderLike(512);
    const fs::path file = scratch() / "write.png";
    codecAgainstOpenImageIo(state, [&](ImageCodecs codecs) {
        writeImage(file, image, FileDepth::Uint8, true, codecs);
    });
}
BENCHMARK(BM_WritePng512)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(15);

// A precomputed map's worth: 512^2 RGB floats (one face of a 512 environment cube).
void BM_WriteExr512(benchmark::State& state) {
    Image image = renderLike(512);
    image.channels = 3;
    image.pixels.resize(size_t(512) * 512 * 3);
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] *= 1.0f + float(i % 7);
    const fs::path file = scratch() / "write.exr";
    codecAgainstOpenImageIo(state, [&](ImageCodecs codecs) {
        writeImage(file, image, FileDepth::Float32, false, codecs);
    });
}
BENCHMARK(BM_WriteExr512)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(15);

fs::path readFile(int which) {
    const fs::path textures = fs::path(PBRLAB_SOURCE_DIR) / "assets/textures/metal-plates";
    switch (which) {
        case 0:
            return textures / "albedo.png";  // 256^2, 8-bit RGB
        case 1:
            return textures / "roughness.png";  // 256^2, 16-bit grey
        case 2:
            return kShared / "gltf/WaterBottle/WaterBottle_baseColor.png";  // 2048^2 RGB
        case 3:
            return kShared / "hdr/venice_sunset_1k.hdr";
        default:
            return kShared / "hdr/studio_small_03_1k.hdr";
    }
}

void BM_Read(benchmark::State& state) {
    const fs::path file = readFile(int(state.range(0)));
    if (!fs::exists(file)) {
        state.SkipWithError("../shared/data absent");
        for (auto _ : state) {
        }
        return;
    }
    state.SetLabel(file.filename().string());
    codecAgainstOpenImageIo(state, [&](ImageCodecs codecs) {
        benchmark::DoNotOptimize(readImage(file, codecs).pixels.data());
    });
}
BENCHMARK(BM_Read)->DenseRange(0, 4)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(9);

}  // namespace

BENCHMARK_MAIN();
