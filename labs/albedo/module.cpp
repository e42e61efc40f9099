// albedo: decode the sRGB-encoded base-colour texel to linear reflectance.
#include "pbrlab/module.h"

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "sRGB texel to linear albedo";
    d.components = 3;
    d.display = {DisplayMode::LinearColor, 0, 1};
    d.needs = NeedsAlbedo;
    // Band: between the exact curve and pow(c, 2.2), +- 1e-3 of the value or the spread of
    // 8 ulps of the texel (README.md, "Tolerance and why").
    d.tolerance = {1e-6, 1e-3, 8};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return ref::srgbToLinear(s.albedoTexel);
    };
    d.alternatives = {{"pow(c, 2.2), the usual approximation of the sRGB curve (docs/design.md)",
                       [](const Surface& s, const ReferenceContext&) {
                           return glm::pow(glm::clamp(s.albedoTexel, 0.0, 1.0), glm::dvec3(2.2));
                       }}};
    // Any texel, each channel on its own.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.albedoTexel = r.color();
        return s;
    };
    // x: the red texel, y: the green texel, every 8-bit code value i / 255 (0 and 1 included);
    // blue is their mean, so each channel covers [0, 1] and the channels differ.
    d.probe.xAxis = "red texel 0..1 (every 8-bit code)";
    d.probe.yAxis = "green texel 0..1 (every 8-bit code); blue = (red + green) / 2";
    d.probe.width = 256;
    d.probe.height = 256;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.albedoTexel = {x, y, 0.5 * (x + y)};
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
