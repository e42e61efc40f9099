// Linear in radiance (step_grader.h): a step that reads the environment returns radiance (or
// E / PI) that is a linear function of it. The same inputs and samples on environments that
// are multiples and sums of each other must give the same multiples and sums; a clamp, a tone
// map, a firefly cap or any other nonlinearity applied to what it reads does not.

#include <algorithm>
#include <cmath>

#include "grading/error_patterns.h"
#include "grading/step_grader.h"

namespace pbrlab::step_grading {

namespace {

// The environments compared (envgen.h): the soft sky (brightest ~8), the bright lobe alone
// (1e4 to 1e5) and their sum, sky-hdr; sky-hdr scaled by 2^10 and 2^-10 (about 1e3 and 1e-3:
// powers of two, so a function linear in radiance gives exactly 2^10 times its float result,
// every rounding scaled with it).
constexpr char kSoft[] = "sky-soft", kLobes[] = "hdr-lobe", kSum[] = "sky-hdr";
constexpr double kScales[] = {1024.0, 1.0 / 1024.0};

// What a linear function's results may differ by. Scaled: nothing (measured 0 on every step's
// reference solution). The sum: float rounding of the two environments' texels summed once
// (sky-hdr) against the two results summed after; measured on the reference solutions: 8.6e-6
// of the value (irradiance), 6.3e-7 (prefilter), 5.2e-7 (mc_specular); 1e-4 is 11x the largest,
// and the nonlinearities tried (tests/exploits) fail the scales by 0.998 of the value and more.
constexpr double kTolerance = 1e-4;

// Random points of the domain for the linearity checks, apart from the graded ones (the seed's
// own stream). The check costs more than most: it builds three environments no other check
// reads (sky-hdr x 1024, sky-hdr / 1024, hdr-lobe), and irradiance's quadrature reads 6144
// texels a fragment on each; `pbrlab -v check ID` prints it as "linear in radiance".
constexpr int kPoints = 128;

// The point of `got` farthest from `expected`, and by how much (relative).
struct Worst {
    double deviation = 0;  // relative
    int index = -1;
    glm::dvec3 got{0}, expected{0};
};

// The worst deviation of `got` from `expected` over the covered points of `g`. Deviations are
// relative to the expected value, floored at 1e-3 of its mean magnitude (a point that reads
// almost nothing is compared absolutely).
Worst worstDeviation(const ModuleDesc& d, const Grid& g, const std::vector<glm::dvec3>& got,
                     const std::vector<glm::dvec3>& expected) {
    double mean = 0;
    int count = 0;
    for (size_t i = 0; i < g.surfaces.size(); ++i)
        if (g.surfaces[i].covered)
            for (int c = 0; c < d.components; ++c) mean += std::abs(expected[i][c]), ++count;
    mean /= std::max(count, 1);
    Worst w;
    for (size_t i = 0; i < g.surfaces.size(); ++i) {
        if (!g.surfaces[i].covered) continue;
        for (int c = 0; c < d.components; ++c) {
            const double a = got[i][c], e = expected[i][c];
            // NaN or Inf where the environment is finite: as far from linear as it gets.
            const double deviation = std::isfinite(a) && std::isfinite(e)
                                         ? std::abs(a - e) / std::max(std::abs(e), 1e-3 * mean)
                                         : HUGE_VAL;
            if (deviation > w.deviation || w.index < 0)
                w = {deviation, int(i), got[i], expected[i]};
        }
    }
    return w;
}

// The linearity check `name` from its worst deviation; `what` says what a linear function gives.
CheckReport linearityReport(const ModuleDesc& d, const Grid& g, const std::string& name,
                            const Worst& w, const std::string& what) {
    CheckReport c;
    c.name = name;
    // A broken contract (radiance in, radiance out): it leads the message.
    c.kind = CheckKind::Contract;
    c.category = CheckCategory::Invariants;
    c.measured = w.deviation;
    c.expected = "<= " + number(kTolerance) + " of the value";
    c.passed = w.deviation <= kTolerance;
    c.detail = what;
    if (!c.passed && w.index >= 0)
        c.detail = "nonlinear in radiance: " + what + " at " +
                   describeInputs(d, g.surfaces[size_t(w.index)]) + ": yours " + number(w.got[0]) +
                   ", " + number(w.got[1]) + ", " + number(w.got[2]) +
                   ", a linear function gives " + number(w.expected[0]) + ", " +
                   number(w.expected[1]) + ", " + number(w.expected[2]) + " (" +
                   number(w.deviation, 3) +
                   " off relatively; float rounding: under 1e-4). Is a clamp, a tone map or "
                   "another nonlinearity applied to the radiance it reads?";
    else
        c.detail += ": within " + number(w.deviation, 3) + " of a linear function's";
    return c;
}

}  // namespace

void StepGrader::gradeLinearity(const Scene& scene) {
    if (!(d_.needs & NeedsEnvironment) || !d_.linearInEnvironment) return;
    stage("linear in radiance");
    std::vector<Surface> inputs =
        d_.domain ? domainSurfaces(d_, settings_.seed + 0x11ea, kPoints) : probeSurfaces(d_.probe);
    for (Surface& s : inputs) s.emissive = glm::dvec3(0);  // emission is no radiance read
    const Grid g = grid(std::move(inputs));
    const ParamValues params(d_.params);
    const std::vector<glm::dvec3> sum = valuesOnEnvironment(scene, kSum, params, g);
    for (double k : kScales) {
        const std::string scaled = std::string(kSum) + "*" + number(k, 17);
        const std::vector<glm::dvec3> got = valuesOnEnvironment(scene, scaled, params, g);
        std::vector<glm::dvec3> expected = sum;
        for (glm::dvec3& v : expected) v *= k;
        const std::string factor = k > 1 ? "1024" : "1/1024";
        record(linearityReport(
            d_, g, "linear in radiance: the environment " + factor + " x as bright",
            worstDeviation(d_, g, got, expected),
            "with every radiance of the environment (" + std::string(kSum) + ") times " + factor +
                ", the values are to be " + factor + " x as large"));
    }
    // The maps derived from the environment (split_sum's) are homogeneous in it but not
    // additive: the host's bins stand for their texels at radiance-weighted centres, so the
    // maps of a sum are not the sum of the maps (measured on the reference: 5.6e-4). Their
    // readers are checked by the scales alone, which are exact.
    if (d_.needs & NeedsPrecomputedMaps) return;
    const std::vector<glm::dvec3> soft = valuesOnEnvironment(scene, kSoft, params, g),
                                  lobes = valuesOnEnvironment(scene, kLobes, params, g);
    std::vector<glm::dvec3> expected(sum.size());
    for (size_t i = 0; i < sum.size(); ++i) expected[i] = soft[i] + lobes[i];
    record(linearityReport(
        d_, g, "linear in radiance: two environments summed", worstDeviation(d_, g, sum, expected),
        "on the sum of two environments (the soft sky and a bright lobe of 1e4 to 1e5), the "
        "values are to be the sum of the values on each"));
}

// The step's values at the points of `g` with the scene's environment replaced by `environment`.
std::vector<glm::dvec3> StepGrader::valuesOnEnvironment(const Scene& scene,
                                                        const std::string& environment,
                                                        const ParamValues& params, const Grid& g) {
    Scene s = scene;
    s.environment = environment;
    return pointValues(renderPoints(params, s, g.surfaces, g.width, g.height).value,
                       g.surfaces.size());
}

}  // namespace pbrlab::step_grading
