// tonemap: Reinhard's operator x / (x + 1), then gamma 1/2.2 for the display.
#include "pbrlab/module.h"

#include <cmath>
#include <limits>

#include "pbrlab/named_terms.h"

using namespace pbrlab;

namespace {

// What view.glsl tonemaps: a non-zero s.extra carries the probe's HDR value (w = 1 marks it;
// the stability sweep's extreme values arrive the same way); on the sphere extra is zero and
// the input is the reflected radiance of step `reflectance`. Denormal components count as zero on
// both sides, whether or not the GPU flushes them.
glm::dvec3 hdrInput(const Surface& s, const ReferenceContext& c) {
    const double minNormal = std::numeric_limits<float>::min();  // denormals count as zero
    if (glm::any(glm::greaterThanEqual(glm::abs(s.extra), glm::dvec4(minNormal))))
        return glm::dvec3(s.extra);
    return ref::reflectedRadiance(s.position, s.normal, s.view, s.albedo, s.metallic, s.roughness,
                                  s.ao, c.lights.data(), int(c.lights.size())) +
           s.emissive;
}

// Named terms for feedback (pbrlab/named_terms.h): the gamma's and Reinhard's exponents fitted,
// or the gamma applied first.
struct Knobs {
    double reinhard = -1, gamma = 1 / 2.2, gammaFirst = 0;
};
std::string gammaText(double e) {
    // The exponent is 1 / gamma; above 1 it decodes instead of encoding.
    if (std::abs(e) < 1e-9) return "the exponent 0 (every value 1)";
    if (std::abs(e - 1) < 1e-9) return "no gamma (exponent 1)";
    if (e > 1)
        return "the exponent " + exponentText(e) + " (it decodes: the display needs 1/" +
               exponentText(e) + ")";
    return "gamma " + exponentText(1 / e) + " (exponent 1/" + exponentText(1 / e) + ")";
}
std::vector<NamedTerm> tonemapTerms() {
    return namedTerms<Knobs>(
        [](const Surface& s, const ReferenceContext& c, const Knobs& k) {
            const glm::dvec3 h = glm::max(hdrInput(s, c), glm::dvec3(0.0));
            if (k.gammaFirst != 0) {
                const glm::dvec3 g = power(h, 1 / 2.2);
                return g / (g + 1.0);
            }
            return power(h * power(h + 1.0, k.reinhard), k.gamma);
        },
        {exponent<Knobs>("gamma", "the gamma", &Knobs::gamma, 1 / 2.2, 0.1, 3, gammaText),
         exponent<Knobs>("(1 + hdr)", "Reinhard's denominator", &Knobs::reinhard, -1, -3, 1,
                         [](double e) {
                             return e == 0
                                        ? std::string(
                                              "no Reinhard denominator (hdr, not "
                                              "hdr / (1 + hdr))")
                                        : "hdr (1 + hdr)^" + exponentText(e) + " before the gamma";
                         }),
         onOff<Knobs>("the gamma applied before Reinhard's x / (1 + x), where the reference "
                      "tonemaps first",
                      &Knobs::gammaFirst)});
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Display encoding: Reinhard, then gamma 1/2.2";
    d.components = 3;
    d.display = {DisplayMode::Encoded, 0, 1};
    d.needs = NeedsMaterial | NeedsEmissive;
    // Band: +- 1e-3 of the value, at least 1e-3 (display values: a quarter of an 8-bit step),
    // or the spread of 8 ulps of the HDR input (the gamma's slope near black is steep;
    // README.md).
    d.tolerance = {1e-3, 1e-3, 8};
    // HDR colours from 1e-3 to 1e3 per channel, every decade as likely, carried in extra.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.extra = {r.logRange(1e-3, 1e3), r.logRange(1e-3, 1e3), r.logRange(1e-3, 1e3), 1};
        return s;
    };
    d.cases = {lessonGridCase()};
    d.reference = [](const Surface& s, const ReferenceContext& c) {
        return ref::displayEncode(hdrInput(s, c));
    };
    // x: HDR value v from 1e-3 to 1e3 on a log scale (v = 1 at the centre column); y: hue,
    // hdr = v (1, y, 1 - y): magenta at the bottom, (1, 0.5, 0.5) in the middle, yellow at
    // the top, so every channel also meets hdr = 0 exactly.
    d.probe.xAxis = "HDR value 1e-3..1e3 (log)";
    d.probe.yAxis = "hdr = v (1, y, 1-y), y 0..1";
    d.probe.width = 61;
    d.probe.height = 21;
    d.probe.at = [](double x, double y) {
        const double v = std::pow(10.0, 6 * x - 3);
        Surface s;
        s.covered = true;
        s.extra = {v, v * y, v * (1 - y), 1};
        return s;
    };
    d.extraName = "hdr";  // the radiance the function encodes (extra.xyz), for feedback
    d.namedTerms = tonemapTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
