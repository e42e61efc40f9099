// The stability sweep: every module's view and CPU reference on the extreme inputs of the
// design (roughness 0 and 1, N·V = 0, N·L = 0, V = -L, light at distance 0, intensity 0 and
// 1e6, F0 = 0 and 1, degenerate normal-map inputs, denormals).
#pragma once

#include "evaluate.h"

namespace pbrlab {

struct ExtremeSet {
    int width = 0, height = 0;
    std::vector<Surface> surfaces;    // width * height; unused cells are not covered
    std::vector<std::string> labels;  // what each covered cell is, for reports
};

ExtremeSet extremeSurfaces();

struct StabilityResult {
    Comparison gpu;              // GPU vs the reference's band on the extreme set
    int referenceNonFinite = 0;  // CPU reference NaN/Inf count (must be 0)
    int referenceNegative = 0;   // negative reference values for a non-negative module
    std::string firstProblem;    // label of the first cell where anything broke
};

// Views that read the scene's point lights (uniforms) are swept a second time with the
// scene's lights placed at the extremes (distance 0 and 1e-6, intensity 1e6, below, grazing).
StabilityResult stabilitySweep(LabRenderer& renderer, const LoadedModule& module,
                               const Scene& scene, const StudentSource& source = {});

}  // namespace pbrlab
