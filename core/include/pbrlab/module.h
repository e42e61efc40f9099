// What a lab module is: a descriptor the host reads (id, step, contract function, parameters,
// how its value is displayed and compared) plus a CPU reference in double precision. The
// module's GLSL lives beside it: solution.glsl (the student function) and view.glsl
// (`vec3 view(Surface s)`: what the step shows, evaluated per pixel).
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <glm/glm.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "pbrlab/cube_sampler.h"
#include "pbrlab/params.h"
#include "pbrlab/reference.h"

namespace pbrlab {

// Bump when ModuleDesc or anything it contains changes layout.
constexpr int kModuleAbiVersion = 4;

// Everything a contract function may take, per pixel. The GPU fills the same fields in
// GLSL (shaders/surface.glsl) from the G-buffer (scene) or from uploaded textures (probe), so
// the CPU reference sees exactly the float inputs the shader saw.
struct Surface {
    bool covered = false;  // false: background, nothing to evaluate
    glm::dvec3 position{0}, normal{0, 0, 1};
    glm::dvec4 tangent{1, 0, 0, 1};
    glm::dvec2 uv{0};
    glm::dvec3 view{0, 0, 1};   // V: towards the camera
    glm::dvec3 light{0, 0, 1};  // L: towards the first light (zero when on it)
    glm::dvec3 lightPosition{0}, lightColor{0};
    glm::dvec3 albedoTexel{0};  // the base colour as stored (sRGB-encoded)
    glm::dvec3 albedo{0};       // linear
    double metallic = 0, roughness = 0.5, ao = 1;
    glm::dvec3 normalTexel{0.5, 0.5, 1};  // tangent-space normal map texel in [0, 1]
    glm::dvec3 emissive{0};               // emitted radiance, linear
    glm::dvec4 extra{0};                  // probe-only inputs; meaning given by the module
};

// shaders/common.glsl's pbrlab_grazingBand: smoothstep(0.05, 0.1, 4 N.V N.L).
inline double grazingBand(const Surface& s) {
    double d =
        4 * std::max(glm::dot(s.normal, s.view), 0.0) * std::max(glm::dot(s.normal, s.light), 0.0);
    double t = std::clamp((d - 0.05) / 0.05, 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

// What a CPU reference may read besides the surface.
struct ReferenceContext {
    const ParamValues& params;
    std::vector<ref::PointLight> lights;  // the scene's point lights
    glm::dvec3 cameraPosition{0};
    const IblInputs* ibl = nullptr;  // the precomputed maps, for modules with NeedsEnvironment
};

using ReferenceFn = std::function<glm::dvec3(const Surface&, const ReferenceContext&)>;

enum class DisplayMode {
    Grey,          // (v - lo) / (hi - lo), shown as it is (as the assignment's images are)
    LinearColor,   // a linear colour, sRGB-encoded for the screen
    HdrColor,      // linear radiance: Reinhard, then gamma 1/2.2
    SignedVector,  // a direction: 0.5 + 0.5 v
    FalseColor,    // (v.x - lo) / (hi - lo) through a colour map with a legend
    Encoded,       // already display-encoded (the tonemap step): shown as it is
};

struct Display {
    DisplayMode mode = DisplayMode::Grey;
    double lo = 0, hi = 1;
    bool logScale = false;  // FalseColor: map log10(v) between log10(lo) and log10(hi)
};

// Pass/fail rule: per component, error = |gpu - ref| / max(|ref|, floor). The floor turns the
// measure into an absolute error where the reference is small. Numbers and their measured
// reason are written in the module's handout.
struct Tolerance {
    double floor = 1e-3;
    double maxError = 1e-3;
    // Share of compared pixels allowed over maxError (0: none). For views that filter HDR
    // textures: GL leaves the precision of bilinear weights to the implementation (llvmpipe
    // uses 8 bits), so next to a 20000-bright sun a handful of pixels differ by whole
    // percents while the function is right. NaN, Inf and negatives are never excused.
    double outlierFraction = 0;
};

// A full-screen grid whose pixels map to the function's inputs, domain ends included:
// x and y run over [0, 1] with both ends hit exactly (pixel i -> i / (size - 1)).
struct Probe {
    std::string xAxis, yAxis;  // what x and y mean, for plots and reports
    int width = 65, height = 65;
    std::function<Surface(double x, double y)> at;
    // When x sweeps the light's angle from N in the plane of incidence (x = 0: -90 degrees,
    // x = 1: +90), plots may draw a row as a polar lobe. viewAngle: where V is, in degrees.
    bool xIsLightAngle = false;
    double viewAngle = 0;
};

// N·V along x, from 0 (grazing) to 1 (along the normal); roughness 0.05..1 along y. N = +z,
// V in the xz-plane. Shared by the steps that are functions of the view angle and roughness
// only (g1, brdf_lut).
inline Probe viewCosineRoughnessProbe() {
    Probe p;
    p.xAxis = "N·V 0..1";
    p.yAxis = "roughness 0.05..1";
    p.width = 65;
    p.height = 65;
    p.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {std::sqrt(1 - x * x), 0, x};
        s.roughness = 0.05 + 0.95 * y;
        return s;
    };
    return p;
}

// The plane-of-incidence probe the specular steps share: N = +z, V 60 degrees from N, L swept
// in the same plane from -90 degrees (x = 0, grazing on the mirror side) through the mirror
// direction (x = 1/6), N (x = 1/2) and V itself (x = 5/6) to +90 degrees; y = roughness
// 0.05..1. `material` sets albedo and metallic.
inline Probe planeOfIncidenceProbe(void (*material)(Surface&)) {
    Probe p;
    p.xAxis = "angle(N, L) -90..90 deg (V at +60, mirror at -60)";
    p.yAxis = "roughness 0.05..1";
    p.width = 61;
    p.height = 39;
    p.xIsLightAngle = true;
    p.viewAngle = 60;
    p.at = [material](double x, double y) {
        const double theta = (x - 0.5) * std::numbers::pi, v = std::numbers::pi / 3;
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {std::sin(v), 0, std::cos(v)};
        s.light = {std::sin(theta), 0, std::cos(theta)};
        s.roughness = 0.05 + 0.95 * y;
        material(s);
        return s;
    };
    return p;
}

// Which surface inputs the module's view reads, so that nothing else is loaded or compiled.
enum SurfaceNeeds : unsigned {
    NeedsGeometry = 0,  // position, normal, tangent, uv, V, L: always available
    NeedsAlbedo = 1u << 0,
    NeedsMetallic = 1u << 1,
    NeedsRoughness = 1u << 2,
    NeedsAo = 1u << 3,
    NeedsNormalMap = 1u << 4,
    NeedsEnvironment = 1u << 5,  // IBL: environment cube and the split-sum maps (precompute)
    NeedsEmissive = 1u << 6,     // emitted radiance (modules whose view is the final picture)
    NeedsMaterial = NeedsAlbedo | NeedsMetallic | NeedsRoughness | NeedsAo,
};

// Evaluates the module's view, with the code being graded, on the given surfaces (one value
// each): what invariants are measured with.
using EvaluateFn = std::function<std::vector<glm::dvec3>(const std::vector<Surface>&)>;

// A property any correct answer has (normalisation, bounds, reciprocity, end values),
// reported with the measured value to the student.
struct InvariantResult {
    std::string name;      // "∫ D(h) (n·h) dω = 1 at roughness 0.5"
    double measured = 0;   // the quantity that should meet `expected`
    std::string expected;  // "1 ± 0.02"
    bool holds = false;
};
using InvariantsFn = std::function<std::vector<InvariantResult>(const EvaluateFn&)>;

struct ModuleDesc {
    int abiVersion = kModuleAbiVersion;
    std::string id;        // contract id, e.g. "ndotl"
    int step = 0;          // contract step number (1..21): the lab order
    std::string lab;       // "direct" or "ibl"
    std::string title;     // one line for lists
    std::string function;  // the GLSL signature students implement
    std::vector<ParamDecl> params;
    int components = 1;       // meaningful channels of the value: 1 (float), 2, or 3
    bool nonNegative = true;  // a negative value is an error
    Display display;
    std::string scene = "sphere";    // default scene (assets/scenes/<name>.json)
    unsigned needs = NeedsGeometry;  // SurfaceNeeds flags
    std::vector<std::string> uses;   // other contract ids the view calls
    bool skyBackground = false;      // draw the environment behind the scene (radiance views)
    Tolerance tolerance;
    ReferenceFn reference;
    Probe probe;
    InvariantsFn invariants;  // optional
};

}  // namespace pbrlab

// Exports the module from its shared library. `makeDesc` is a function returning ModuleDesc.
#define PBRLAB_MODULE(makeDesc)                            \
    extern "C" int pbrlab_module_abi() {                   \
        return pbrlab::kModuleAbiVersion;                  \
    }                                                      \
    extern "C" const pbrlab::ModuleDesc* pbrlab_module() { \
        static const pbrlab::ModuleDesc desc = makeDesc(); \
        return &desc;                                      \
    }
