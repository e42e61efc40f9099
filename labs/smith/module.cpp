// smith: Smith shadowing-masking G = G1(N·V) G1(N·L).
#include "pbrlab/module.h"

#include <cmath>

#include "pbrlab/shading_terms.h"

using namespace pbrlab;

namespace {

// Named terms for feedback (pbrlab/named_terms.h): either G1 missing or used for both
// directions, k swapped or remapped as for IBL.
std::vector<NamedTerm> smithTerms() {
    using K = ShadingKnobs;
    return namedTerms<K>(
        [](const Surface& s, const ReferenceContext&, const K& k) {
            const double l = shadingG1(glm::dot(s.normal, s.light), s.roughness, k, 0);
            const double v =
                k.g1lTwice != 0 ? l : shadingG1(glm::dot(s.normal, s.view), s.roughness, k, 0);
            return glm::dvec3(power(v, k.G1V) * power(k.g1vTwice != 0 ? v : l, k.G1L));
        },
        {wholeFactor<K>("G1(N.V)", "the masking term G1(N.V)", {&K::G1V}),
         wholeFactor<K>("G1(N.L)", "the shadowing term G1(N.L)", {&K::G1L}),
         onOff("G1(N.V) for the light too, where the reference has G1(N.L)", &K::g1vTwice),
         onOff("G1(N.L) for the view too, where the reference has G1(N.V)", &K::g1lTwice),
         kSwappedTerm(),
         onOff("k = roughness^2 / 2 (the IBL remapping), where direct light has "
               "k = (roughness + 1)^2 / 8",
               &K::kChoice)});
}

ModuleDesc describeModule() {
    ModuleDesc d;
    d.title = "Smith shadowing-masking G";
    d.params = {lightDirectionParam()};
    d.components = 1;
    d.display = {DisplayMode::Grey, 0, 1};
    d.needs = NeedsRoughness;
    // Band: +- 1e-3 of G, at least 1e-6, or the spread of 8 ulps of N, V and L (README.md).
    d.tolerance = {1e-6, 1e-3, 8};
    // V and L on either side of N and a little below the horizon (N.V, N.L from -0.3: what
    // interpolated normals give at silhouettes and terminators), roughness 0.05 to 1.
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.view = r.around(s.normal, -0.3, 1);
        s.light = r.around(s.normal, -0.3, 1);
        s.roughness = r.range(0.05, 1);
        return s;
    };
    d.cases = {lessonGridCase()};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return glm::dvec3(ref::geometrySmith(s.normal, s.view, s.light, s.roughness));
    };
    // x: N·V, y: N·L, both 0..1, at roughness 0.5; V and L on opposite sides of N.
    d.probe.xAxis = "N·V 0..1";
    d.probe.yAxis = "N·L 0..1 (roughness 0.5)";
    d.probe.width = 65;
    d.probe.height = 65;
    d.probe.at = [](double x, double y) {
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.view = {std::sqrt(1 - x * x), 0, x};
        s.light = {-std::sqrt(1 - y * y), 0, y};
        s.roughness = 0.5;
        return s;
    };
    // Bounds: 0 <= G <= 1 for every N.V, N.L in [0, 1] and roughness in [0.05, 1] (G is a
    // visible fraction).
    d.invariants = [](const EvaluateFn& evaluate) {
        std::vector<Surface> grid;
        for (double a : {0.0, 0.01, 0.1, 0.3, 0.7, 1.0})
            for (double b : {0.0, 0.01, 0.1, 0.3, 0.7, 1.0})
                for (double r : {0.05, 0.3, 0.6, 1.0}) {
                    Surface s;
                    s.covered = true;
                    s.normal = {0, 0, 1};
                    s.view = {std::sqrt(1 - a * a), 0, a};
                    s.light = {-std::sqrt(1 - b * b), 0, b};
                    s.roughness = r;
                    grid.push_back(s);
                }
        std::vector<glm::dvec3> G = evaluate(grid);
        double lo = 1e300, hi = -1e300;
        for (const auto& g : G) lo = std::min(lo, g.x), hi = std::max(hi, g.x);
        return std::vector<InvariantResult>{
            {"smallest G", lo, ">= 0", lo >= 0, "G is a visible fraction"},
            {"largest G", hi, "<= 1 (+1e-5)", hi <= 1 + 1e-5, "G is a visible fraction"}};
    };
    d.termViews = {{"G", TermView::Encode::None, [](const Surface& s) {
                        return glm::dvec3(
                            ref::geometrySmith(s.normal, s.view, s.light, s.roughness));
                    }}};
    d.namedTerms = smithTerms();
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
