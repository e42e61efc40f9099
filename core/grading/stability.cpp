#include "grading/stability.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace pbrlab {

namespace {

std::string vec(const glm::dvec3& v) {
    std::ostringstream o;
    o << "(" << v.x << "," << v.y << "," << v.z << ")";
    return o.str();
}

const glm::dvec3 kUp(0, 0, 1);
const glm::dvec3 kTilted = glm::normalize(glm::dvec3(0.3, 0.2, 1));

// A covered cell of the extreme set, labelled for reports.
void add(ExtremeSet& set, Surface s, std::string label) {
    s.covered = true;
    set.surfaces.push_back(s);
    set.labels.push_back(std::move(label));
}

// Roughness from 0 to 1 at views head-on, grazing, tilted and from below, with albedo and
// metallic at 0 and 1, each light direction relative to the view: the same, opposite (V = -L),
// grazing, normal, from below, and the zero vector (light exactly at the point).
void addDirections(ExtremeSet& set) {
    const glm::dvec3 up = kUp, grazing(1, 0, 0), side(0, 1, 0), below(0.6, 0, -0.8);
    const double roughnesses[] = {0, 1e-4, 0.05, 0.5, 1};
    const glm::dvec3 views[] = {up, grazing, kTilted, below};
    for (double r : roughnesses)
        for (const auto& V : views)
            for (int l = 0; l < 6; ++l) {
                glm::dvec3 L = l == 0   ? V
                               : l == 1 ? -V
                               : l == 2 ? side
                               : l == 3 ? up
                               : l == 4 ? below
                                        : glm::dvec3(0);
                for (int m = 0; m < 4; ++m) {
                    Surface s;
                    s.normal = up;
                    s.view = V;
                    s.light = L;
                    s.roughness = r;
                    s.albedo = s.albedoTexel = glm::dvec3(m & 1 ? 1.0 : 0.0);
                    s.metallic = m & 2 ? 1.0 : 0.0;
                    s.lightPosition = s.position + L * 2.0;
                    s.lightColor = glm::dvec3(1);
                    s.extra = glm::dvec4(glm::dot(up, V), r, 0, 0);
                    add(set, s,
                        "roughness " + std::to_string(r) + " V " + vec(V) + " L " + vec(L) +
                            " albedo " + std::to_string(s.albedo.x) + " metallic " +
                            std::to_string(s.metallic));
                }
            }
}

// Lights: at the point, very close, far; intensity 0 and 1e6.
void addLightDistances(ExtremeSet& set) {
    for (double d : {0.0, 1e-6, 1e-3, 1.0, 1e3})
        for (double intensity : {0.0, 1.0, 1e6}) {
            Surface s;
            s.normal = kUp;
            s.view = kUp;
            s.position = glm::dvec3(0.25, -0.5, 1);
            s.lightPosition = s.position + kTilted * d;
            s.light = d > 0 ? kTilted : glm::dvec3(0);
            s.lightColor = glm::dvec3(intensity);
            s.albedo = s.albedoTexel = glm::dvec3(0.5);
            s.extra = glm::dvec4(d, intensity, 0, 0);
            add(set, s,
                "light at distance " + std::to_string(d) + " intensity " +
                    std::to_string(intensity));
        }
}

// Scalar probe inputs (extra.x: a cosine, an HDR value...) at and beyond their ends, and
// denormals.
void addScalarInputs(ExtremeSet& set) {
    for (double x : {-1.0, 0.0, 1e-40, 1e-7, 1.0, 1e6})
        for (double y : {0.0, 1e-40, 1.0}) {
            Surface s;
            s.normal = kUp;
            s.view = kUp;
            s.light = kUp;
            s.extra = glm::dvec4(x, y, 0, 0);
            s.roughness = y;
            s.albedo = s.albedoTexel = glm::dvec3(std::max(x, 0.0));
            add(set, s, "extra (" + std::to_string(x) + ", " + std::to_string(y) + ")");
        }
}

// Normal mapping: flat, zero-length decoded normal, tangent parallel to N or zero.
void addNormalMapInputs(ExtremeSet& set) {
    const glm::dvec4 tangents[] = {{1, 0, 0, 1}, {1, 0, 0, -1}, {0, 0, 1, 1}, {0, 0, 0, 1}};
    const glm::dvec3 texels[] = {
        {0.5, 0.5, 1}, {0.5, 0.5, 0.5}, {0, 0, 0}, {1, 1, 1}, {1, 0.5, 0.5}};
    for (const auto& t : tangents)
        for (const auto& n : texels) {
            Surface s;
            s.normal = kUp;
            s.view = kTilted;
            s.light = kTilted;
            s.tangent = t;
            s.normalTexel = n;
            add(set, s,
                "tangent " + vec(glm::dvec3(t)) + " w " + std::to_string(t.w) + " texel " + vec(n));
        }
}

// The set laid out in rows of 32, the last padded with cells not covered.
void padRows(ExtremeSet& set) {
    set.width = 32;
    set.height = int((set.surfaces.size() + 31) / 32);
    set.surfaces.resize(size_t(set.width) * set.height);  // padding: not covered
}

// One ulp of a float just above 1 (2^-23): the host normalises N, V, L and H in float, so
// their lengths are 1 within about 2 of these (measured on llvmpipe: normalize(L + V) over
// 65536 random pairs within 1.32 ulps of length 1, test_inputs.cpp), and a cosine of equal
// unit vectors reaches 1 + 2 ulps.
constexpr double kUlp = std::numeric_limits<float>::epsilon();

// A unit vector as a float normalize() leaves it, then lengthened by `ulps` ulps.
glm::dvec3 unit(const glm::dvec3& d, double ulps) {
    return glm::dvec3(glm::vec3(glm::normalize(d)) * float(1 + ulps * kUlp));
}

// A dot product as the GPU computes it, in float.
double floatDot(const glm::dvec3& a, const glm::dvec3& b) {
    return double(glm::dot(glm::vec3(a), glm::vec3(b)));
}

// 8-bit normal-map texels: flat, both ends of every channel, next to zero length (128/255
// decodes to 1/255 per channel), along the tangent.
const glm::dvec3 kCallerTexels[] = {
    {0.5, 0.5, 1}, {0, 0, 0}, {1, 1, 1}, {128 / 255.0, 128 / 255.0, 128 / 255.0}, {1, 0.5, 0.5}};

// A caller's input at normal N (tangent t), view V and light L, roughness r, with albedo,
// metallic and (1 -) ao at m; `index` picks the tangent's handedness and the texel.
Surface callerSurface(const glm::dvec3& N, const glm::dvec3& V, const glm::dvec3& L,
                      const glm::dvec3& t, double r, int m, int index) {
    Surface s;
    s.covered = true;
    s.normal = N;
    s.view = V;
    s.light = L;
    s.position = glm::dvec3(0.25, -0.5, 1);
    s.lightPosition = s.position + 2.0 * L;
    s.lightColor = glm::dvec3(m ? 100 : 1);
    s.roughness = r;
    s.albedo = s.albedoTexel = glm::dvec3(m);
    s.metallic = m;
    s.ao = 1 - m;
    s.tangent = glm::dvec4(unit(t, 2), index % 2 ? -1 : 1);
    s.normalTexel = kCallerTexels[size_t(index) % std::size(kCallerTexels)];
    return s;
}

// The callers' inputs at normal N: V at each angle from it, with each light the callers give,
// at both ends of roughness and of albedo, metallic and ao. `index` counts the inputs made.
void addCallerInputsAt(ExtremeSet& set, const glm::dvec3& N, double smallestRoughness, int& index) {
    // The angle of V from N: head-on, 30, 60, 85 degrees, grazing (N.V = 0) and 1 degree below
    // the horizon (a silhouette's interpolated normal).
    const double viewDegrees[] = {0, 30, 60, 85, 90, 91};
    const char* lightNames[] = {"V = L", "L = N", "L = mirror of V (H = N)", "N.L = 0",
                                "L below the surface"};
    const glm::dvec3 n = glm::normalize(N);
    const glm::dvec3 a = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 t = glm::normalize(a - n * glm::dot(n, a)), b = glm::cross(n, t);
    for (double degrees : viewDegrees) {
        const double theta = glm::radians(degrees);
        const glm::dvec3 V = unit(n * std::cos(theta) + t * std::sin(theta), 2);
        const glm::dvec3 lights[] = {V, unit(n, 2), unit(glm::reflect(-V, n), 2), unit(b, 2),
                                     unit(0.6 * t - 0.8 * n, 2)};
        for (int l = 0; l < 5; ++l) {
            const glm::dvec3& L = lights[l];
            // V = -L (no half vector): a robustness input, not the callers'.
            if (glm::dot(L, V) < -0.999) continue;
            for (double r : {smallestRoughness, 1.0})
                for (int m = 0; m < 2; ++m) {
                    const Surface s = callerSurface(N, V, L, t, r, m, index++);
                    char label[192];
                    std::snprintf(label, sizeof label,
                                  "%s, N.V = %.9g, N.L = %.9g (in float), roughness %.4g, "
                                  "albedo %d, metallic %d, ao %d",
                                  lightNames[l], floatDot(N, V), floatDot(N, L), r, m, m, 1 - m);
                    set.surfaces.push_back(s);
                    set.labels.push_back(label);
                }
        }
    }
}

// Probe inputs in extra (a sample's Xi, a box corner, an HDR value): what callers pass, up
// to 1 - 2^-16 (Hammersley's radical inverse below 65536 points) and 2^-16.
void addCallerProbeInputs(ExtremeSet& set, const glm::dvec3& normal, double smallestRoughness) {
    const double below1 = 1 - std::exp2(-16), small = std::exp2(-16);
    for (const glm::dvec2 e : {glm::dvec2(0.5, below1), glm::dvec2(below1, 0.5),
                               glm::dvec2(below1, below1), glm::dvec2(small, small)})
        for (double r : {smallestRoughness, 1.0}) {
            Surface s;
            s.covered = true;
            s.normal = normal;
            s.view = s.light = unit(glm::dvec3(0.1, 0.2, 1), 2);
            s.position = glm::dvec3(0.25, -0.5, 1);
            s.lightPosition = s.position + 2.0 * s.light;  // not on the point (a note)
            s.lightColor = glm::dvec3(1);
            s.albedo = s.albedoTexel = glm::dvec3(0.5);
            s.roughness = r;
            s.extra = glm::dvec4(e, 0, 0);
            set.surfaces.push_back(s);
            set.labels.push_back("extra (" + std::to_string(e.x) + ", " + std::to_string(e.y) +
                                 "), roughness " + std::to_string(r));
        }
}

}  // namespace

