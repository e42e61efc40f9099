// fresnel: Schlick's approximation of the Fresnel reflectance, rising from F0 at
// normal incidence to 1 at grazing incidence.
#include "pbrlab/module.h"

#include <cmath>

#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// The cosine the view feeds to fresnelSchlick (u_cosine): N·V shows the rim every surface
// gets at grazing view angles; H·V is what the BRDF feeds it (steps `specular` to `reflectance`).
enum Cosine { kNdotV = 0, kHdotV = 1 };

double viewCosine(const Surface& s, int cosine) {
    if (cosine == kHdotV)
        return std::max(glm::dot(ref::halfwayVector(s.light, s.view), s.view), 0.0);
    return std::max(glm::dot(s.normal, s.view), 0.0);
}

// Named terms for feedback (pbrlab/named_terms.h): the Schlick factor's power fitted, (1 - F0)
// missing or twice, F0 multiplying the factor.
std::vector<NamedTerm> fresnelTerms() {
    using K = ShadingKnobs;
    return namedTerms<K>(
        [](const Surface& s, const ReferenceContext& c, const K& k) {
            const double cosine =
                c.params.number("cosine") == 1
                    ? std::max(glm::dot(ref::halfwayVector(s.light, s.view), s.view), 0.0)
                    : std::max(glm::dot(s.normal, s.view), 0.0);
            return shadingFresnel(cosine, ref::baseReflectivity(s.albedo, s.metallic), k);
        },
        {exponent<K>("(1 - cos)", "the Schlick factor", &K::schlick, 5, 0.5, 10,
                     [](double e) { return "the Schlick factor (1 - cos)^" + exponentText(e); }),
         factor<K>("(1 - F0)", "the factor (1 - F0) in front of the Schlick factor",
                   {&K::oneMinusF0}),
         onOff("F0 multiplying the Schlick factor (F0 + F0 (1 - cos)^5), where the "
               "reference has F0 + (1 - F0)(1 - cos)^5",
               &K::f0TimesSchlick)});
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Fresnel-Schlick F = F0 + (1 - F0)(1 - cos)^5";
    d.params = {enumParam("cosine", kNdotV, {"NdotV", "HdotV"},
                          "Angle fed to fresnelSchlick: N·V (the rim) or H·V (as in the BRDF)"),
                lightDirectionParam("Direction from the scene centre to the light (H·V only)")};
    d.components = 3;
    d.display = {DisplayMode::LinearColor, 0, 1};
    d.needs = NeedsAlbedo | NeedsMetallic;
    // Band: +- 1e-3 of F, at least 1e-6, or the spread of 8 ulps of the inputs (where V is
    // nearly -L, H and so H.V are ill-conditioned: the spread says how much; README.md).
    d.tolerance = {1e-6, 1e-3, 8};
    // V and L in N's hemisphere (V.L >= -0.9), any albedo and metallic: F0 from
    // baseReflectivity, as in the view.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.view = r.around(s.normal, 0, 1);
        do s.light = r.around(s.normal, 0, 1);
        while (glm::dot(s.light, s.view) < -0.9);
        s.albedo = r.color();
        s.metallic = r.uniform();
        return s;
    };
    d.cases = {lessonGridCase()};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        const int cosine = int(c.params.number("cosine"));
        return ref::fresnelSchlick(viewCosine(s, cosine),
                                   ref::baseReflectivity(s.albedo, s.metallic));
    };
    // x: cos θ from 0 (grazing) to 1 (normal incidence); y: F0 grey from 0 to 1 (a metal,
    // metallic 1, so F0 = albedo exactly). V and L lie mirrored about N, so N·V = H·V = x
    // whichever cosine is chosen.
    d.probe.xAxis = "cos theta 0..1";
    d.probe.yAxis = "F0 (grey) 0..1";
    d.probe.width = 65;
    d.probe.height = 33;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        const double sine = std::sqrt(std::max(1 - x * x, 0.0));
        s.normal = {0, 0, 1};
        s.view = {sine, 0, x};
        s.light = {-sine, 0, x};
        s.metallic = 1;
        s.albedo = glm::dvec3(y);
        return s;
    };
    // End values: F = F0 head-on (cos = 1) and F = 1 at grazing (cos = 0), here on a metal
    // whose F0 is its albedo (0.3, 0.5, 0.7); the default view feeds N.V.
    d.invariants = [](const EvaluateFn& evaluate) {
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.albedo = s.albedoTexel = {0.3, 0.5, 0.7};
        s.metallic = 1;
        s.light = s.normal;
        Surface headOn = s, grazing = s;
        headOn.view = {0, 0, 1};
        grazing.view = {1, 0, 0};
        std::vector<glm::dvec3> F = evaluate({headOn, grazing});
        double e0 = glm::length(F[0] - s.albedo), e90 = glm::length(F[1] - glm::dvec3(1));
        return std::vector<InvariantResult>{
            {"|F(0 deg) - F0|", e0, "<= 1e-3", e0 <= 1e-3, "head-on, Schlick's F is F0"},
            {"|F(90 deg) - 1|", e90, "<= 1e-3", e90 <= 1e-3, "at grazing incidence F is 1"}};
    };
    // F on V.H, as the BRDF uses it; the specular weight kS is F itself.
    auto fresnelOnHalfway = [](const Surface& s) {
        return ref::fresnelSchlick(
            std::max(glm::dot(ref::halfwayVector(s.light, s.view), s.view), 0.0),
            ref::baseReflectivity(s.albedo, s.metallic));
    };
    d.termViews = {{"F", TermView::Encode::None, fresnelOnHalfway},
                   {"kS", TermView::Encode::None, fresnelOnHalfway}};
    d.namedTerms = fresnelTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
