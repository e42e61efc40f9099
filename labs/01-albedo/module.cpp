// Step 1, albedo: decode the sRGB-encoded base-colour texel to linear reflectance.
#include "pbrlab/module.h"

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "albedo";
    d.step = 1;
    d.lab = "direct";
    d.title = "sRGB texel to linear albedo";
    d.function = "vec3 srgbToLinear(vec3 c)";
    d.components = 3;
    d.display = {DisplayMode::LinearColor, 0, 1};
    d.needs = NeedsAlbedo;
    // pow(c, 2.2) is a correct variant and differs from the exact curve by up to 0.085
    // (floor 0.05); 0.15 accepts it, float rounding is 7e-7, and mistakes are off by >= 0.9.
    d.tolerance = {0.05, 0.15};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return ref::srgbToLinear(s.albedoTexel);
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
