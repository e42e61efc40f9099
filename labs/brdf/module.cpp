// brdf: the Cook-Torrance BRDF f_r = kD albedo / PI + specular (no cosine).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// Named terms for feedback (pbrlab/shading_terms.h): the lobe's and the diffuse term's
// factors, and the cosine N.L, which belongs to the reflectance equation.
std::vector<NamedTerm> brdfTerms() {
    using K = ShadingKnobs;
    return namedTerms<K>(
        [](const Surface& s, const ReferenceContext&, const K& k) {
            return grazingBand(s) * shadingBrdf(s, s.light, k);
        },
        joined(joined(specularLobeTerms(false), diffuseTerms()),
               {wholeFactor<K>(
                   "N.L", "the cosine N.L (it belongs to the reflectance equation, not to f_r)",
                   {&K::cosine}, 0)}));
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Cook-Torrance BRDF kD albedo / PI + specular";
    d.params = {lightDirectionParam()};
    d.components = 3;
    d.display = {DisplayMode::HdrColor, 0, 1};
    d.needs = NeedsAlbedo | NeedsMetallic | NeedsRoughness;
    // As step `specular`: between the floored and the lesson's denominator, +- 1e-3 of the value or
    // the spread of 8 ulps of N, V, L (README.md).
    d.tolerance = {1e-7, 1e-3, 8};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return grazingBand(s) *
               ref::cookTorranceBRDF(s.normal, s.view, s.light, s.albedo, s.metallic, s.roughness);
    };
    d.alternatives = {{"the lesson's 4 N.V N.L + 0.001 in the specular denominator (seed 001)",
                       [](const Surface& s, const ReferenceContext&) {
                           return grazingBand(s) *
                                  ref::cookTorranceBRDF(s.normal, s.view, s.light, s.albedo,
                                                        s.metallic, s.roughness,
                                                        ref::DenominatorGuard::LessonEpsilon);
                       },
                       true}};
    d.domain = highlightDomain;  // the whole lobe, half the points near the highlight
    d.cases = {lessonGridCase()};
    // As step `specular`'s probe (planeOfIncidenceProbe), for a half-metallic orange: albedo
    // (0.9, 0.5, 0.1), metallic 0.5, so both the diffuse and the specular term show in every
    // channel.
    d.probe = planeOfIncidenceProbe([](Surface& s) {
        s.metallic = 0.5;
        s.albedo = s.albedoTexel = glm::dvec3(0.9, 0.5, 0.1);
    });
    // Reciprocity (Helmholtz): f(V, L) = f(L, V). Pairs with N.V, N.L >= 0.3, dielectric and
    // metal, two roughnesses; the largest relative difference over them.
    d.invariants = [](const EvaluateFn& evaluate) {
        std::vector<Surface> pairs;
        const double cosines[] = {0.3, 0.6, 0.95};
        for (double a : cosines)
            for (double b : cosines)
                for (double r : {0.3, 0.8})
                    for (double m : {0.0, 1.0}) {
                        Surface s;
                        s.covered = true;
                        s.normal = {0, 0, 1};
                        s.albedo = s.albedoTexel = {0.8, 0.5, 0.2};
                        s.metallic = m;
                        s.roughness = r;
                        s.view = {std::sqrt(1 - a * a), 0, a};
                        s.light = glm::normalize(
                            glm::dvec3(-0.6 * std::sqrt(1 - b * b), 0.8 * std::sqrt(1 - b * b), b));
                        Surface swapped = s;
                        std::swap(swapped.view, swapped.light);
                        pairs.push_back(s);
                        pairs.push_back(swapped);
                    }
        std::vector<glm::dvec3> f = evaluate(pairs);
        double worst = 0;
        for (size_t i = 0; i + 1 < f.size(); i += 2)
            for (int c = 0; c < 3; ++c)
                worst = std::max(
                    worst, std::abs(f[i][c] - f[i + 1][c]) / std::max(std::abs(f[i][c]), 1e-3));
        return std::vector<InvariantResult>{
            {"reciprocity max |f(V,L) - f(L,V)| / f", worst, "<= 1e-4", worst <= 1e-4,
             "f_r(V, L) = f_r(L, V) for any BRDF: something treats V and L differently"}};
    };
    // The diffuse weight kD = (1 - F)(1 - metallic) and the Lambert half of the BRDF
    // (kD albedo / pi) have no function of their own: they are written inside
    // ref::cookTorranceBRDF, as here.
    auto diffuseWeight = [](const Surface& s) {
        const glm::dvec3 F = ref::fresnelSchlick(
            std::max(glm::dot(ref::halfwayVector(s.light, s.view), s.view), 0.0),
            ref::baseReflectivity(s.albedo, s.metallic));
        return (1.0 - F) * (1.0 - s.metallic);
    };
    d.termViews = {{"kD", TermView::Encode::None, diffuseWeight},
                   {"diffuse", TermView::Encode::Radiance, [diffuseWeight](const Surface& s) {
                        return diffuseWeight(s) * s.albedo / ref::kPi * incidentIrradiance(s);
                    }}};
    d.namedTerms = brdfTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
