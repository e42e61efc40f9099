// irradiance: E(N) / PI from the environment cube, the diffuse half of image-based
// lighting (diffuse = albedo * irradianceAt(N)).
#include "pbrlab/module.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <vector>

#include "pbrlab/named_terms.h"

using namespace pbrlab;

namespace {

// The reference solution's quadrature, in double: every texel of the environment mip whose
// faces are 32 x 32 (level max(log2(size) - 5, 0)), radiance x cosine x the texel's solid angle
// h^2 / (1 + s^2 + t^2)^(3/2), divided by PI. The texels' directions, weights and radiances
// depend only on the environment, so they are gathered once per environment (a table of 6144
// entries); a pixel is then one pass over the table.
struct TexelTable {
    const CubeSampler* environment = nullptr;
    std::vector<glm::dvec3> direction;  // d / |d| (the solution's cosine is N.d / |d|)
    std::vector<double> solidAngle;     // h^2 / |d|^3
    std::vector<glm::dvec3> radiance;   // textureLod(uEnvironment, d, lod)
    double lod = 0;
    std::vector<glm::dvec3> rawDirection;  // d itself, to recheck radiances (see current())
};

TexelTable buildTable(const CubeSampler& env) {
    TexelTable table;
    table.environment = &env;
    const int base = env.size();
    // findMSB(size) - 5: the level whose faces are 32 texels wide (box averages of the base).
    const int lod = std::max(int(std::bit_width(unsigned(base))) - 1 - 5, 0);
    const int size = std::max(base >> lod, 1);
    const double h = 2.0 / size;
    table.lod = lod;
    for (int face = 0; face < 6; ++face)
        for (int j = 0; j < size; ++j)
            for (int i = 0; i < size; ++i) {
                const double s = -1.0 + (i + 0.5) * h, t = -1.0 + (j + 0.5) * h;
                const glm::dvec3 d = cubeFaceDirection(face, s, t);
                const double r2 = glm::dot(d, d);
                table.rawDirection.push_back(d);
                table.direction.push_back(d / std::sqrt(r2));
                table.solidAngle.push_back(h * h / (r2 * std::sqrt(r2)));
                table.radiance.push_back(env.sample(d, lod));
            }
    return table;
}

// The table for this environment. A CubeSampler at the same address may hold another
// environment later (a new session, another scene), so a few radiances are re-read each time
// and the table is rebuilt when any differs.
const TexelTable& current(const CubeSampler& env) {
    thread_local TexelTable table;
    bool valid = table.environment == &env && !table.radiance.empty();
    for (size_t k = 0; valid && k < table.radiance.size(); k += 757)
        valid = env.sample(table.rawDirection[k], table.lod) == table.radiance[k];
    if (!valid) table = buildTable(env);
    return table;
}

glm::dvec3 irradianceAt(const glm::dvec3& N, const CubeSampler& env) {
    const TexelTable& t = current(env);
    glm::dvec3 sum(0.0);
    for (size_t k = 0; k < t.direction.size(); ++k) {
        const double cosine = glm::dot(N, t.direction[k]);
        if (cosine > 0.0) sum += t.radiance[k] * (cosine * t.solidAngle[k]);
    }
    return sum / std::numbers::pi;
}

// The converged integral, for grading: every texel of the mip whose faces are 64 wide (box
// averages of the base, 24576 texels) weighted by its exact solid angle (the area of the
// spherical rectangle it covers) and the cosine at its centre. On the soft sky it is within
// 2e-4 of the same sum over 128-wide faces (README.md).
struct ExactTable {
    const CubeSampler* environment = nullptr;
    std::vector<glm::dvec3> direction, radiance;
    std::vector<double> solidAngle;
};

double cornerAngle(double x, double y) {  // solid angle of [0, x] x [0, y] on a unit-distance face
    return std::atan2(x * y, std::sqrt(x * x + y * y + 1));
}

glm::dvec3 convergedIrradiance(const glm::dvec3& N, const CubeSampler& env) {
    thread_local ExactTable table;
    if (table.environment != &env || table.radiance.empty()) {
        table = ExactTable{&env, {}, {}, {}};
        const int base = env.size();
        const int lod = std::max(int(std::bit_width(unsigned(base))) - 1 - 6, 0);
        const int size = std::max(base >> lod, 1);
        const double h = 2.0 / size;
        for (int face = 0; face < 6; ++face)
            for (int j = 0; j < size; ++j)
                for (int i = 0; i < size; ++i) {
                    const double s0 = -1 + i * h, s1 = s0 + h, t0 = -1 + j * h, t1 = t0 + h;
                    const glm::dvec3 d = cubeFaceDirection(face, 0.5 * (s0 + s1), 0.5 * (t0 + t1));
                    table.direction.push_back(glm::normalize(d));
                    table.solidAngle.push_back(cornerAngle(s1, t1) - cornerAngle(s0, t1) -
                                               cornerAngle(s1, t0) + cornerAngle(s0, t0));
                    table.radiance.push_back(env.sample(d, lod));
                }
    }
    glm::dvec3 sum(0.0);
    for (size_t k = 0; k < table.direction.size(); ++k) {
        const double cosine = glm::dot(N, table.direction[k]);
        if (cosine > 0.0) sum += table.radiance[k] * (cosine * table.solidAngle[k]);
    }
    return sum / std::numbers::pi;
}

// Named terms for feedback (pbrlab/named_terms.h): the reference's texel sum with the cosine at
// another power, light from below the horizon counted, or the solid angle without its
// sin(theta).
struct Knobs {
    double cosine = 1, wholeSphere = 0;
    double sinTheta = 1;  // the sin(theta) of the solid angle sin(theta) dtheta dphi
};
glm::dvec3 texelSum(const Surface& s, const ReferenceContext& c, const Knobs& k) {
    if (!c.ibl) return glm::dvec3(0);
    const TexelTable& t = current(c.ibl->environment);
    glm::dvec3 sum(0.0);
    for (size_t i = 0; i < t.direction.size(); ++i) {
        double cosine = glm::dot(s.normal, t.direction[i]);
        if (k.wholeSphere != 0) cosine = std::abs(cosine);
        // The solid angle without its sin(theta) (a Riemann sum over dtheta dphi) weighs a
        // texel by 1/sin(theta): near N that is averaged over the texel as over a disc of its
        // angular radius r (2/r), as the student's sum over small steps of theta does, not
        // read at the texel's centre (a fraction of a degree from N at the sizes graded).
        const double radius = std::sqrt(t.solidAngle[i] / std::numbers::pi);
        const double solidAngle =
            k.sinTheta == 1
                ? t.solidAngle[i]
                : t.solidAngle[i] *
                      std::pow(std::max(std::sqrt(std::max(1 - cosine * cosine, 0.0)), radius / 2),
                               k.sinTheta - 1);
        if (cosine > 0) sum += t.radiance[i] * (power(cosine, k.cosine) * solidAngle);
    }
    return sum / std::numbers::pi;
}
std::vector<NamedTerm> texelSumTerms() {
    return namedTerms<Knobs>(
        texelSum,
        {exponentTried<Knobs>("N.L", "the cosine N.L", &Knobs::cosine, 1, {0, 2},
                              [](double e) {
                                  return e == 0   ? std::string("no cosine N.L")
                                         : e == 1 ? std::string("the cosine N.L")
                                                  : "the cosine to the power " + exponentText(e) +
                                                        " (N.L)^" + exponentText(e);
                              }),
         onOff<Knobs>("light from below the horizon counted (|N.L| over the whole sphere, where "
                      "the reference has max(N.L, 0) over the hemisphere)",
                      &Knobs::wholeSphere),
         factorTried<Knobs>("sin(theta)",
                            "the sin(theta) of the solid angle dw = sin(theta) dtheta dphi",
                            {&Knobs::sinTheta}, 1, {0})});
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Irradiance E(N)/PI by convolution";
    d.components = 3;
    d.display = {DisplayMode::HdrColor};
    d.needs = NeedsEnvironment;
    d.skyBackground = true;
    // The quality report (the shipped sky, the reference's own quadrature): float rounding,
    // 1.4e-5 (README.md).
    d.tolerance = {1e-3, 2e-3, 0, 2e-3};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        return c.ibl ? irradianceAt(s.normal, c.ibl->environment) : glm::dvec3(0);
    };
    // N over the whole sphere of directions, laid out like the equirectangular environment:
    // x = longitude (0.5 looks down -z, increasing towards +x), y = latitude from the nadir
    // (0) to the zenith (1). Both ends of x are the same direction; y's ends are the poles.
    d.probe.xAxis = "longitude of N, -180..180 degrees (0 = -z)";
    d.probe.yAxis = "latitude of N, -90..90 degrees";
    d.probe.width = 129;
    d.probe.height = 65;
    d.probe.at = [](double x, double y) {
        const double azimuth = 2 * std::numbers::pi * (x - 0.5);
        const double elevation = std::numbers::pi * (y - 0.5);
        Surface s;
        s.covered = true;
        s.normal = {std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                    -std::cos(elevation) * std::cos(azimuth)};
        s.view = s.normal;
        return s;
    };
    // Graded against the converged integral on the soft sky (README.md, "Grading"): any
    // correct quadrature (a cube texel sum, a Riemann sum in theta and phi, cosine-weighted
    // Monte Carlo) is within 2% of it; every mistake is off by far more.
    EstimatorSpec e;
    e.converged = [](const Surface& s, const ReferenceContext& c, std::uint32_t) {
        return c.ibl ? Estimate{convergedIrradiance(s.normal, c.ibl->environment), glm::dvec3(0)}
                     : Estimate{};
    };
    e.systematic = {2e-3, 1.5e-2, 0};
    e.scaleTolerance = 0.03;
    d.estimator = e;
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.view = s.normal;
        return s;
    };
    d.namedTerms = texelSumTerms();
    d.namedTermPoints = 48;  // each value is a sum over 6144 texels
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
