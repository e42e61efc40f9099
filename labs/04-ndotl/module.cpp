// Step 4, ndotl: the Lambert cosine N·L, how much of a light's irradiance reaches a surface.
#include "pbrlab/module.h"

#include <numbers>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "ndotl";
    d.step = 4;
    d.lab = "direct";
    d.title = "Lambert cosine N·L";
    d.function = "float lambertCosine(vec3 N, vec3 L)";
    d.params = {lightDirectionParam()};
    d.components = 1;
    d.display = {DisplayMode::Grey, 0, 1};
    // Float dot products of unit vectors are off by a few 1e-8 from double (measured max
    // scaled error 8.2e-6); 1e-4 leaves room for other GPUs' rounding and still fails any
    // formula error (see README.md).
    d.tolerance = {1e-2, 1e-4};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return glm::dvec3(ref::lambertCosine(s.normal, s.light));
    };
    // x: angle between N and L from 0 to 180 degrees (90 at the centre column, exactly);
    // y: azimuth of L around N, 0 to 360 degrees. The value only depends on x.
    d.probe.xAxis = "angle(N, L) 0..180 deg";
    d.probe.yAxis = "azimuth of L 0..360 deg";
    d.probe.width = 65;
    d.probe.height = 17;
    d.probe.at = [](double x, double y) {
        const double theta = x * std::numbers::pi, phi = y * 2 * std::numbers::pi;
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.light = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta)};
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
