#include "term_views.h"

#include <algorithm>

#include "pbrlab/reference.h"

namespace pbrlab {

namespace {

glm::dvec3 halfway(const Surface& s) {
    return ref::halfwayVector(s.light, s.view);
}

glm::dvec3 fresnel(const Surface& s) {
    return ref::fresnelSchlick(std::max(glm::dot(halfway(s), s.view), 0.0),
                               ref::baseReflectivity(s.albedo, s.metallic));
}

// The diffuse weight kD = (1 - F)(1 - metallic) has no function of its own: it is written
// inside ref::cookTorranceBRDF, as here.
glm::dvec3 diffuseWeight(const Surface& s) {
    return (1.0 - fresnel(s)) * (1.0 - s.metallic);
}

// The light arriving at the point, times the cosine: what a BRDF term is multiplied by.
glm::dvec3 irradiance(const Surface& s) {
    return ref::pointLightRadiance(s.lightColor, s.lightPosition, s.position) *
           ref::lambertCosine(s.normal, s.light);
}

}  // namespace

const std::vector<TermView> kTermViews = {
    {"albedo", TermView::Encode::LinearColor, [](const Surface& s) { return s.albedo; }},
    {"roughness", TermView::Encode::None, [](const Surface& s) { return glm::dvec3(s.roughness); }},
    {"metallic", TermView::Encode::None, [](const Surface& s) { return glm::dvec3(s.metallic); }},
    {"ao", TermView::Encode::None, [](const Surface& s) { return glm::dvec3(s.ao); }},
    {"normal", TermView::Encode::None, [](const Surface& s) { return 0.5 + 0.5 * s.normal; }},
    {"mapped normal", TermView::Encode::None,
     [](const Surface& s) {
         return 0.5 + 0.5 * ref::normalFromMap(s.normal, s.tangent, s.normalTexel);
     }},
    {"N.L", TermView::Encode::None,
     [](const Surface& s) { return glm::dvec3(ref::lambertCosine(s.normal, s.light)); }},
    {"D", TermView::Encode::None,
     [](const Surface& s) {
         const double D = ref::distributionGGX(s.normal, halfway(s), s.roughness);
         return glm::dvec3(D / (1 + D));  // compresses the peak for display
     }},
    {"G", TermView::Encode::None,
     [](const Surface& s) {
         return glm::dvec3(ref::geometrySmith(s.normal, s.view, s.light, s.roughness));
     }},
    {"F", TermView::Encode::None, fresnel},
    {"kS", TermView::Encode::None, fresnel},  // the specular weight is F itself
    {"kD", TermView::Encode::None, diffuseWeight},
    // The Lambert half of ref::cookTorranceBRDF (kD albedo / pi), which has no function of
    // its own, times the light.
    {"diffuse", TermView::Encode::Radiance,
     [](const Surface& s) { return diffuseWeight(s) * s.albedo / ref::kPi * irradiance(s); }},
    {"specular", TermView::Encode::Radiance,
     [](const Surface& s) {
         return ref::cookTorranceSpecular(s.normal, s.view, s.light,
                                          ref::baseReflectivity(s.albedo, s.metallic),
                                          s.roughness) *
                irradiance(s);
     }},
};

Image termImage(const TermView& term, const Image& like, const std::vector<Surface>& surfaces) {
    Image out = like;
    for (size_t i = 0; i < surfaces.size(); ++i) {
        const Surface& s = surfaces[i];
        glm::dvec3 c = term.value(s);
        if (term.encode != TermView::Encode::None) {
            const Display display{term.encode == TermView::Encode::LinearColor
                                      ? DisplayMode::LinearColor
                                      : DisplayMode::HdrColor};
            c = displayColor(glm::dvec4(c, 1), display, 3);
        }
        for (int k = 0; k < 3; ++k) out.pixels[i * 4 + size_t(k)] = s.covered ? float(c[k]) : 0.12f;
        out.pixels[i * 4 + 3] = 1;
    }
    return out;
}

}  // namespace pbrlab
