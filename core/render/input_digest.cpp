#include "render/input_digest.h"

#include <cstddef>
#include <type_traits>

#include "steps/contract.h"

namespace pbrlab {

namespace {

// The bytes of `value` from `first` to its end: for a structure whose fields from `first` on
// are all doubles (no padding between them), every such field, including any added later.
template <class T, class Field>
void addDoublesFrom(Digest& digest, const T& value, const Field& first) {
    static_assert(std::is_standard_layout_v<T>);
    const auto* begin = reinterpret_cast<const unsigned char*>(&first);
    const auto* end = reinterpret_cast<const unsigned char*>(&value) + sizeof(T);
    digest.add(begin, size_t(end - begin));
}

}  // namespace

void addInputs(Digest& digest, const Surface& surface) {
    static_assert((sizeof(Surface) - offsetof(Surface, position)) % sizeof(double) == 0,
                  "every field of Surface after `covered` is a double or a vector of them");
    digest.add(surface.covered);
    addDoublesFrom(digest, surface, surface.position);
}

void addInputs(Digest& digest, const ParamValues& params) {
    digest.add(params.all().size());
    for (const auto& [name, value] : params.all()) {
        digest.add(name);
        digest.add(value);
    }
}

void addInputs(Digest& digest, const Scene& scene) {
    static_assert(
        sizeof(Camera) % sizeof(double) == 0 && sizeof(PointLightDesc) % sizeof(double) == 0,
        "the camera and a light are made of doubles");
    addDoublesFrom(digest, scene.camera, scene.camera.position);
    digest.add(scene.lights.size());
    for (const PointLightDesc& light : scene.lights) addDoublesFrom(digest, light, light.position);
    digest.add(scene.materials.size());
    for (const MaterialDesc& m : scene.materials) {
        digest.add(m.name);
        digest.add(m.albedo);
        digest.add(glm::dvec4(m.metallic, m.roughness, m.ao, m.occlusionStrength));
        digest.add(m.normalScale);
        digest.add(m.emissive);
        for (const TextureSource* map : {&m.albedoMap, &m.metallicRoughnessMap, &m.roughnessMap,
                                         &m.metallicMap, &m.aoMap, &m.normalMap, &m.emissiveMap}) {
            digest.add(map->key);
            digest.add(map->wrapU);
            digest.add(map->wrapV);
        }
    }
    digest.add(scene.objects.size());
    for (const ObjectDesc& object : scene.objects) {
        digest.add(object.model);
        digest.add(object.translate);
        digest.add(object.scale);
        digest.add(object.material);
    }
    digest.add(scene.models.size());
    for (const SceneModel& model : scene.models) {
        digest.add(reinterpret_cast<std::uintptr_t>(model.data.get()));
        digest.add(model.materialOffset);
    }
    digest.add(scene.environment);
}

void addInputs(Digest& digest, const ModuleDesc& module) {
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
}

std::optional<std::uint64_t> renderInputs(LabRenderer& renderer, const RenderRequest& request) {
    if (!request.module || !request.module->desc || !request.params || !request.scene)
        return std::nullopt;
    const ModuleDesc& d = *request.module->desc;
    // A student's files, or code the digest cannot see.
    if (!request.source.dir.empty() || request.extraUniforms) return std::nullopt;
    // A step whose solution is withheld (an assignment's site) links the student's file in its
    // place: in the view's program (the steps it sees), or for a view that reads the
    // environment's maps, in any step (their passes link steps too).
    const ContractStep* own = findContractStep(d.id);
    std::vector<const ContractStep*> linked;
    if (own && !(d.needs & NeedsEnvironment))
        linked = stepsVisibleFrom(*own);
    else
        for (const ContractStep& step : contractSteps()) linked.push_back(&step);
    for (const ContractStep* step : linked)
        if (solutionWithheld(*step)) return std::nullopt;

    Digest digest;
    addInputs(digest, d);
    addInputs(digest, *request.params);
    addInputs(digest, *request.scene);
    digest.add(request.surfaces != nullptr);
    if (request.surfaces) {
        digest.add(request.surfaces->size());
        for (const Surface& s : *request.surfaces) addInputs(digest, s);
    }
    digest.add(glm::ivec2(request.width, request.height));
    digest.add(request.view);
    // What is drawn and what is returned; not cacheGBuffer and reuseGBuffer, which return what
    // a G-buffer drawn again would.
    for (const bool b :
         {request.source.cumulative, request.source.traceNonFinite, request.readSurfaces,
          request.readValue, request.coarseSpheres, request.seamlessCubes, request.isolatePoints})
        digest.add(b);
    digest.add(request.ibl.key());
    if (d.needs & NeedsEnvironment)
        digest.add(renderer.environmentDigest(*request.scene, request.ibl,
                                              (d.needs & NeedsPrecomputedMaps) != 0));
    return digest.h;
}

std::uint64_t bandInputs(LabRenderer& renderer, const ModuleDesc& module, const Scene& scene,
                         const ReferenceContext& context, const IblSettings& ibl,
                         const std::vector<Surface>& surfaces) {
    Digest digest;
    addInputs(digest, module);
    addInputs(digest, context.params);
    digest.add(context.lights.size());
    for (const ref::PointLight& light : context.lights) {
        digest.add(light.position);
        digest.add(light.color);
    }
    digest.add(context.cameraPosition);
    if (module.needs & NeedsEnvironment)
        digest.add(
            renderer.environmentDigest(scene, ibl, (module.needs & NeedsPrecomputedMaps) != 0));
    digest.add(surfaces.size());
    for (const Surface& s : surfaces) addInputs(digest, s);
    return digest.h;
}

}  // namespace pbrlab
