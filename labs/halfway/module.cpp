// halfway: the half vector H = normalize(L + V), the microfacet normal that mirrors
// the light into the eye.
#include "pbrlab/module.h"

#include <cmath>
#include <numbers>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Half vector H";
    d.params = {lightDirectionParam()};
    d.components = 3;
    d.nonNegative = false;  // a direction: components are signed
    d.display = {DisplayMode::SignedVector, -1, 1};
    // Band: +- 1e-3 of each component, at least 1e-6, or the spread of 8 ulps of L and V
    // (README.md, "Tolerance and why").
    d.tolerance = {1e-6, 1e-3, 8};
    // Any L and V but nearly opposite ones (V.L >= -0.9; V = -L has no half vector and
    // belongs to the robustness sweep).
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.view = r.direction();
        s.light = r.around(s.view, -0.9, 1);
        s.normal = r.direction();
        return s;
    };
    d.cases = {lessonGridCase()};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return ref::halfwayVector(s.light, s.view);
    };
    // V along the normal, L over the whole hemisphere around it: x = polar angle of L from 0
    // (L = V) to 90 degrees (grazing, 45 at the centre column), y = azimuth of L 0..360 deg.
    // H then leans half as far as L, in the same azimuth. V = -L (no half vector) is not in
    // the teaching domain: the stability sweep covers it.
    d.probe = lightAroundNormalProbe(0.5, 33, "angle(V, L) 0..90 deg (V = N)");
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
