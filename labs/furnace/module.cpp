// furnace: the directional albedo E(mu) of the single-scattering GGX lobe with F0 = 1, and its
// cosine-weighted average E_avg, read from the split-sum LUT (E = A + B).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>

#include "pbrlab/cube_sampler.h"
#include "pbrlab/named_terms.h"

using namespace pbrlab;

namespace {

// The parts of the step's value, for feedback that names the one a student got wrong.
struct Knobs {
    double bias = 1;       // B in E = A + B
    double swapped = 0;    // 1: the LUT read at (roughness, N.V)
    double two = 1;        // the 2 of E_avg = 2 integral E(mu) mu dmu
    double cosine = 1;     // the weight mu of E_avg's integral
    double plainMean = 0;  // 1: E_avg = the plain mean of E over mu (no 2 mu)
};

double albedoAt(const Image& lut, double mu, double roughness, const Knobs& k = {}) {
    const glm::dvec4 ab =
        sampleTexture(lut, k.swapped != 0 ? glm::dvec2(roughness, mu) : glm::dvec2(mu, roughness));
    return ab.x + k.bias * ab.y;
}

// 2 integral of E(mu) mu dmu along one row of the LUT, exactly: the sampler interpolates
// linearly between texel centres x_i = (i + 0.5) / width and holds the edge texels' values
// beyond them, so the integrand is piecewise quadratic; each piece in closed form.
double rowAverage(const Image& lut, int row) {
    const int w = lut.width;
    const auto e = [&](int i) { return double(lut.at(i, row, 0)) + double(lut.at(i, row, 1)); };
    const auto x = [&](int i) { return (i + 0.5) / w; };
    double sum = e(0) * x(0) * x(0) + e(w - 1) * (1 - x(w - 1) * x(w - 1));
    for (int i = 0; i + 1 < w; ++i) {
        // 2 integral over [a, a + h] of (p + (q - p) s) x dx, x = a + h s.
        const double a = x(i), h = x(i + 1) - a, p = e(i), q = e(i + 1);
        sum += h * (a * (p + q) + h * (p + 2 * q) / 3);
    }
    return sum;
}

// E_avg at any roughness: the rows' exact averages interpolated as the sampler interpolates
// between rows (linear in t between row centres, held beyond the first and last).
double averageAlbedo(const Image& lut, double roughness) {
    const double t = std::clamp(roughness, 0.0, 1.0) * lut.height - 0.5;
    const int j = int(std::floor(t));
    const double f = t - j;
    const auto row = [&](int r) { return rowAverage(lut, std::clamp(r, 0, lut.height - 1)); };
    return (1 - f) * row(j) + f * row(j + 1);
}

// The step's value with every part a knob; at the defaults, the reference itself. Other
// settings integrate with the midpoint rule on 2048 nodes (within 1e-6 of exact: enough to
// name a mistake).
glm::dvec3 albedoWithKnobs(const Surface& s, const ReferenceContext& c, const Knobs& k) {
    if (!c.ibl || c.ibl->lut.pixels.empty()) return glm::dvec3(0);
    const Image& lut = c.ibl->lut;
    const double mu = std::clamp(glm::dot(s.normal, s.view), 0.0, 1.0);
    const double E = albedoAt(lut, mu, s.roughness, k);
    const Knobs reference;
    if (k.bias == reference.bias && k.swapped == 0 && k.two == 1 && k.cosine == 1 &&
        k.plainMean == 0)
        return {E, averageAlbedo(lut, s.roughness), 0};
    constexpr int n = 2048;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const double m = (i + 0.5) / n;
        sum += albedoAt(lut, m, s.roughness, k) * (k.plainMean != 0 ? 0.5 : power(m, k.cosine));
    }
    return {E, power(2.0, k.two) * sum / n, 0};
}
std::vector<NamedTerm> albedoTerms() {
    using K = Knobs;
    return namedTerms<K>(
        albedoWithKnobs,
        {removed<K>("the LUT's bias B (E = A + B with F0 = 1)", &K::bias),
         onOff<K>("the LUT read at (roughness, N.V), where its coordinates are (N.V, roughness)",
                  &K::swapped),
         factor<K>("2", "the 2 of E_avg = 2 integral E(mu) mu dmu", {&K::two}),
         exponentTried<K>("mu", "the cosine weight mu inside E_avg's integral", &K::cosine, 1,
                          {0, 2},
                          [](double e) { return "E_avg weighted by mu^" + exponentText(e); }),
         onOff<K>("the plain mean of E over N.V where E_avg weights it by 2 mu", &K::plainMean)});
}

Surface atCosineAndRoughness(double mu, double roughness) {
    Surface s;
    s.covered = true;
    s.normal = {0, 0, 1};
    s.view = {std::sqrt(std::max(1 - mu * mu, 0.0)), 0, mu};
    s.roughness = roughness;
    return s;
}

// Properties every correct answer has, whatever its quadrature: E and E_avg lie in [0, 1]
// (a white metal cannot return more light than arrives), and E_avg does not depend on N.V.
std::vector<InvariantResult> albedoProperties(const Evaluator& evaluate) {
    std::vector<Surface> grid;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 16; ++i)
            grid.push_back(atCosineAndRoughness((i + 0.5) / 16, 0.05 + 0.95 * j / 7));
    const std::vector<glm::dvec3> v = evaluate(grid);
    double lo = 1e300, hi = -1e300, spread = 0;
    for (size_t p = 0; p < v.size(); ++p) {
        lo = std::min({lo, v[p].x, v[p].y});
        hi = std::max({hi, v[p].x, v[p].y});
        spread = std::max(spread, std::abs(v[p].y - v[p - p % 16].y));
    }
    return {{"smallest of E, E_avg", lo, ">= 0", lo >= 0, "E = A + B is a share of the light"},
            {"largest of E, E_avg", hi, "<= 1 (+1e-3)", hi <= 1.001,
             "a white metal returns more light than arrives: a weight is too large"},
            {"largest change of E_avg with N.V at one roughness", spread, "<= 1e-5", spread <= 1e-5,
             "E_avg averages over every N.V: it must not depend on the one given"}};
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "The white furnace: directional albedo E and its average";
    d.components = 2;
    // E in false colour with a legend: 1 where the lobe keeps all the light.
    d.display = {DisplayMode::FalseColor, 0, 1};
    // The LUT is one of the precomputed maps; E is no radiance, so it is not graded linear in
    // the environment's.
    d.needs = NeedsRoughness | NeedsEnvironment | NeedsPrecomputedMaps;
    d.linearInEnvironment = false;
    d.skyBackground = true;
    d.scene = "furnace";
    // E: the student reads the same LUT as the reference: +- 1e-3 of the value, room for a
    // GPU whose filter weights have 8 bits (measured here: 5e-7). E_avg: the student's own
    // quadrature of the LUT's row, +- 1e-3: the midpoint rule passes from 8 nodes on (7.4e-4),
    // fails at 4 (3.1e-3) (README.md, "Tolerance and why").
    d.componentTolerances = {{1e-4, 1e-3, 0, 1e-3}, {1e-3, 0, 0, 1e-3}};
    d.tolerance = d.componentTolerances.front();
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        return albedoWithKnobs(s, c, Knobs{});
    };
    d.probe = viewCosineRoughnessProbe();
    d.domain = [](DomainRandom& r) { return atCosineAndRoughness(r.uniform(), r.uniform()); };
    d.invariants = albedoProperties;
    d.namedTerms = albedoTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
