// glTF 2.0 models (.gltf and .glb) through tinygltf: meshes with positions, normals, uvs and
// tangents (generated, with handedness, when the file has none), node transforms, and the
// metallic-roughness material's factors and maps. Images are not decoded here, nor are
// external image files read: each becomes a TextureSource that a renderer reads on first use,
// so a module that samples no map costs no image work. Errors name the file.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "assets/image_io.h"
#include "assets/mesh.h"

namespace pbrlab {

// The glTF metallic-roughness material (defaults as the specification gives them).
struct ModelMaterial {
    std::string name;
    glm::dvec4 baseColorFactor{1};                   // linear; the map is sRGB and multiplies it
    double metallicFactor = 1, roughnessFactor = 1;  // multiply the map's B and G channels
    double normalScale = 1;                          // scales the normal map's x and y
    double occlusionStrength = 1;                    // ao = 1 + strength * (map.r - 1)
    glm::dvec3 emissiveFactor{0};                    // linear; the map is sRGB and multiplies it
    // Which maps the material samples and how (image: index into ModelData::images, -1: none).
    struct Map {
        int image = -1;
        TextureSource::Wrap wrapU = TextureSource::Wrap::Repeat,
                            wrapV = TextureSource::Wrap::Repeat;  // the texture's sampler
        bool operator==(const Map&) const = default;
    };
    Map baseColorTexture, metallicRoughnessTexture, normalTexture, occlusionTexture,
        emissiveTexture;
};

struct ModelPrimitive {
    MeshData mesh;                   // in the mesh's own space
    glm::dmat4 transform{1};         // node transform (parents applied)
    int material = -1;               // index into ModelData::materials, -1: the default material
    bool generatedNormals = false;   // flat, the file had none
    bool generatedTangents = false;  // the file had none
};

struct ModelData {
    std::filesystem::path file;
    std::vector<ModelPrimitive> primitives;
    std::vector<ModelMaterial> materials;
    std::vector<TextureSource> images;  // not decoded (see above)
    int meshCount = 0;
    std::vector<std::string> warnings;  // features read but not rendered (e.g. TEXCOORD_1)

    size_t vertexCount() const;
    // World-space bounds of every primitive (node transforms applied).
    glm::dvec3 boundsMin() const;
    glm::dvec3 boundsMax() const;
};

// The most meshes one scene draws: each built-in sphere and each glTF primitive that a node
// places is one draw, every frame, of every pass. A glTF model, or a scene, that would draw
// more is refused with an error saying so, rather than rendering for minutes. Measured on a
// grid of spheres, one 512x512 reflectance render with OSMesa's llvmpipe (2 cores, busy):
// 1 sphere 0.5 s of CPU, 1000 5.3 s, 5000 10 s, 10000 16 s (41 s wall): about 1.2 ms each,
// so 10000 is a slow but finished render, and 200000 (once tried) would take minutes.
inline constexpr size_t kMaxDrawnMeshes = 10000;

// Triangle strips and fans become triangle lists; a primitive without normals gets flat ones
// (as the glTF specification asks); points and lines are left out with a warning. Throws
// pbrlab::Error "FILE: ..." for a missing, truncated or invalid file, data it cannot read
// (e.g. sparse or out-of-range accessors), a file with no triangles at all, nodes that are not
// a forest (a loop, a node with two parents: named with the path of the loop), a buffer or
// image outside the model's folder (refused, not read), or more than kMaxDrawnMeshes draws.
ModelData loadGltf(const std::filesystem::path& file);

// Per-vertex tangents from uv derivatives (Gram-Schmidt against the normal). w = +1 when
// cross(N, T) points towards decreasing v (the image's up: glTF's convention, and the normal
// map's +Y), -1 for mirrored uvs; degenerate uv gives any unit vector perpendicular to N.
void generateTangents(MeshData& mesh);

// The lesson's 7x7 sphere grid as a .glb (one shared sphere mesh, 49 nodes and materials:
// metallic = row / 7, roughness = clamp(column / 7, 0.05, 1), base colour (0.5, 0, 0)).
void writeSphereGridGlb(const std::filesystem::path& file);

// A unit sphere wearing the project's metal-plates set as glTF maps embedded in the .glb:
// base colour, metallic-roughness packed with occlusion (R = ao, G = roughness, B = metal, as
// many exporters write it: one image shared by two maps), normal map and emissive glowing
// seams. No TANGENT attribute, so loaders must generate them. `size` is the texture size.
void writeTexturedSphereGlb(const std::filesystem::path& file, int size = 128);

}  // namespace pbrlab
