// f0: the reflectance at normal incidence F0 of the metallic workflow, 0.04 for
// dielectrics and the albedo for metals, blended by the metallic parameter.
#include "pbrlab/module.h"

using namespace pbrlab;

namespace {

// The probe's albedo at height y: every channel runs over [0, 1] (red up, green as y^2,
// blue down), so each channel of the blend is checked against its own end values.
glm::dvec3 probeAlbedo(double y) {
    return {y, y * y, 1 - y};
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Base reflectivity F0 = mix(0.04, albedo, metallic)";
    d.components = 3;
    d.display = {DisplayMode::LinearColor, 0, 1};
    d.needs = NeedsAlbedo | NeedsMetallic;
    // Band: +- 1e-3 of F0, at least 1e-6, or the spread of 8 ulps of the inputs (README.md).
    d.tolerance = {1e-6, 1e-3, 8};
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.albedo = r.color();
        s.metallic = r.uniform();
        return s;
    };
    d.cases = {lessonGridCase()};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return ref::baseReflectivity(s.albedo, s.metallic);
    };
    // x: metallic 0..1 (0.5 at the centre column); y: albedo (y, y^2, 1 - y).
    d.probe.xAxis = "metallic 0..1";
    d.probe.yAxis = "albedo (y, y^2, 1-y), y 0..1";
    d.probe.width = 33;
    d.probe.height = 33;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.metallic = x;
        s.albedo = probeAlbedo(y);
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
