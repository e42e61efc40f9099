// A scene as plain data, loaded from JSON (assets/scenes/*.json): camera, point lights,
// materials (factors and optional texture maps) and objects. Errors name the file and field.
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

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

struct MaterialDesc {
    std::string name;
    glm::dvec3 albedo{1};  // linear base colour factor (multiplies the map)
    double metallic = 0, roughness = 0.5, ao = 1;
    // Texture maps, absolute paths; empty when the material has none.
    std::filesystem::path albedoMap, roughnessMap, metallicMap, aoMap, normalMap;
};

struct ObjectDesc {
    std::string primitive = "sphere";
    glm::dvec3 translate{0};
    double scale = 1;
    int material = 0;  // index into Scene::materials
};

struct Scene {
    std::filesystem::path file;
    Camera camera;
    std::vector<PointLightDesc> lights;
    std::vector<MaterialDesc> materials;
    std::vector<ObjectDesc> objects;
    // Equirectangular radiance (.hdr/.exr, absolute path), or "sky" for the project's own
    // generated environment (the default for modules that need one).
    std::string environment = "sky";
};

// Throws pbrlab::Error "FILE: field 'objects[3].material': ..." on any problem, including
// texture files that do not exist (paths are relative to the scene file).
Scene loadScene(const std::filesystem::path& file);

}  // namespace pbrlab
