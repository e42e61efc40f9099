// `pbrlab converge`: error against run time for everything approximate in the IBL pipeline,
// measured on the split-sum scene against a CPU reference in double precision.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "ibl/map_error.h"
#include "render/renderer.h"

namespace pbrlab {

struct ConvergeOptions {
    std::filesystem::path out = "converge";
    std::string scene = "sphere-grid";
    int size = 96;             // image side; the CPU truth costs size^2 * truthSamples
    int truthSamples = 65536;  // Monte Carlo samples per pixel of the specular truth
                               // (roughness < 0.5; rougher lobes use a texel sum)
    int maxBruteForce = 1024;  // brute force at 1, 2, 4 ... this many samples
    bool quick = false;        // fewer settings (tests)
    IblSettings ibl;           // the maps' settings, except where a row varies them
    std::function<void(const std::string&)> onPrecomputePass;  // progress (RendererOptions)
};

struct ConvergeRow {
    std::string term;  // "specular" or "diffuse"
    // brute_force, brute_force_vndf, split_sum, convolution, spherical_harmonics
    std::string method;
    std::string setting;  // what varies, e.g. "prefilter=256 lut=128 fis=off"
    int samples = 0;
    double ms = 0;                  // per frame: the view pass (glFinish + steady clock)
    double precomputeMs = 0;        // once per environment: the precompute passes it needed
    double rmse = 0, maxError = 0;  // linear radiance
    // The same after Reinhard x / (1 + x), what a viewer sees: in linear units a 20000-bright
    // sun hit by a few samples dominates everything; on screen it saturates to 1.
    double displayRmse = 0;
};

// Renders with a renderer of its own, without the disk cache: every precompute is measured.
std::vector<ConvergeRow> runConverge(const DataPaths& paths, const ConvergeOptions& options);

// converge.csv, converge.gp (gnuplot script) and converge.png (when gnuplot is installed).
void writeConvergeReport(const std::vector<ConvergeRow>& rows, const std::filesystem::path& out);

// ---- the precomputed maps' own error against their cost -------------------------------------

// One precompute measured: the maps, each pass's time, the maps' errors against the truth.
struct IblRun {
    std::unique_ptr<IblMaps> maps;
    IblErrors errors;
    double milliseconds = 0;  // every pass, programs compiled included (glFinish + clock)
};
// Builds the derived maps (no environment cube: what `pbrlab precompute` writes) and measures
// them. Without a cache every map is computed.
IblRun measurePrecompute(IblPrecompute& precompute, const Image& equirect,
                         const IblSettings& settings, IblTruth& truth,
                         const IblDiskCache* cache = nullptr);

// The settings `--error-budget` chooses among, cheapest first: each step costs more than the
// one before and lowers the error of the map that limited it (docs/ibl.md, "Error budget").
std::vector<IblSettings> iblLadder();
// Every map's mean error at or below `budget`.
bool withinBudget(const IblErrors& errors, double budget);

struct IblChoice {
    IblSettings settings;
    IblRun run;
    int tried = 0;     // rungs of the ladder measured
    bool met = false;  // false: no rung met the budget; the most accurate one is returned
};
// The cheapest rung of the ladder whose maps, computed from this environment, have every mean
// error within `budget` (measured here, rung by rung from the cheapest). What `pbrlab
// precompute --error-budget` and the GUI's precompute call.
IblChoice chooseIblSettings(IblPrecompute& precompute, const Image& equirect, IblTruth& truth,
                            double budget, const IblDiskCache* cache = nullptr);

// Builds the maps while the truth is computed in a thread of its own, then measures them:
// what `pbrlab precompute` does.
IblRun precomputeWithErrors(IblPrecompute& precompute, const Image& equirect,
                            const IblSettings& settings, const IblDiskCache* cache);
// Writes the maps (EXR cube faces, LUT, sh.json) and errors.csv into `out`, and prints each
// pass's time next to its map's error.
void writePrecompute(const IblRun& run, const Image& equirect, const std::filesystem::path& out);

// `pbrlab precompute --bench`: LearnOpenGL's sizes and sample counts against the default, both
// through pbrlab's passes, in the same run, on the project's sky and the given files (none:
// ../shared/data/hdr/*.hdr beside the sources when present). Prints times (median of `runs`)
// and errors; true when the default is at least 10x faster with every error at or below the
// baseline's on every environment.
struct PrecomputeBenchOptions {
    std::vector<std::string> files;
    int runs = 3;
    std::filesystem::path out;  // bench.csv when not empty
};
bool benchPrecompute(const DataPaths& paths, const PrecomputeBenchOptions& options);

// Measures the whole ladder (the error-against-time front) on one environment.
std::vector<IblRun> measureIblLadder(IblPrecompute& precompute, const Image& equirect,
                                     IblTruth& truth);

}  // namespace pbrlab
