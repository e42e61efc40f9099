// Turning values into what a person sees, in one place for the CLI, gallery, GUI and grading
// reports: the module's display mapping, a false-colour map with its legend, and the
// warning colours for non-finite values (NaN magenta, infinity cyan).
#pragma once

#include <glm/glm.hpp>

#include "assets/image_io.h"
#include "pbrlab/module.h"

namespace pbrlab {

inline constexpr glm::dvec3 kBackgroundColor{0.12, 0.12, 0.12};
inline constexpr glm::dvec3 kNanColor{1, 0, 1};
inline constexpr glm::dvec3 kInfColor{0, 1, 1};

// Our own colour map: dark blue -> purple -> red -> orange -> pale yellow, monotonic in
// lightness so that order still reads in grey. t is clamped to [0, 1].
glm::dvec3 falseColor(double t);

// One value (alpha 0: background) -> display RGB in [0, 1] (sRGB-encoded where it applies).
glm::dvec3 displayColor(const glm::dvec4& value, const Display& display, int components);

// The whole image: RGBA in [0, 1], alpha 1.
Image displayImage(const Image& value, const Display& display, int components);

// |a - b| per pixel (max over the first `components` channels) through the false-colour map
// between 0 and `range`; pixels where either image is background stay background.
Image differenceImage(const Image& a, const Image& b, int components, double range);

}  // namespace pbrlab
