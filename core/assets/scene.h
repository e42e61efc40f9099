// A scene as plain data, loaded from JSON (assets/scenes/*.json): camera, point lights,
// materials (factors and optional texture maps), objects (spheres and glTF models) and the
// environment. Errors name the file and field.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "assets/gltf.h"
#include "assets/image_io.h"

namespace pbrlab {

struct Camera {
    glm::dvec3 position{0, 0, 3};
    glm::dvec3 target{0, 0, 0};
    double fovY = 45;  // degrees
};

struct PointLightDesc {
    glm::dvec3 position{0};
    glm::dvec3 color{1};
};

// glTF's metallic-roughness material, which the scene JSON uses too: every map multiplies its
// factor (a JSON material that names a map and no factor gets factor 1, so the map alone
// decides). Maps are read only when a module samples them.
struct MaterialDesc {
    std::string name;
    glm::dvec3 albedo{1};  // linear base colour factor
    double metallic = 0, roughness = 0.5;
    double ao = 1;                                   // ambient occlusion factor
    double occlusionStrength = 1;                    // with aoMap: ao *= 1 + strength * (map.r - 1)
    double normalScale = 1;                          // scales the normal map's x and y
    glm::dvec3 emissive{0};                          // linear emitted radiance factor
    TextureSource albedoMap;                         // sRGB
    TextureSource metallicRoughnessMap;              // glTF packing: G = roughness, B = metallic
    TextureSource roughnessMap, metallicMap, aoMap;  // single channel (R)
    TextureSource normalMap;                         // tangent space, OpenGL (+Y up)
    TextureSource emissiveMap;                       // sRGB
};

// A glTF model as the scene holds it: its geometry and where its materials start in
// Scene::materials (primitive material i is materials[materialOffset + i]; the glTF default
// material, for primitives naming none, is materials[materialOffset + model materials]).
struct SceneModel {
    std::shared_ptr<const ModelData> data;
    int materialOffset = 0;
};

struct ObjectDesc {
    int model = -1;  // index into Scene::models; -1: the built-in unit sphere
    glm::dvec3 translate{0};
    double scale = 1;
    // Index into Scene::materials; for a model -1 keeps the model's own materials, any other
    // value replaces all of them.
    int material = 0;
};

// One mesh to draw: what the G-buffer pass walks, the same for spheres and models.
struct DrawItem {
    const MeshData* mesh = nullptr;  // nullptr: the renderer's unit sphere
    glm::dmat4 transform{1};
    int material = 0;
};

struct Scene {
    std::filesystem::path file;
    Camera camera;
    std::vector<PointLightDesc> lights;
    std::vector<MaterialDesc> materials;
    std::vector<ObjectDesc> objects;
    std::vector<SceneModel> models;
    // Equirectangular radiance (.hdr/.exr, absolute path), or "sky" for the project's own
    // generated environment (the default for modules that need one).
    std::string environment = "sky";
};

// The most point lights a scene has. Every view program declares uLightPositions and
// uLightColors with this many slots whatever the scene's count (PBRLAB_LIGHT_SLOTS,
// shaders/common.glsl) in its fragment shader, a vec4 slot per vec3: 64 lights take 2 * 64 * 4 =
// 512 of the 1024 uniform components OpenGL guarantees a fragment shader
// (MAX_FRAGMENT_UNIFORM_COMPONENTS' minimum), so a scene at the limit compiles on any driver the
// GUI may meet, with the other half left to the contract's own uniforms. Measured: OSMesa's
// llvmpipe (Mesa 22.3) holds 16384 components; the two arrays alone link up to 2049 lights and fail
// at 4096 ("Too many fragment shader default uniform block components"), 100000 with "count of
// uniform locations > MAX_UNIFORM_LOCATIONS".
inline constexpr size_t kMaxSceneLights = 64;

// Throws pbrlab::Error "FILE: field 'objects[3].material': ..." on any problem, including
// texture files that do not exist (paths are relative to the scene file), more than
// kMaxSceneLights lights, or objects that draw more than kMaxDrawnMeshes meshes.
Scene loadScene(const std::filesystem::path& file);

// Every mesh of every object, with its world transform and material.
std::vector<DrawItem> drawItems(const Scene& scene);

// A scene showing one glTF model lit as `base` lights its subject: the model replaces the
// objects, the camera keeps its direction and field of view and moves to frame the model's
// bounds, and the lights are placed and scaled (intensity with distance squared) so the model
// receives what base's subject at the target received. Throws pbrlab::Error naming the file.
Scene sceneForModel(const Scene& base, const std::filesystem::path& modelFile);

// Appends a model (its materials converted) to the scene; returns its index in scene.models.
int addModel(Scene& scene, std::shared_ptr<const ModelData> model);

}  // namespace pbrlab
