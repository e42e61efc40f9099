// CPU copies of the GPU's cube maps and LUT, sampled as OpenGL samples them (face selection
// by major axis, bilinear between texel centres, linear between mips), so a module's CPU
// reference can read exactly the precomputed data its shader reads. Bilinear taps that fall
// off a face are clamped to its edge, as the GPU does with GL_TEXTURE_CUBE_MAP_SEAMLESS off
// (how the desktop grades), or taken from the neighbouring face, as it does with it on
// (WebGL 2, where it cannot be turned off: the page's evaluation).
#pragma once

#include <vector>

#include "pbrlab/image.h"
#include "pbrlab/reference.h"

namespace pbrlab {

// OpenGL's cube-map faces (OpenGL 4.5 section 8.13, table 8.19), in one place for every CPU
// copy of a cube: face order +x -x +y -y +z -z; face coordinates s, t in [-1, 1], s along a
// face image's rows, t down its columns (t = -1 is row 0, the t = 0 edge of the texture).
struct CubeFacePoint {
    int face = -1;  // -1: the direction has no major axis (zero length, or not a number)
    double s = 0, t = 0;
};
// The face a direction selects (its major axis; ties go to x, then y) and where it meets it.
CubeFacePoint cubeFacePoint(const glm::dvec3& direction);
// The direction through (s, t) of a face, not normalised (the face is the plane at distance 1
// along its axis): the inverse of cubeFacePoint.
glm::dvec3 cubeFaceDirection(int face, double s, double t);

class CubeSampler {
public:
    CubeSampler() = default;
    // mips[level][face]: square RGBA images, face order +x -x +y -y +z -z, row 0 = t = 0.
    // seamless: filter across face edges (OpenGL 4.5 section 8.14.2: a tap beyond an edge
    // reads the neighbouring face's texel there; a tap beyond a corner, where three faces
    // meet, the mean of those three texels).
    explicit CubeSampler(std::vector<std::vector<Image>> mips, bool seamless = false)
        : mips_(std::move(mips)), seamless_(seamless) {}
    bool seamless() const { return seamless_; }
    bool empty() const { return mips_.empty(); }
    int levels() const { return int(mips_.size()); }
    int size() const { return mips_.empty() ? 0 : mips_[0][0].width; }
    glm::dvec3 sample(const glm::dvec3& dir, double lod = 0) const;
    // mips[level][face], as given.
    const std::vector<std::vector<Image>>& mips() const { return mips_; }

private:
    glm::dvec3 sampleLevel(const glm::dvec3& dir, int level) const;
    // Texel (x, y) of a face, or beyond its edges, the neighbouring faces' (seamless).
    glm::dvec4 texelAcrossEdges(int level, int face, int x, int y) const;
    std::vector<std::vector<Image>> mips_;
    bool seamless_ = false;
};

// Bilinear lookup of a 2D texture at uv in [0, 1] (clamp to edge), row 0 = t = 0.
glm::dvec4 sampleTexture(const Image& image, const glm::dvec2& uv);

// What an IBL module's CPU reference may read: the same maps the shader was given.
struct IblInputs {
    CubeSampler environment;  // uEnvironment (all mips)
    CubeSampler irradiance;   // uIrradianceMap
    CubeSampler prefilter;    // uPrefilterMap
    double prefilterMaxLod = 0;
    Image lut;  // uBrdfLut, row 0 = roughness 0 (t = 0)
};

}  // namespace pbrlab
