#include "check.h"

namespace pbrlab {

ReferenceContext referenceContext(const Scene& scene, const ParamValues& params) {
    ReferenceContext context{params, {}, glm::dvec3(glm::vec3(scene.camera.position))};
    // The shader received float uniforms; so does the reference.
    for (const auto& l : scene.lights)
        context.lights.push_back(
            {glm::dvec3(glm::vec3(l.position)), glm::dvec3(glm::vec3(l.color))});
    return context;
}

CheckResult checkModule(LabRenderer& renderer, const LoadedModule& module,
                        const ParamValues& params, const Scene& sceneIn,
                        const StudentSource& source, int width, int height) {
    const ModuleDesc& d = *module.desc;
    Scene scene = applyParamBindings(sceneIn, d, params);
    ReferenceContext context = referenceContext(scene, params);
    if (d.needs & NeedsEnvironment) context.ibl = &renderer.environmentInputs(scene);
    CheckResult r;
    renderer.setSeamlessCubes(false);  // see LabRenderer::setSeamlessCubes
    struct Restore {
        LabRenderer& r;
        ~Restore() { r.setSeamlessCubes(true); }
    } restore{renderer};
    RenderResult onScene = renderer.renderScene(module, params, scene, source, width, height, true);
    r.scene = compareWithReference(onScene.value, onScene.surfaces, d, context);
    r.sceneMilliseconds = onScene.milliseconds;
    RenderResult onProbe = renderer.renderProbe(module, params, scene, source);
    r.probe = compareWithReference(onProbe.value, onProbe.surfaces, d, context);
    r.probeMilliseconds = onProbe.milliseconds;
    r.passed = r.scene.compared > 0 && r.scene.passes(d.tolerance, d.nonNegative) &&
               r.probe.passes(d.tolerance, d.nonNegative);
    return r;
}

}  // namespace pbrlab
