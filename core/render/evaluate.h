// One evaluation path: a module's view rendered on some inputs, and the pass band of its CPU
// reference on the same float inputs. `check`, `grade`, the GUI's badges and views and the
// stability sweep all evaluate through here.
#pragma once

#include "render/compare.h"
#include "render/renderer.h"

namespace pbrlab {

// What a CPU reference reads besides the surface: the scene's lights and camera as the
// shader received them (float), and the environment's maps when the module needs them: those
// of `ibl`, the settings of the render it is compared with (RenderRequest::ibl).
ReferenceContext referenceContext(LabRenderer& renderer, const ModuleDesc& module,
                                  const Scene& scene, const ParamValues& params,
                                  const IblSettings& ibl);

struct EvalRequest {
    RenderRequest render;  // set render.seamlessCubes = false to compare (EvalRequest does)
    bool band = true;      // build the reference's pass band and compare with it
    StopRequested stop;    // asked while the band is built (it throws Cancelled)
    EvalRequest() { render.seamlessCubes = false; }
};

struct Evaluation {
    RenderResult render;
    Band band;
    Comparison comparison;
};

Evaluation evaluate(LabRenderer& renderer, const EvalRequest& request);

// Whether the module's view (probe permutation, with this many lights) reads the scene's light
// uniforms: steps that sum the scene's lights are graded and swept with other lights too.
bool readsSceneLights(LabRenderer& renderer, const LoadedModule& module,
                      const StudentSource& source, int lightCount);

}  // namespace pbrlab
