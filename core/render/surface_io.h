// Packs pbrlab::Surface into the float textures the GLSL side reads (shaders/surface.glsl)
// and back. The CPU reference always evaluates on unpacked values, i.e. on exactly the
// float inputs the shader saw.
#pragma once

#include <vector>

#include "assets/image_io.h"
#include "pbrlab/module.h"

namespace pbrlab {

constexpr int kGBufferTextures = 7;  // written by the G-buffer pass
constexpr int kProbeTextures = 12;  // the G-buffer's seven plus V, L, light position, colour, extra

// Probe grid -> 12 RGBA images, row 0 = top (as everywhere on the CPU side).
std::vector<Image> packSurfaces(const std::vector<Surface>& surfaces, int width, int height);

// 7 G-buffer images (scene: V and L derived from the camera and the first light, as
// surface.glsl does) or 12 probe images -> one Surface per pixel, row 0 = top.
std::vector<Surface> unpackSurfaces(const std::vector<Image>& textures,
                                    const glm::dvec3& cameraPosition,
                                    const ref::PointLight& firstLight);

}  // namespace pbrlab
