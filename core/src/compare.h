// GPU image vs CPU reference: the error statistics every check and grade reports.
#pragma once

#include <string>
#include <vector>

#include "pbrlab/image.h"
#include "pbrlab/module.h"

namespace pbrlab {

struct ErrorStats {
    int compared = 0;  // pixels with a surface
    double maxAbs = 0, meanAbs = 0;
    // error = |gpu - ref| / max(|ref|, floor), per component; the tolerance applies to it.
    double maxError = 0, meanError = 0;
    int nanCount = 0, infCount = 0, negativeCount = 0;
    int overCount = 0;             // pixels whose error exceeds the tolerance
    double quantileError = 0;      // the error not exceeded by (1 - outlierFraction) of pixels
    int worstX = -1, worstY = -1;  // where maxError happened (row 0 = top)
    glm::dvec3 worstGpu{0}, worstRef{0};

    int nonFinite() const { return nanCount + infCount; }
    bool passes(const Tolerance& t, bool nonNegative) const {
        return nonFinite() == 0 && (!nonNegative || negativeCount == 0) &&
               (t.outlierFraction > 0 ? quantileError : maxError) <= t.maxError;
    }
};

// Evaluates `module.reference` on every covered surface and compares with `gpu`.
ErrorStats compareWithReference(const Image& gpu, const std::vector<Surface>& surfaces,
                                const ModuleDesc& module, const ReferenceContext& context,
                                std::vector<glm::dvec3>* referenceOut = nullptr);

std::string describe(const ErrorStats& s, const Tolerance& t);

}  // namespace pbrlab
