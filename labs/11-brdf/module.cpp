// Step 11, brdf: the Cook-Torrance BRDF f_r = kD albedo / PI + specular (no cosine).
#include "pbrlab/module.h"

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace pbrlab;

namespace {

ModuleDesc describeModule() {
    ModuleDesc d;
    d.id = "brdf";
    d.step = 11;
    d.lab = "direct";
    d.title = "Cook-Torrance BRDF kD albedo / PI + specular";
    d.function =
        "vec3 cookTorranceBRDF(vec3 N, vec3 V, vec3 L, vec3 albedo, float metallic, float "
        "roughness)";
    d.params = {lightDirectionParam()};
    d.components = 3;
    d.display = {DisplayMode::HdrColor, 0, 1};
    d.needs = NeedsAlbedo | NeedsMetallic | NeedsRoughness;
    // As step 10: the specular term's GGX peak at roughness 0.05 is off by up to 6.2% in float
    // (sphere grid; 6e-5 on the sphere and the probe). 0.2 leaves 3x; mistakes >= 0.58.
    d.tolerance = {1e-3, 0.2};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return grazingBand(s) *
               ref::cookTorranceBRDF(s.normal, s.view, s.light, s.albedo, s.metallic, s.roughness);
    };
    // As step 10's probe (planeOfIncidenceProbe), for a half-metallic orange: albedo
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
            {"reciprocity max |f(V,L) - f(L,V)| / f", worst, "<= 1e-4", worst <= 1e-4}};
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
