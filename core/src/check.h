// `check`: a module's GPU output (reference solution or a student's) against its CPU
// reference, on the scene and on the probe grid.
#pragma once

#include "compare.h"
#include "renderer.h"

namespace pbrlab {

struct CheckResult {
    ErrorStats scene, probe;
    double sceneMilliseconds = 0, probeMilliseconds = 0;
    bool passed = false;
};

ReferenceContext referenceContext(const Scene& scene, const ParamValues& params);

CheckResult checkModule(LabRenderer& renderer, const LoadedModule& module,
                        const ParamValues& params, const Scene& scene, const StudentSource& source,
                        int width, int height);

}  // namespace pbrlab
