// The term views: one term of the BRDF, or one of its inputs, per pixel of the picture, from
// the surfaces the G-buffer held. The scene inputs are the host's; every other term is declared
// by the step whose lesson it belongs to (ModuleDesc::termViews).
#pragma once

#include <vector>

#include "assets/image_io.h"
#include "pbrlab/module.h"

namespace pbrlab {

class ModuleRegistry;

// In the view chooser's order, after the image views: the scene inputs (albedo, roughness,
// metallic, ao, normal: what the G-buffer holds, no step's), then each loaded step's term
// views, in step order.
std::vector<TermView> termViews(const ModuleRegistry& registry);

// The term over the picture: `like` gives the size, surfaces one Surface per pixel (row 0 at
// the top); background pixels are grey.
Image termImage(const TermView& term, const Image& like, const std::vector<Surface>& surfaces);

}  // namespace pbrlab