ExtremeSet extremeSurfaces() {
    ExtremeSet set;
    addDirections(set);
    addLightDistances(set);
    addScalarInputs(set);
    addNormalMapInputs(set);
    padRows(set);
    return set;
}

ExtremeSet callerSurfaces(double smallestRoughness) {
    ExtremeSet set;
    // Normals: exact +z, +z 2 ulps long, two tilted ones 2 ulps short and 2 ulps long.
    const glm::dvec3 normals[] = {unit({0, 0, 1}, 0), unit({0, 0, 1}, 2), unit({0.3, 0.2, 1}, -2),
                                  unit({-0.6, 0.7, 0.38}, 2)};
    int index = 0;
    for (const glm::dvec3& N : normals) addCallerInputsAt(set, N, smallestRoughness, index);
    addCallerProbeInputs(set, normals[3], smallestRoughness);
    padRows(set);
    return set;
}

double smallestRoughness(const ModuleDesc& module) {
    double smallest = 1;
    auto take = [&](const Surface& s) {
        if (s.covered && s.roughness > 0) smallest = std::min(smallest, s.roughness);
    };
    if (module.probe.at)
        for (const Surface& s : probeSurfaces(module.probe)) take(s);
    if (module.domain) {
        DomainRandom random(1);
        for (int i = 0; i < 256; ++i) {
            Surface s = module.domain(random);
            s.covered = true;
            take(s);
        }
    }
    return smallest;
}

