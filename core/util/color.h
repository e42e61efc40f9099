// The exact sRGB transfer curve (IEC 61966-2-1), once for the host's CPU code: what colour
// textures store, what 8-bit pictures show. The GPU's copy is shaders/color.glsl, the same
// formulas and clamps.
#pragma once

#include <algorithm>
#include <cmath>

namespace pbrlab {

// Linear [0, 1] -> encoded [0, 1]: a linear toe, then a 1 / 2.4 power. Clamped first.
inline double srgbEncode(double linear) {
    const double v = std::clamp(linear, 0.0, 1.0);
    return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

// Encoded [0, 1] -> linear [0, 1], the inverse of srgbEncode. Clamped first.
inline double srgbDecode(double encoded) {
    const double c = std::clamp(encoded, 0.0, 1.0);
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

}  // namespace pbrlab
