// Step 2, radiance: the radiance a point light delivers at a point, falling off as 1/d^2.
#include "pbrlab/module.h"

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "radiance";
    d.step = 2;
    d.lab = "direct";
    d.title = "Point-light radiance (inverse square)";
    d.function = "vec3 pointLightRadiance(vec3 lightColor, vec3 lightPos, vec3 worldPos)";
    d.params = {lightDirectionParam()};
    d.components = 3;
    d.display = {DisplayMode::HdrColor, 0, 1};
    // Float rounding of a difference, a dot and a division: measured <= 3.2e-7 relative;
    // 5e-6 leaves 15x for other drivers, and any wrong falloff is off by > 1.
    d.tolerance = {1e-3, 5e-6};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return ref::pointLightRadiance(s.lightColor, s.lightPosition, s.position);
    };
    // x: distance from the point to the light, 0.05 to 5 (2.525 at the centre column);
    // y: intensity of a white light, 0 to 10.
    d.probe.xAxis = "distance d 0.05..5";
    d.probe.yAxis = "intensity 0..10 (white)";
    d.probe.width = 65;
    d.probe.height = 65;
    d.probe.at = [](double x, double y) {
        const glm::dvec3 direction = glm::dvec3(1, 2, 2) / 3.0;
        const double distance = 0.05 + 4.95 * x;
        Surface s;
        s.covered = true;
        s.position = {0.5, -0.25, 1};
        s.normal = {0, 0, 1};
        s.light = direction;
        s.lightPosition = s.position + direction * distance;
        s.lightColor = glm::dvec3(10 * y);
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
