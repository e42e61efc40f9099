// Step 9, fresnel: Schlick's approximation of the Fresnel reflectance, rising from F0 at
// normal incidence to 1 at grazing incidence.
#include "pbrlab/module.h"

#include <cmath>

using namespace pbrlab;

namespace {

// The cosine the view feeds to fresnelSchlick (u_cosine): N·V shows the rim every surface
// gets at grazing view angles; H·V is what the BRDF feeds it (steps 10-12).
enum Cosine { kNdotV = 0, kHdotV = 1 };

double viewCosine(const Surface& s, int cosine) {
    if (cosine == kHdotV)
        return std::max(glm::dot(ref::halfwayVector(s.light, s.view), s.view), 0.0);
    return std::max(glm::dot(s.normal, s.view), 0.0);
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "fresnel";
    d.step = 9;
    d.lab = "direct";
    d.title = "Fresnel-Schlick F = F0 + (1 - F0)(1 - cos)^5";
    d.function = "vec3 fresnelSchlick(float cosTheta, vec3 F0)";
    d.params = {enumParam("cosine", kNdotV, {"NdotV", "HdotV"},
                          "Angle fed to fresnelSchlick: N·V (the rim) or H·V (as in the BRDF)"),
                lightDirectionParam("Direction from the scene centre to the light (H·V only)")};
    d.components = 3;
    d.display = {DisplayMode::LinearColor, 0, 1};
    d.needs = NeedsAlbedo | NeedsMetallic;
    // Float rounding: <= 1.4e-6; with the light behind the sphere (H·V, V ~ -L) the direction
    // of H = L + V is ill-conditioned: 2.7e-4. 2e-3 leaves 7x; mistakes are off by >= 0.27.
    d.tolerance = {1e-3, 2e-3};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        const int cosine = int(c.params.number("cosine"));
        return ref::fresnelSchlick(viewCosine(s, cosine),
                                   ref::baseReflectivity(s.albedo, s.metallic));
    };
    // x: cos θ from 0 (grazing) to 1 (normal incidence); y: F0 grey from 0 to 1 (a metal,
    // metallic 1, so F0 = albedo exactly). V and L lie mirrored about N, so N·V = H·V = x
    // whichever cosine is chosen.
    d.probe.xAxis = "cos theta 0..1";
    d.probe.yAxis = "F0 (grey) 0..1";
    d.probe.width = 65;
    d.probe.height = 33;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        const double sine = std::sqrt(std::max(1 - x * x, 0.0));
        s.normal = {0, 0, 1};
        s.view = {sine, 0, x};
        s.light = {-sine, 0, x};
        s.metallic = 1;
        s.albedo = glm::dvec3(y);
        return s;
    };
    // End values: F = F0 head-on (cos = 1) and F = 1 at grazing (cos = 0), here on a metal
    // whose F0 is its albedo (0.3, 0.5, 0.7); the default view feeds N.V.
    d.invariants = [](const EvaluateFn& evaluate) {
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.albedo = s.albedoTexel = {0.3, 0.5, 0.7};
        s.metallic = 1;
        s.light = s.normal;
        Surface headOn = s, grazing = s;
        headOn.view = {0, 0, 1};
        grazing.view = {1, 0, 0};
        std::vector<glm::dvec3> F = evaluate({headOn, grazing});
        double e0 = glm::length(F[0] - s.albedo), e90 = glm::length(F[1] - glm::dvec3(1));
        return std::vector<InvariantResult>{{"|F(0 deg) - F0|", e0, "<= 1e-3", e0 <= 1e-3},
                                            {"|F(90 deg) - 1|", e90, "<= 1e-3", e90 <= 1e-3}};
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
