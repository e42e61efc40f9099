// Step 3, halfway: the half vector H = normalize(L + V), the microfacet normal that mirrors
// the light into the eye.
#include "pbrlab/module.h"

#include <cmath>
#include <numbers>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "halfway";
    d.step = 3;
    d.lab = "direct";
    d.title = "Half vector H";
    d.function = "vec3 halfwayVector(vec3 L, vec3 V)";
    d.params = {lightDirectionParam()};
    d.components = 3;
    d.nonNegative = false;  // a direction: components are signed
    d.display = {DisplayMode::SignedVector, -1, 1};
    // Float rounding of a normalisation: measured <= 4.8e-6 (floor 0.01) with the light in
    // front; 1e-4 leaves 20x, and the nearest mistake (the average) is off by 0.19.
    d.tolerance = {1e-2, 1e-4};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return ref::halfwayVector(s.light, s.view);
    };
    // V along the normal, L over the whole hemisphere around it: x = polar angle of L from 0
    // (L = V) to 90 degrees (grazing, 45 at the centre column), y = azimuth of L 0..360 deg.
    // H then leans half as far as L, in the same azimuth. V = -L (no half vector) is not in
    // the teaching domain: the stability sweep covers it.
    d.probe.xAxis = "angle(V, L) 0..90 deg (V = N)";
    d.probe.yAxis = "azimuth of L 0..360 deg";
    d.probe.width = 65;
    d.probe.height = 33;
    d.probe.at = [](double x, double y) {
        const double theta = x * std::numbers::pi / 2, phi = y * 2 * std::numbers::pi;
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {0, 0, 1};
        s.light = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta)};
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
