// Building blocks of the procedural assets (textures, sky): integer hashing and smooth curves.
// Pure functions of their arguments (no std::rand, no clock), so every run writes the same
// bytes and tests can compare files.
#pragma once

#include <algorithm>
#include <cstdint>

namespace pbrlab::procedural {

// A 32-bit avalanche mix (xor-shift / multiply rounds).
inline std::uint32_t mix(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

// [0, 1) from the top 24 bits (exact in a double).
inline double unit(std::uint32_t h) {
    return double(h >> 8) * (1.0 / 16777216.0);
}

inline double lerp(double a, double b, double t) {
    return a + (b - a) * t;
}

inline double smoothstep(double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Perlin's quintic: zero first and second derivatives at 0 and 1.
inline double fade(double t) {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

}  // namespace pbrlab::procedural
