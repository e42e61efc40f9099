// One evaluation path: a module's view rendered on some inputs, and the pass band of its CPU
// reference on the same float inputs. `check`, `grade`, the GUI's badges and views and the
// stability sweep all evaluate through here.
#pragma once

#include <cstdint>
#include <list>
#include <utility>

#include "render/compare.h"
#include "render/renderer.h"

namespace pbrlab {

// What a CPU reference reads besides the surface: the scene's lights and camera as the
// shader received them (float), and the environment's maps when the module needs them: those
// of `ibl`, the settings of the render it is compared with (RenderRequest::ibl).
ReferenceContext referenceContext(LabRenderer& renderer, const ModuleDesc& module,
                                  const Scene& scene, const ParamValues& params,
                                  const IblSettings& ibl);

// The last bands evaluate() built, each with a digest of everything it was built from. A band
// is a pure function of the module's reference, the surfaces the view saw and the reference's
// context (parameters, lights, camera, the environment's maps), and it is most of an
// evaluation: nine or more reference evaluations a point. An evaluation that changes only GLSL
// (a student's edit, the next file a grader grades) takes it from here instead of building it
// again. The GUI's evaluation keeps its last band; the page's grader the bands of a grade.
class BandCache {
public:
    explicit BandCache(size_t capacity = 1) : capacity_(capacity) {}
    // The band built from these inputs (null: none kept).
    const Band* find(std::uint64_t inputs);
    void keep(std::uint64_t inputs, const Band& band);
    int built() const { return built_; }    // evaluations that built their band
    int reused() const { return reused_; }  // evaluations that took it from here

private:
    size_t capacity_;
    std::list<std::pair<std::uint64_t, Band>> bands_;  // the most recently used first
    int built_ = 0, reused_ = 0;
};

struct EvalRequest {
    RenderRequest render;  // set render.seamlessCubes = false to compare (EvalRequest does)
    bool band = true;      // build the reference's pass band and compare with it
    StopRequested stop;    // asked while the band is built (it throws Cancelled)
    BandCache* bandCache = nullptr;  // the band of the same inputs is taken from here
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
