// ndf: the GGX (Trowbridge-Reitz) normal distribution D(N, H, roughness).
#include "pbrlab/module.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// Named terms for feedback (pbrlab/named_terms.h): D with each exponent of its formula fitted.
std::vector<NamedTerm> ndfTerms() {
    using K = ShadingKnobs;
    return namedTerms<K>(
        [](const Surface& s, const ReferenceContext&, const K& k) {
            return glm::dvec3(shadingGgx(glm::dot(s.normal, ref::halfwayVector(s.light, s.view)),
                                         s.roughness, k));
        },
        {exponent<K>("alpha", "alpha", &K::alphaPower, 2, 0.25, 8,
                     [](double e) { return "alpha = roughness^" + exponentText(e); }),
         exponent<K>("alpha^2", "the numerator alpha^2", &K::alpha2, 1, 0, 3,
                     [](double e) { return "(alpha^2)^" + exponentText(e) + " in the numerator"; }),
         exponent<K>("N.H", "N.H", &K::NHpower, 2, 0.25, 6,
                     [](double e) { return "(N.H)^" + exponentText(e) + " in the denominator"; }),
         exponent<K>("denominator", "the denominator", &K::denominator, 2, 0.25, 4,
                     [](double e) { return "the denominator to the power " + exponentText(e); })});
}

// A point with N = z and L = V = H at polar angle theta and azimuth phi around it (so the
// view's halfwayVector(L, V) returns that H).
Surface halfwayAt(double theta, double phi, double roughness) {
    Surface s;
    s.covered = true;
    s.normal = {0, 0, 1};
    s.view = s.light = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                        std::cos(theta)};
    s.roughness = roughness;
    return s;
}

// Normalisation: integral of D(h) (n.h) over the hemisphere = 1. Midpoint rule, 512 theta
// x 8 phi (D does not depend on phi); on the reference the rule is within 2e-5 of 1 at
// these roughnesses, so 1 +- 0.01 judges the student's D, not the quadrature.
std::vector<InvariantResult> normalisation(const EvaluateFn& evaluate) {
    std::vector<InvariantResult> out;
    const int thetas = 512, phis = 8;
    const double pi = std::numbers::pi, dTheta = pi / 2 / thetas, dPhi = 2 * pi / phis;
    for (double r : {0.3, 0.6, 1.0}) {
        std::vector<Surface> hs;
        for (int i = 0; i < thetas; ++i)
            for (int j = 0; j < phis; ++j)
                hs.push_back(halfwayAt((i + 0.5) * dTheta, (j + 0.5) * dPhi, r));
        std::vector<glm::dvec3> D = evaluate(hs);
        double integral = 0;
        for (size_t k = 0; k < hs.size(); ++k)
            integral +=
                D[k].x * hs[k].view.z * std::sqrt(1 - hs[k].view.z * hs[k].view.z) * dTheta * dPhi;
        char name[96];
        std::snprintf(name, sizeof name, "integral of D(h) (n.h) dw at roughness %.1f", r);
        out.push_back({name, integral, "1 +- 0.01", std::abs(integral - 1) <= 0.01,
                       "D is a density of normals: a constant factor (PI, 4) is off"});
    }
    return out;
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "GGX normal distribution D";
    d.params = {lightDirectionParam()};
    d.components = 1;
    d.display = {DisplayMode::FalseColor, 0.01, 100, true};  // D spans decades: log scale
    d.needs = NeedsRoughness;
    // Band: +- 1e-3 of D, or the spread of 8 ulps of N and H, which near the peak of a smooth
    // lobe is what one ulp of N.H does to D (4 / alpha^2 of it; README.md).
    d.tolerance = {1e-9, 1e-3, 8};
    // N anywhere; H around it, half the points near the peak (N.H >= 0.95, where smooth
    // lobes live) and half over the hemisphere; roughness 0.05 to 1. L = V = H, as in the
    // probe, so that the view's halfwayVector(L, V) returns H.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.view = s.light =
            r.uniform() < 0.5 ? r.around(s.normal, 0.95, 1) : r.around(s.normal, 0, 1);
        s.roughness = r.range(0.05, 1);
        return s;
    };
    d.cases = {lessonGridCase()};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return glm::dvec3(
            ref::distributionGGX(s.normal, ref::halfwayVector(s.light, s.view), s.roughness));
    };
    // x: N·H from 0 (H in the tangent plane) to 1 (H = N); y: roughness 0.05 to 1. N = z and
    // L = V = H, so the view's halfwayVector(L, V) returns that H.
    d.probe.xAxis = "N·H 0..1";
    d.probe.yAxis = "roughness 0.05..1";
    d.probe.width = 129;
    d.probe.height = 65;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = s.light = {std::sqrt(1 - x * x), 0, x};
        s.roughness = 0.05 + 0.95 * y;
        return s;
    };
    d.invariants = normalisation;
    // The function receives N and H = halfwayVector(L, V): an error is located by N.H (in the
    // scenes V and L differ, so N.V and N.L would name the wrong axis).
    d.inputAxes = {
        {"N.H",
         [](const Surface& s) { return glm::dot(s.normal, ref::halfwayVector(s.light, s.view)); },
         [](Surface& s, double v) {
             s.view = s.light = atCosine(s.normal, ref::halfwayVector(s.light, s.view), v);
         }},
        {"roughness", [](const Surface& s) { return s.roughness; },
         [](Surface& s, double v) { s.roughness = v; }},
    };
    d.termViews = {{"D", TermView::Encode::None, [](const Surface& s) {
                        const double D = ref::distributionGGX(
                            s.normal, ref::halfwayVector(s.light, s.view), s.roughness);
                        return glm::dvec3(D / (1 + D));  // compresses the peak for display
                    }}};
    d.namedTerms = ndfTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
