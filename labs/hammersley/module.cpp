// hammersley: the Hammersley point set (i / n, radical inverse of i).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "pbrlab/ibl_reference.h"

using namespace pbrlab;

namespace {

constexpr int kMaxPoints = 1024;  // the view's cap on n (scene parameter and probe rows)

// What the view computes (view.glsl), for the Hammersley set in double precision:
//   x: the local discrepancy of the n points at the box [0, a) x [0, b), in points
//      (how many lie inside minus n a b);
//   y: n x_i - i for the point i whose column [i / n, (i + 1) / n) holds a (0 for x_i = i / n).
glm::dvec3 discrepancyView(double a, double b, std::uint32_t n) {
    int inside = 0;
    for (std::uint32_t j = 0; j < n; ++j) {
        const glm::dvec2 p = ref::hammersley(j, n);
        if (p.x < a && p.y < b) ++inside;
    }
    const auto slot = std::min(std::uint32_t(a * n), n - 1);
    return {inside - double(n) * a * b, ref::hammersley(slot, n).x * n - slot, 0};
}

// The point (i, n) as point.glsl reads it from extra.
Surface pointInputs(std::uint32_t i, std::uint32_t n) {
    Surface s;
    s.covered = true;
    s.extra = {double(i >> 16), double(i & 0xFFFFu), double(n), 1};
    return s;
}

// The contract's whole range of the arguments, beyond what the discrepancy view can afford (it
// loops over all n points): hammersley(i, n) itself (point.glsl), compared with the double
// reference.
//   y over every bit of i: i = 2^k for k = 0..31 (y = 2^-(k+1), exact in float, so a reversal
//     of fewer bits than 32 gives 0 there) and mixed patterns, n = 2^20. Band: 4e-6 of y, twice
//     the worst a correct loop over the 32 bits reaches (32 float additions, each rounding by
//     at most 2^-24 of the sum: 1.9e-6; bitfieldReverse and the swaps are exact to 6e-8).
//   x = i / n for n = 1 to 2^20 (the estimators' counts reach 65536): i = 0, 1, n / 3, n - 1.
//     (y of these points is the first check's: it does not depend on n.)
//     Band: 1e-6 of x (i and n are exact floats; GLSL's division is within 2.5 ulps, 3e-7).
// Cost: 2 renders of under 200 points, ~20 ms.
std::vector<InvariantResult> wholeRangeInvariants(const Evaluator& evaluate) {
    std::vector<std::uint32_t> bits;
    for (int k = 0; k < 32; ++k) bits.push_back(1u << k);
    for (std::uint32_t i : {0xFFFFFFFFu, 0xAAAAAAAAu, 0x55555555u, 0xFFFF0000u, 0x0000FFFFu,
                            0x80000001u, 0xDEADBEEFu, 0x12345678u})
        bits.push_back(i);
    constexpr std::uint32_t kLargestCount = 1u << 20;
    std::vector<Surface> points;
    for (std::uint32_t i : bits) points.push_back(pointInputs(i, kLargestCount));
    const std::vector<glm::dvec3> y = evaluate.run(points, "point", {});
    double worstY = 0;
    std::uint32_t worstI = 0;
    for (size_t k = 0; k < bits.size(); ++k) {
        const double expected = ref::hammersley(bits[k], kLargestCount).y;
        const double e = std::abs(y[k].y - expected) / (4e-6 * expected);
        if (!(e <= worstY)) worstY = e, worstI = bits[k];  // NaN counts as worst
    }
    char hintY[256];
    int lowestWrongBit = -1;
    for (int k = 0; k < 32 && lowestWrongBit < 0; ++k)
        if (!(std::abs(y[size_t(k)].y - std::exp2(-(k + 1))) <= 4e-6 * std::exp2(-(k + 1))))
            lowestWrongBit = k;
    if (lowestWrongBit > 0)
        std::snprintf(hintY, sizeof hintY,
                      "ignores the bits of i above bit %d: wrong from i = 2^%d (y = 2^-%d "
                      "expected); the radical inverse mirrors all 32 bits of i",
                      lowestWrongBit - 1, lowestWrongBit, lowestWrongBit + 1);
    else
        std::snprintf(hintY, sizeof hintY,
                      "wrong at i = %u: the radical inverse mirrors all 32 bits of i", worstI);

    std::vector<std::uint32_t> counts = {1, 7, 1000, 1024, 4096, 65536, kLargestCount};
    std::vector<Surface> pairs;
    std::vector<std::uint32_t> pairCount;
    for (std::uint32_t n : counts)
        for (std::uint32_t i : {0u, 1u, n / 3, n - 1})
            if (i < n) {
                pairs.push_back(pointInputs(i, n));
                pairCount.push_back(n);
            }
    const std::vector<glm::dvec3> x = evaluate.run(pairs, "point", {});
    double worstX = 0;
    std::uint32_t firstWrongCount = 0;
    for (size_t k = 0; k < pairs.size(); ++k) {
        const std::uint32_t i =
            (std::uint32_t(pairs[k].extra.x) << 16) | std::uint32_t(pairs[k].extra.y);
        // x only: y is the radical inverse of i whatever n is (graded above).
        const double expected = ref::hammersley(i, pairCount[k]).x;
        const double e = std::abs(x[k].x - expected) / std::max(1e-6 * expected, 1e-30);
        if (!(e <= 1) && !firstWrongCount) firstWrongCount = pairCount[k];
        if (!(e <= worstX)) worstX = e;
    }
    char hintX[256] = "";
    if (firstWrongCount > kMaxPoints) {  // right at every count the discrepancy view draws
        std::uint32_t rightUpTo = 1;
        for (std::uint32_t n : counts)
            if (n < firstWrongCount) rightUpTo = n;
        std::snprintf(hintX, sizeof hintX,
                      "ignores its count above %u: wrong from n = %u, right up to n = %u",
                      rightUpTo, firstWrongCount, rightUpTo);
    } else {
        std::snprintf(hintX, sizeof hintX, "x = i / n for every n the callers pass (up to 2^20)");
    }
    return {{"y over every bit of i (i = 2^0 .. 2^31, n = 2^20), error in bands", worstY, "<= 1",
             worstY <= 1, hintY},
            {"x = i / n for n = 1 .. 2^20, error in bands", worstX, "<= 1", worstX <= 1, hintX}};
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Hammersley points";
    d.params = {intParam("samples", 64, 1, kMaxPoints, "Number of points n in the set")};
    d.components = 2;
    // Both channels in points; mid grey = 0, saturated at +-4 points.
    d.display = {DisplayMode::Grey, -4, 4};
    d.needs = NeedsGeometry;
    // Judged by properties, not point by point (README.md): x = i / n exactly (the slot
    // offset, channel 2: within 1e-3 of 0, float rounding of i / n), and a low-discrepancy y
    // (channel 1: the box counts within 8 points of the Hammersley set's: measured <= 5 for
    // other low-discrepancy sequences, 27-30 for white noise at n = 1024).
    d.tolerance = {8, 0, 0};
    d.componentTolerances = {{8, 0, 0}, {1e-3, 0, 0}};
    d.nonNegative = false;
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        if (s.extra != glm::dvec4(0)) {  // probe and stability inputs
            const double a = std::clamp(s.extra.x, 0.0, 1.0);
            return discrepancyView(a, a, std::uint32_t(std::clamp(s.extra.y, 1.0, 1024.0)));
        }
        // The corner as the shader derives it from the (float) uv.
        const float a = std::abs(2.0f * float(s.uv.x) - 1.0f), b = 1.0f - float(s.uv.y);
        const int n = std::clamp(int(c.params.number("samples")), 1, kMaxPoints);
        return discrepancyView(a, b, std::uint32_t(n));
    };
    // x: box corner a from 0 to 1 (the square box [0, a)^2; the column's point i runs from 0 to
    // n - 1); y: n from 1 to 1024 on a log scale (rounded: 1, 1, 1, 1, 2, ... 1024).
    d.probe.xAxis = "box [0,a)^2, a 0..1 (point i = 0..n-1)";
    d.probe.yAxis = "n 1..1024 (log)";
    d.probe.width = 129;
    d.probe.height = 65;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.extra = {x, std::round(std::exp2(10.0 * y)), 0, 1};  // w = 1: never all zero
        return s;
    };
    d.extraViews = {"point"};
    d.invariants = wholeRangeInvariants;
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
