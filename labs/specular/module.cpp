// specular: the Cook-Torrance specular lobe D G F / (4 N·V N·L).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// Named terms for feedback (pbrlab/shading_terms.h): each factor of the lobe, which is the
// step's whole value.
std::vector<NamedTerm> specularTerms() {
    return namedTerms<ShadingKnobs>(
        [](const Surface& s, const ReferenceContext&, const ShadingKnobs& k) {
            return grazingBand(s) * cookTorranceLobe(s, s.light, k).specular;
        },
        specularLobeTerms(true));
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Cook-Torrance specular D G F / (4 N·V N·L)";
    d.params = {lightDirectionParam()};
    d.components = 3;
    d.display = {DisplayMode::FalseColor, 1e-4, 10, true};
    d.needs = NeedsAlbedo | NeedsMetallic | NeedsRoughness;
    // Band: between the floored and the lesson's + 0.001 denominator, +- 1e-3 of the value or
    // the spread of 8 ulps of N, V, L (near the peak of a smooth lobe one ulp of N.H moves D by
    // 4 / alpha^2 of it; README.md).
    d.tolerance = {1e-7, 1e-3, 8};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return grazingBand(s) *
               ref::cookTorranceSpecular(s.normal, s.view, s.light,
                                         ref::baseReflectivity(s.albedo, s.metallic), s.roughness);
    };
    d.alternatives = {{"the lesson's 4 N.V N.L + 0.001 in the denominator (seed 001)",
                       [](const Surface& s, const ReferenceContext&) {
                           return grazingBand(s) * ref::cookTorranceSpecular(
                                                       s.normal, s.view, s.light,
                                                       ref::baseReflectivity(s.albedo, s.metallic),
                                                       s.roughness,
                                                       ref::DenominatorGuard::LessonEpsilon);
                       },
                       true}};
    d.domain = highlightDomain;  // the whole lobe, half the points near the highlight
    d.cases = {lessonGridCase()};
    // In the plane of incidence (planeOfIncidenceProbe), F0 = (0.95, 0.5, 0.04): a metal's,
    // an in-between one and a dielectric's (metallic 1, albedo = F0).
    d.probe = planeOfIncidenceProbe([](Surface& s) {
        s.metallic = 1;
        s.albedo = s.albedoTexel = glm::dvec3(0.95, 0.5, 0.04);
    });
    // White furnace: with F0 = 1 and uniform white light the specular lobe reflects at most
    // what arrives: integral of f_spec (N.L) dL <= 1 for any V. Midpoint rule over the
    // hemisphere, 128 theta x 128 phi, at N.V = 0.7 and roughness 0.5 / 1 (smooth lobes need
    // finer grids than a grader should spend). The view's grazing fade only removes energy.
    d.invariants = [](const EvaluateFn& evaluate) {
        std::vector<InvariantResult> out;
        const int thetas = 128, phis = 128;
        const double pi = std::numbers::pi, dTheta = pi / 2 / thetas, dPhi = 2 * pi / phis;
        for (double r : {0.5, 1.0}) {
            std::vector<Surface> ls;
            for (int i = 0; i < thetas; ++i)
                for (int j = 0; j < phis; ++j) {
                    double theta = (i + 0.5) * dTheta, phi = (j + 0.5) * dPhi;
                    Surface s;
                    s.covered = true;
                    s.normal = {0, 0, 1};
                    s.view = {std::sqrt(1 - 0.49), 0, 0.7};
                    s.light = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                               std::cos(theta)};
                    s.albedo = s.albedoTexel = glm::dvec3(1);
                    s.metallic = 1;  // F0 = albedo = 1 for the view's baseReflectivity
                    s.roughness = r;
                    ls.push_back(s);
                }
            std::vector<glm::dvec3> f = evaluate(ls);
            double albedo = 0;
            for (size_t k = 0; k < ls.size(); ++k) {
                double cosTheta = ls[k].light.z;
                albedo += f[k].x * cosTheta * std::sqrt(1 - cosTheta * cosTheta) * dTheta * dPhi;
            }
            char name[96];
            std::snprintf(name, sizeof name, "white-furnace albedo at roughness %.1f", r);
            out.push_back({name, albedo, "<= 1 (+0.01)", albedo <= 1.01,
                           "the lobe reflects more light than arrives: a factor is missing from "
                           "the denominator"});
        }
        return out;
    };
    d.termViews = {{"specular", TermView::Encode::Radiance, [](const Surface& s) {
                        return ref::cookTorranceSpecular(
                                   s.normal, s.view, s.light,
                                   ref::baseReflectivity(s.albedo, s.metallic), s.roughness) *
                               incidentIrradiance(s);
                    }}};
    d.namedTerms = specularTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
