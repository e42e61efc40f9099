// ndotl: the Lambert cosine N·L, how much of a light's irradiance reaches a surface.
#include "pbrlab/module.h"

#include <numbers>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Lambert cosine N·L";
    d.params = {lightDirectionParam()};
    d.components = 1;
    d.display = {DisplayMode::Grey, 0, 1};
    // Band: +- 1e-3 of the value, at least 1e-6, or the spread of 8 ulps of N and L
    // (README.md, "Tolerance and why").
    d.tolerance = {1e-6, 1e-3, 8};
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.light = r.direction();
        s.view = r.around(s.normal, 0, 1);
        return s;
    };
    d.cases = {lessonGridCase()};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return glm::dvec3(ref::lambertCosine(s.normal, s.light));
    };
    // x: angle between N and L from 0 to 180 degrees (90 at the centre column, exactly);
    // y: azimuth of L around N, 0 to 360 degrees. The value only depends on x.
    d.probe = lightAroundNormalProbe(1, 17, "angle(N, L) 0..180 deg");
    d.termViews = {{"N.L", TermView::Encode::None, [](const Surface& s) {
                        return glm::dvec3(ref::lambertCosine(s.normal, s.light));
                    }}};
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
