#include "render/evaluate.h"

#include <cstdint>

#include "render/input_digest.h"

namespace pbrlab {

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
