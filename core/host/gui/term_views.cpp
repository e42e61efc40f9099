#include "term_views.h"

#include "render/display.h"
#include "steps/plugin_host.h"

namespace pbrlab {

std::vector<TermView> termViews(const ModuleRegistry& registry) {
    std::vector<TermView> terms = {
        {"albedo", TermView::Encode::LinearColor, [](const Surface& s) { return s.albedo; }},
        {"roughness", TermView::Encode::None,
         [](const Surface& s) { return glm::dvec3(s.roughness); }},
        {"metallic", TermView::Encode::None,
         [](const Surface& s) { return glm::dvec3(s.metallic); }},
        {"ao", TermView::Encode::None, [](const Surface& s) { return glm::dvec3(s.ao); }},
        {"normal", TermView::Encode::None, [](const Surface& s) { return 0.5 + 0.5 * s.normal; }},
    };
    for (const LoadedModule& m : registry.modules())
        terms.insert(terms.end(), m.desc->termViews.begin(), m.desc->termViews.end());
    return terms;
}

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
