// A value image against its pass band: the band's construction (reference, accepted
// alternatives, tolerance with measured conditioning; pbrlab::Tolerance) and the statistics
// every check, grade, GUI badge and stability sweep reports.
#pragma once

#include <string>
#include <vector>

#include "assets/image_io.h"
#include "pbrlab/module.h"
#include "util/cancel.h"

namespace pbrlab {

// What passes at each point: every component c of the value within [lo.c - slack.c,
// hi.c + slack.c], or every component within slack.c of one of the separate definitions.
// `expected` is what the report shows as "the reference" there.
struct Band {
    std::vector<glm::dvec3> expected, lo, hi, slack;
    std::vector<std::vector<glm::dvec3>> separate;  // per separate alternative, per point
    void resize(size_t n) {
        expected.assign(n, glm::dvec3(0));
        lo.assign(n, glm::dvec3(0));
        hi.assign(n, glm::dvec3(0));
        slack.assign(n, glm::dvec3(0));
    }
    // How far v is outside the band at point i, in slacks (<= 1 inside).
    double excess(size_t i, const glm::dvec3& v, int components) const;
};

// How far the reference moves at this point when every float input (the surface's fields and
// the scene's lights) moves by up to `ulps` units in the last place, per component: the
// measured conditioning that widens the band where rounding of the inputs matters.
glm::dvec3 referenceSpread(const ModuleDesc& module, const Surface& surface,
                           const ReferenceContext& context, double ulps, std::uint64_t seed);

// The module's band on these surfaces: its reference, its accepted alternatives and its
// tolerance (pbrlab::Tolerance). Points that are not covered are left at zero. Throws
// Cancelled when `stop` says so (asked between points).
Band referenceBand(const ModuleDesc& module, const std::vector<Surface>& surfaces,
                   const ReferenceContext& context, const StopRequested& stop = {});

struct Comparison {
    int compared = 0;  // covered points
    int nanCount = 0, infCount = 0, negativeCount = 0;
    int outside = 0;            // points with a component outside the band
    double worstExcess = 0;     // the largest distance outside the band, in slacks (<= 1 inside)
    double quantileExcess = 0;  // not exceeded by (1 - outlierFraction) of the points
    int worstIndex = -1;        // point (row-major) of worstExcess
    int worstX = -1, worstY = -1;
    glm::dvec3 worstValue{0}, worstExpected{0}, worstLo{0}, worstHi{0};  // lo, hi: slack included

    int nonFinite() const { return nanCount + infCount; }
    bool passes(bool nonNegative, double outlierFraction) const {
        return compared > 0 && nonFinite() == 0 && (!nonNegative || negativeCount == 0) &&
               (outlierFraction > 0 ? quantileExcess : worstExcess) <= 1;
    }
};

Comparison compareWithBand(const Image& value, const std::vector<Surface>& surfaces,
                           const Band& band, int components, bool nonNegative,
                           double outlierFraction);

std::string describe(const Comparison& c);

}  // namespace pbrlab
