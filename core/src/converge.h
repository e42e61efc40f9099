// `pbrlab converge`: error against run time for everything approximate in the IBL pipeline,
// measured on the split-sum scene against a CPU reference in double precision.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "renderer.h"

namespace pbrlab {

struct ConvergeOptions {
    std::filesystem::path out = "converge";
    std::string scene = "sphere-grid";
    int size = 96;             // image side; the CPU truth costs size^2 * truthSamples
    int truthSamples = 65536;  // Monte Carlo samples per pixel of the specular truth
                               // (roughness < 0.5; rougher lobes use a texel sum)
    int maxBruteForce = 1024;  // brute force at 1, 2, 4 ... this many samples
    bool quick = false;        // fewer settings (tests)
};

struct ConvergeRow {
    std::string term;     // "specular" or "diffuse"
    std::string method;   // brute_force, split_sum, convolution, spherical_harmonics
    std::string setting;  // what varies, e.g. "prefilter=256 lut=128 fis=off"
    int samples = 0;
    double ms = 0;                  // per frame: the view pass (glFinish + steady clock)
    double precomputeMs = 0;        // once per environment: the precompute passes it needed
    double rmse = 0, maxError = 0;  // linear radiance
    // The same after Reinhard x / (1 + x), what a viewer sees: in linear units a 20000-bright
    // sun hit by a few samples dominates everything; on screen it saturates to 1.
    double displayRmse = 0;
};

std::vector<ConvergeRow> runConverge(LabRenderer& renderer, const DataPaths& paths,
                                     const ConvergeOptions& options);

// converge.csv, converge.gp (gnuplot script) and converge.png (when gnuplot is installed).
void writeConvergeReport(const std::vector<ConvergeRow>& rows, const std::filesystem::path& out);

}  // namespace pbrlab