namespace {

// The scene's point lights reach some views only through the light uniforms (reflectance sums
// them), not through the per-surface light of the extreme set. For those, a second pass puts
// the scene's lights at the extremes themselves: on the point most extreme surfaces sit at
// (distance 0), on the light set's point with intensity 1e6, 1e-6 away with intensity 1e6,
// below the surface, and far away at grazing incidence.
Scene extremeLights(Scene scene) {
    scene.lights = {{{0, 0, 0}, {1, 1, 1}},
                    {{0.25, -0.5, 1}, glm::dvec3(1e6)},
                    {{0, 1e-6, 0}, glm::dvec3(1e6)},
                    {{0, 0, -2}, {1, 1, 1}},
                    {{1e3, 0, 1e-3}, glm::dvec3(1e6)}};
    return scene;
}

void merge(Comparison& into, const Comparison& more) {
    if (more.worstExcess > into.worstExcess) {
        into.worstExcess = more.worstExcess;
        into.worstX = more.worstX;
        into.worstY = more.worstY;
        into.worstValue = more.worstValue;
        into.worstExpected = more.worstExpected;
    }
    into.quantileExcess = std::max(into.quantileExcess, more.quantileExcess);
    into.compared += more.compared;
    into.nanCount += more.nanCount;
    into.infCount += more.infCount;
    into.negativeCount += more.negativeCount;
    into.outside += more.outside;
}

StabilityResult sweepOnce(LabRenderer& renderer, const LoadedModule& module, const Scene& scene,
                          const StudentSource& source, const ExtremeSet& set,
                          const std::string& labelSuffix) {
    const ModuleDesc& d = *module.desc;
    const ParamValues params(d.params);
    EvalRequest request;  // as in checks: the CPU sampler reads the texels the GPU reads
    request.render = {&module, &params, &scene, source, &set.surfaces, set.width, set.height};
    request.render.seamlessCubes = false;
    const Evaluation e = evaluate(renderer, request);
    StabilityResult result;
    result.gpu = e.comparison;
    for (size_t i = 0; i < set.labels.size(); ++i) {
        bool broken = false;
        for (int c = 0; c < d.components; ++c) {
            double ref = e.band.expected[i][c];
            double gpu = e.render.value.pixels[i * 4 + size_t(c)];
            if (!std::isfinite(ref)) ++result.referenceNonFinite, broken = true;
            if (d.nonNegative && ref < 0) ++result.referenceNegative, broken = true;
            if (!std::isfinite(gpu) || (d.nonNegative && gpu < 0)) broken = true;
        }
        if (broken && result.firstProblem.empty())
            result.firstProblem = set.labels[i] + labelSuffix;
    }
    return result;
}

}  // namespace

StabilityResult stabilitySweep(LabRenderer& renderer, const LoadedModule& module,
                               const Scene& scene, const StudentSource& source) {
    const ExtremeSet set = extremeSurfaces();
    StabilityResult result = sweepOnce(renderer, module, scene, source, set, "");
    const Scene lit = extremeLights(scene);
    if (!readsSceneLights(renderer, module, source, int(lit.lights.size()))) return result;
    StabilityResult more =
        sweepOnce(renderer, module, lit, source, set, " (scene lights at the extremes)");
    merge(result.gpu, more.gpu);
    result.referenceNonFinite += more.referenceNonFinite;
    result.referenceNegative += more.referenceNegative;
    if (result.firstProblem.empty()) result.firstProblem = more.firstProblem;
    return result;
}

}  // namespace pbrlab
