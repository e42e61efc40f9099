// glTF 2.0 models (.gltf and .glb) through tinygltf: meshes with positions, normals, uvs and
// tangents (generated, with handedness, when the file has none), node transforms, and the
// metallic-roughness material's factors and which texture maps it uses. Errors name the file.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "pbrlab/mesh.h"

namespace pbrlab {

struct ModelMaterial {
    std::string name;
    glm::dvec4 baseColorFactor{1};
    double metallicFactor = 1, roughnessFactor = 1;
    glm::dvec3 emissiveFactor{0};
    // Which maps the material samples (image indices into the file, -1: none).
    int baseColorTexture = -1, metallicRoughnessTexture = -1, normalTexture = -1,
        occlusionTexture = -1, emissiveTexture = -1;
};

struct ModelPrimitive {
    MeshData mesh;            // in the mesh's own space
    glm::dmat4 transform{1};  // node transform (parents applied)
    int material = -1;        // index into ModelData::materials, -1: the default material
    bool generatedTangents = false;
};

struct ModelData {
    std::filesystem::path file;
    std::vector<ModelPrimitive> primitives;
    std::vector<ModelMaterial> materials;
    int meshCount = 0, imageCount = 0;
};

// Throws pbrlab::Error "FILE: ..." for a missing, truncated or invalid file, or a primitive
// this loader cannot use (not triangles, no positions or normals).
ModelData loadGltf(const std::filesystem::path& file);

// Per-vertex tangents from uv derivatives (Gram-Schmidt against the normal). w = +1 when
// cross(N, T) points towards decreasing v (the image's up: glTF's convention, and the normal
// map's +Y), -1 for mirrored uvs; degenerate uv gives any unit vector perpendicular to N.
void generateTangents(MeshData& mesh);

// The lesson's 7x7 sphere grid as a .glb (one shared sphere mesh, 49 nodes and materials:
// metallic = row / 7, roughness = clamp(column / 7, 0.05, 1), base colour (0.5, 0, 0)).
void writeSphereGridGlb(const std::filesystem::path& file);

}  // namespace pbrlab
