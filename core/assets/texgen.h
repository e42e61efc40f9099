// Procedural textures the project makes itself instead of shipping downloaded ones.
// Deterministic: integer-hash noise only (no std::rand, no clock), so every run writes the same
// bytes and tests can compare files.
#pragma once

#include <filesystem>

namespace pbrlab {

// A "metal plates" PBR texture set: a tileable grid of riveted plates with grooves between
// them, some painted (dielectric, with chipped paint near seams and rivets) and some bare
// metal, with scratches and noise. Writes into outDir (created if missing), size x size each:
//   albedo.png     8-bit RGB, sRGB-encoded, tagged sRGB
//   roughness.png  16-bit grayscale, linear (perceptual roughness, smooth over > 256 levels)
//   metallic.png   16-bit grayscale, linear (0 paint, 1 metal, soft transitions)
//   ao.png         8-bit grayscale, linear (dark in grooves and around rivet heads)
//   normal.png     8-bit RGB tangent-space normal, OpenGL convention (+Y towards the image
//                  top), rgb = n * 0.5 + 0.5, from the same height field as ao
// size must be in [16, 4096]; features scale with it (they are placed in uv units). Throws
// pbrlab::Error on a bad size or a failed write.
void generateMetalPlates(const std::filesystem::path& outDir, int size = 256);

}  // namespace pbrlab
