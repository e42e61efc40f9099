#include "render/evaluate.h"

#include <cstdint>

#include "util/digest.h"

namespace pbrlab {

namespace {

// What referenceBand(module, surfaces, context) reads, field by field (a Surface's padding is
// no input). The module by its id, address, tolerances and alternatives' names: a reference is
// code, which has no digest here (a grader's altered copy of a module, at another address or at
// the same one later, differs in its tolerances or alternatives).
std::uint64_t bandInputs(LabRenderer& renderer, const ModuleDesc& module, const Scene& scene,
                         const ReferenceContext& context, const IblSettings& ibl,
                         const std::vector<Surface>& surfaces) {
    Digest digest;
    digest.add(module.id);
    digest.add(reinterpret_cast<std::uintptr_t>(&module));
    digest.add(module.components);
    for (int c = 0; c < module.components; ++c) {
        const Tolerance& t = module.toleranceFor(c);
        digest.add(glm::dvec4(t.absolute, t.relative, t.ulps, t.outlierFraction));
    }
    for (const AcceptedAlternative& a : module.alternatives) {
        digest.add(a.name);
        digest.add(a.range);
    }
    for (const auto& [name, value] : context.params.all()) {
        digest.add(name);
        digest.add(value);
    }
    for (const ref::PointLight& light : context.lights) {
        digest.add(light.position);
        digest.add(light.color);
    }
    digest.add(context.cameraPosition);
    if (module.needs & NeedsEnvironment)
        digest.add(
            renderer.environmentDigest(scene, ibl, (module.needs & NeedsPrecomputedMaps) != 0));
    digest.add(surfaces.size());
    for (const Surface& s : surfaces) {
        digest.add(s.covered);
        for (const glm::dvec3& v :
             {s.position, s.normal, s.view, s.light, s.lightPosition, s.lightColor, s.albedoTexel,
              s.albedo, s.normalTexel, s.emissive})
            digest.add(v);
        digest.add(s.tangent);
        digest.add(s.uv);
        digest.add(glm::dvec3(s.metallic, s.roughness, s.ao));
        digest.add(s.extra);
    }
    return digest.h;
}

}  // namespace

const Band* BandCache::find(std::uint64_t inputs) {
    for (auto it = bands_.begin(); it != bands_.end(); ++it)
        if (it->first == inputs) {
            bands_.splice(bands_.begin(), bands_, it);
            ++reused_;
            return &bands_.front().second;
        }
    return nullptr;
}

void BandCache::keep(std::uint64_t inputs, const Band& band) {
    ++built_;
    if (capacity_ == 0) return;
    if (bands_.size() >= capacity_) bands_.pop_back();
    bands_.emplace_front(inputs, band);
}

ReferenceContext referenceContext(LabRenderer& renderer, const ModuleDesc& module,
                                  const Scene& scene, const ParamValues& params,
                                  const IblSettings& ibl) {
    ReferenceContext context{params, {}, glm::dvec3(glm::vec3(scene.camera.position))};
    // The shader received float uniforms; so does the reference.
    for (const auto& l : scene.lights)
        context.lights.push_back(
            {glm::dvec3(glm::vec3(l.position)), glm::dvec3(glm::vec3(l.color))});
    if (module.needs & NeedsEnvironment)
        context.ibl = &renderer.environmentInputs(scene, ibl, module.needs & NeedsPrecomputedMaps);
    return context;
}

Evaluation evaluate(LabRenderer& renderer, const EvalRequest& request) {
    const RenderRequest& r = request.render;
    const ModuleDesc& d = *r.module->desc;
    Evaluation e;
    RenderRequest render = r;
    // The band reads the surfaces the view saw (the G-buffer read back, or the given surfaces
    // as floats).
    render.readSurfaces = render.readSurfaces || request.band;
    e.render = renderer.render(render);
    if (!request.band) return e;
    const Scene scene = applyParamBindings(*r.scene, d, *r.params);
    const ReferenceContext context = referenceContext(renderer, d, scene, *r.params, r.ibl);
    BandCache* cache = request.bandCache;
    const std::uint64_t inputs =
        cache ? bandInputs(renderer, d, scene, context, r.ibl, e.render.surfaces) : 0;
    if (const Band* kept = cache ? cache->find(inputs) : nullptr) {
        e.band = *kept;
    } else {
        e.band = referenceBand(d, e.render.surfaces, context, request.stop);
        if (cache) cache->keep(inputs, e.band);
    }
    e.comparison = compareWithBand(e.render.value, e.render.surfaces, e.band, d.components,
                                   d.nonNegative, d.tolerance.outlierFraction);
    return e;
}

bool readsSceneLights(LabRenderer& renderer, const LoadedModule& module,
                      const StudentSource& source, int lightCount) {
    return renderer.programs()
        .get(renderer.viewRecipe(module, source, true, lightCount))
        ->uses("uLightPositions");
}

}  // namespace pbrlab
