// What a render or a CPU reference reads, as a digest: the key of what is kept of it (a band of
// the reference, the GUI's last solution picture). Each structure's inputs are added here and
// nowhere else. The structures made only of doubles (Surface after `covered`, the camera, a
// light) are added by their bytes, so a field added to them is in every key without a change
// here; the others are listed field by field below, next to one another.
// tests/test_headless.cpp (InputDigest) changes each input and sees the key change.
#pragma once

#include <cstdint>
#include <vector>

#include "pbrlab/module.h"
#include "render/renderer.h"
#include "util/digest.h"

namespace pbrlab {

void addInputs(Digest& digest, const Surface& surface);
void addInputs(Digest& digest, const ParamValues& params);
// The camera, lights, materials (their maps by key and wrap), objects, models (by address:
// whoever keeps the key keeps the scene, so no other model takes it) and the environment.
void addInputs(Digest& digest, const Scene& scene);
// A module by its id, address, components, tolerances and alternatives' names: a reference is
// code, which has no digest here (a grader's altered copy of a module, at another address or
// at the same one later, differs in its tolerances or alternatives).
void addInputs(Digest& digest, const ModuleDesc& module);

// Everything renderer.render(request) reads, or nothing when that includes a student's files
// (their contents are not digested here): the module, its parameters, the scene, the given
// surfaces, the picture's size, the view, the switches that change what is drawn, the IBL
// settings and the environment's maps the view reads.
std::optional<std::uint64_t> renderInputs(LabRenderer& renderer, const RenderRequest& request);

// Everything referenceBand(module, surfaces, context) reads: the module, the context's
// parameters, lights and camera, the environment's maps when the module reads them, and the
// surfaces.
std::uint64_t bandInputs(LabRenderer& renderer, const ModuleDesc& module, const Scene& scene,
                         const ReferenceContext& context, const IblSettings& ibl,
                         const std::vector<Surface>& surfaces);

}  // namespace pbrlab
