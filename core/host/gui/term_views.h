// The term views: one term of the BRDF, or one of its inputs, per pixel of the picture, from
// the surfaces the G-buffer held, computed with the CPU references (pbrlab::ref).
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <vector>

#include "pbrlab/display.h"
#include "pbrlab/image.h"
#include "pbrlab/module.h"

namespace pbrlab {

struct TermView {
    const char* name;  // as the view chooser and --view name it
    // How the value is encoded for display: linear colours and radiance are display-encoded;
    // the rest (factors in [0, 1], directions mapped to [0, 1]) are shown as they are.
    enum class Encode { None, LinearColor, Radiance } encode;
    std::function<glm::dvec3(const Surface&)> value;
};

// In the view chooser's order, after the image views.
extern const std::vector<TermView> kTermViews;

// The term over the picture: `like` gives the size, surfaces one Surface per pixel (row 0 at
// the top); background pixels are grey.
Image termImage(const TermView& term, const Image& like, const std::vector<Surface>& surfaces);

}  // namespace pbrlab
