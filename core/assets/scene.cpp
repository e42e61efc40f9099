#include "assets/scene.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "assets/envgen.h"
#include "util/error.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace pbrlab {

namespace {

struct Reader {
    fs::path file;

    [[noreturn]] void fail(const std::string& field, const std::string& why) const {
        throw Error(file.string() + ": field '" + field + "': " + why);
    }
    double number(const json& j, const std::string& field) const {
        if (!j.is_number()) fail(field, "expected a number");
        return j.get<double>();
    }
    glm::dvec3 vec3(const json& j, const std::string& field) const {
        if (!j.is_array() || j.size() != 3) fail(field, "expected [x, y, z]");
        glm::dvec3 v;
        for (int i = 0; i < 3; ++i)
            v[i] = number(j[size_t(i)], field + "[" + std::to_string(i) + "]");
        return v;
    }
    double unit(const json& j, const std::string& field) const {
        double v = number(j, field);
        if (v < 0 || v > 1) fail(field, "expected a value in [0, 1], got " + std::to_string(v));
        return v;
    }
    TextureSource texture(const json& j, const std::string& field) const {
        if (!j.is_string()) fail(field, "expected a file path");
        fs::path p = file.parent_path() / j.get<std::string>();
        if (!fs::is_regular_file(p)) fail(field, "texture " + p.string() + " does not exist");
        TextureSource t;
        t.file = fs::weakly_canonical(p);
        t.key = t.file.string();
        return t;
    }
    void onlyKnown(const json& j, const std::string& field,
                   std::initializer_list<const char*> keys) const {
        for (const auto& [key, _] : j.items()) {
            bool known = false;
            for (const char* k : keys) known = known || key == k;
            if (!known) {
                std::string list;
                for (const char* k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
                fail(field.empty() ? key : field + "." + key,
                     "unknown field (known: " + list + ")");
            }
        }
    }

    MaterialDesc material(const json& j, const std::string& field, const std::string& name) const {
        if (!j.is_object()) fail(field, "expected an object");
        onlyKnown(j, field,
                  {"albedo", "metallic", "roughness", "ao", "emissive", "albedoMap",
                   "metallicRoughnessMap", "roughnessMap", "metallicMap", "aoMap", "normalMap",
                   "emissiveMap"});
        MaterialDesc m;
        m.name = name;
        std::pair<const char*, TextureSource*> maps[] = {
            {"albedoMap", &m.albedoMap},
            {"metallicRoughnessMap", &m.metallicRoughnessMap},
            {"roughnessMap", &m.roughnessMap},
            {"metallicMap", &m.metallicMap},
            {"aoMap", &m.aoMap},
            {"normalMap", &m.normalMap},
            {"emissiveMap", &m.emissiveMap}};
        for (auto& [key, map] : maps)
            if (j.contains(key)) *map = texture(j[key], field + "." + key);
        if (j.contains("metallicRoughnessMap") &&
            (j.contains("metallicMap") || j.contains("roughnessMap")))
            fail(field + ".metallicRoughnessMap",
                 "give either metallicRoughnessMap or metallicMap/roughnessMap, not both");
        // A map multiplies its factor; without a factor the map alone decides (factor 1).
        const bool mappedMetal = j.contains("metallicMap") || j.contains("metallicRoughnessMap");
        const bool mappedRough = j.contains("roughnessMap") || j.contains("metallicRoughnessMap");
        if (mappedMetal) m.metallic = 1;
        if (mappedRough) m.roughness = 1;
        if (j.contains("emissiveMap")) m.emissive = glm::dvec3(1);
        if (j.contains("albedo")) m.albedo = vec3(j["albedo"], field + ".albedo");
        if (j.contains("metallic")) m.metallic = unit(j["metallic"], field + ".metallic");
        if (j.contains("roughness")) m.roughness = unit(j["roughness"], field + ".roughness");
        if (j.contains("ao")) m.ao = unit(j["ao"], field + ".ao");
        if (j.contains("emissive")) m.emissive = vec3(j["emissive"], field + ".emissive");
        for (int i = 0; i < 3; ++i) {
            if (m.albedo[i] < 0 || m.albedo[i] > 1) fail(field + ".albedo", "components in [0, 1]");
            if (m.emissive[i] < 0 || !std::isfinite(m.emissive[i]))
                fail(field + ".emissive", "components must be finite and >= 0");
        }
        return m;
    }
};

// glTF's material as the scene's: the same factors-times-maps meaning.
MaterialDesc fromModel(const ModelMaterial& mm, const ModelData& model) {
    MaterialDesc m;
    m.name = mm.name;
    m.albedo = glm::dvec3(mm.baseColorFactor);
    m.metallic = mm.metallicFactor;
    m.roughness = mm.roughnessFactor;
    m.ao = 1;
    m.occlusionStrength = mm.occlusionStrength;
    m.normalScale = mm.normalScale;
    m.emissive = mm.emissiveFactor;
    auto image = [&](const ModelMaterial::Map& map) {
        if (map.image < 0) return TextureSource{};
        TextureSource t = model.images.at(size_t(map.image));
        t.wrapU = map.wrapU;
        t.wrapV = map.wrapV;
        return t;
    };
    m.albedoMap = image(mm.baseColorTexture);
    m.metallicRoughnessMap = image(mm.metallicRoughnessTexture);
    m.aoMap = image(mm.occlusionTexture);
    m.normalMap = image(mm.normalTexture);
    m.emissiveMap = image(mm.emissiveTexture);
    return m;
}

// What drawItems(scene).size() will be.
size_t drawCount(const Scene& scene) {
    size_t draws = 0;
    for (const ObjectDesc& o : scene.objects)
        draws += o.model < 0 ? 1 : scene.models.at(size_t(o.model)).data->primitives.size();
    return draws;
}

// The scene file's JSON; a file that cannot be opened or parsed is an error naming it.
json readSceneJson(const fs::path& file) {
    std::ifstream in(file);
    if (!in) throw Error(file.string() + ": cannot open scene file");
    json doc;
    try {
        doc = json::parse(in);
    } catch (const json::parse_error& e) {
        throw Error(file.string() + ": not valid JSON (" + e.what() + ")");
    }
    return doc;
}

// "environment": a generated environment's name (envgen.h), or a file beside the scene (its path
// then).
std::string readEnvironment(const Reader& r, const json& j) {
    if (!j.is_string())
        r.fail("environment",
               "expected a generated environment's name (\"sky\", \"sky-soft\", "
               "\"white\", ...) or a file path");
    std::string env = j.get<std::string>();
    if (!isGeneratedEnvironment(env)) {
        fs::path p = r.file.parent_path() / env;
        if (!fs::exists(p)) r.fail("environment", p.string() + " does not exist");
        env = p.string();
    }
    return env;
}

// "camera": what it gives of position, target and field of view over `camera`'s defaults,
// checked together.
void readCamera(const Reader& r, const json& c, Camera& camera) {
    r.onlyKnown(c, "camera", {"position", "target", "fov"});
    if (c.contains("position")) camera.position = r.vec3(c["position"], "camera.position");
    if (c.contains("target")) camera.target = r.vec3(c["target"], "camera.target");
    if (c.contains("fov")) camera.fovY = r.number(c["fov"], "camera.fov");
    if (camera.fovY <= 1 || camera.fovY >= 179)
        r.fail("camera.fov", "expected degrees in (1, 179)");
    if (glm::length(camera.position - camera.target) < 1e-9)
        r.fail("camera.target", "equals the camera position");
}

// "lights": at least one point light, at most as many as the shaders hold.
void readLights(const Reader& r, const json& doc, Scene& scene) {
    if (!doc.contains("lights") || !doc["lights"].is_array() || doc["lights"].empty())
        r.fail("lights", "expected a non-empty array of point lights");
    if (doc["lights"].size() > kMaxSceneLights)
        r.fail("lights", std::to_string(doc["lights"].size()) +
                             " lights, more than the shaders hold (at most " +
                             std::to_string(kMaxSceneLights) + ")");
    for (size_t i = 0; i < doc["lights"].size(); ++i) {
        std::string f = "lights[" + std::to_string(i) + "]";
        const json& l = doc["lights"][i];
        if (!l.is_object()) r.fail(f, "expected an object");
        r.onlyKnown(l, f, {"position", "color"});
        if (!l.contains("position")) r.fail(f + ".position", "missing");
        PointLightDesc light;
        light.position = r.vec3(l["position"], f + ".position");
        if (l.contains("color")) light.color = r.vec3(l["color"], f + ".color");
        for (int c = 0; c < 3; ++c)
            if (light.color[c] < 0) r.fail(f + ".color", "components must be >= 0");
        scene.lights.push_back(light);
    }
}

// "materials": the named materials, added to the scene; returns their names in that order.
std::vector<std::string> readNamedMaterials(const Reader& r, const json& doc, Scene& scene) {
    std::vector<std::string> names;
    if (doc.contains("materials")) {
        if (!doc["materials"].is_object())
            r.fail("materials", "expected an object of name: material");
        for (const auto& [name, m] : doc["materials"].items()) {
            scene.materials.push_back(r.material(m, "materials." + name, name));
            names.push_back(name);
        }
    }
    return names;
}

// objects[i] (`f`): a sphere or a glTF model (added to the scene), placed, with a named
// material, its own (added to the scene) or, for a model, the model's.
ObjectDesc readObject(const Reader& r, const json& o, const std::string& f,
                      const std::vector<std::string>& names, Scene& scene) {
    if (!o.is_object()) r.fail(f, "expected an object");
    r.onlyKnown(o, f, {"primitive", "model", "translate", "scale", "material"});
    ObjectDesc obj;
    if (o.contains("primitive")) {
        if (!o["primitive"].is_string() || o["primitive"] != "sphere")
            r.fail(f + ".primitive", "expected \"sphere\" (or give \"model\": a .glb/.gltf)");
    }
    if (o.contains("model")) {
        if (o.contains("primitive")) r.fail(f, "give either \"primitive\" or \"model\"");
        if (!o["model"].is_string()) r.fail(f + ".model", "expected a .glb or .gltf path");
        fs::path modelFile = r.file.parent_path() / o["model"].get<std::string>();
        std::shared_ptr<const ModelData> model;
        try {
            model = std::make_shared<const ModelData>(loadGltf(modelFile));
        } catch (const Error& e) {
            r.fail(f + ".model", e.what());
        }
        obj.model = addModel(scene, model);
    }
    if (o.contains("translate")) obj.translate = r.vec3(o["translate"], f + ".translate");
    if (o.contains("scale")) obj.scale = r.number(o["scale"], f + ".scale");
    if (obj.scale <= 0) r.fail(f + ".scale", "must be > 0");
    if (!o.contains("material")) {
        if (obj.model >= 0) {  // the model's own materials
            obj.material = -1;
            return obj;
        }
        r.fail(f + ".material", "missing");
    }
    const json& m = o["material"];
    if (m.is_string()) {
        auto it = std::find(names.begin(), names.end(), m.get<std::string>());
        if (it == names.end()) r.fail(f + ".material", "no material named " + m.dump());
        obj.material = int(it - names.begin());
    } else {
        scene.materials.push_back(r.material(m, f + ".material", f));
        obj.material = int(scene.materials.size() - 1);
    }
    return obj;
}

// "objects": at least one, at most as many as pbrlab draws, each added to the scene.
void readObjects(const Reader& r, const json& doc, const std::vector<std::string>& names,
                 Scene& scene) {
    if (!doc.contains("objects") || !doc["objects"].is_array() || doc["objects"].empty())
        r.fail("objects", "expected a non-empty array");
    if (doc["objects"].size() > kMaxDrawnMeshes)
        r.fail("objects", std::to_string(doc["objects"].size()) +
                              " objects, more than pbrlab draws (at most " +
                              std::to_string(kMaxDrawnMeshes) + ")");
    for (size_t i = 0; i < doc["objects"].size(); ++i) {
        const std::string f = "objects[" + std::to_string(i) + "]";
        scene.objects.push_back(readObject(r, doc["objects"][i], f, names, scene));
    }
}

}  // namespace

Scene loadScene(const fs::path& file) {
    Reader r{file};
    json doc = readSceneJson(file);
    if (!doc.is_object()) r.fail("(top level)", "expected an object");
    r.onlyKnown(doc, "",
                {"description", "camera", "lights", "materials", "objects", "environment"});
    Scene scene;
    scene.file = file;
    if (doc.contains("environment")) scene.environment = readEnvironment(r, doc["environment"]);
    if (doc.contains("camera")) readCamera(r, doc["camera"], scene.camera);
    readLights(r, doc, scene);
    const std::vector<std::string> names = readNamedMaterials(r, doc, scene);
    readObjects(r, doc, names, scene);
    // A model's primitives are draws too: each object places all of them.
    if (const size_t draws = drawCount(scene); draws > kMaxDrawnMeshes)
        r.fail("objects", "they draw " + std::to_string(draws) +
                              " meshes (a sphere is one, a model one per primitive), more than "
                              "pbrlab draws (at most " +
                              std::to_string(kMaxDrawnMeshes) + ")");
    return scene;
}

int addModel(Scene& scene, std::shared_ptr<const ModelData> model) {
    SceneModel m{model, int(scene.materials.size())};
    for (const ModelMaterial& mm : model->materials)
        scene.materials.push_back(fromModel(mm, *model));
    // glTF's default material: white, fully metallic, fully rough.
    ModelMaterial fallback;
    fallback.name = "(glTF default)";
    scene.materials.push_back(fromModel(fallback, *model));
    scene.models.push_back(m);
    return int(scene.models.size() - 1);
}

std::vector<DrawItem> drawItems(const Scene& scene) {
    std::vector<DrawItem> items;
    for (const ObjectDesc& o : scene.objects) {
        const glm::dmat4 placed =
            glm::scale(glm::translate(glm::dmat4(1), o.translate), glm::dvec3(o.scale));
        if (o.model < 0) {
            items.push_back({nullptr, placed, o.material});
            continue;
        }
        const SceneModel& model = scene.models.at(size_t(o.model));
        const int fallback = model.materialOffset + int(model.data->materials.size());
        for (const ModelPrimitive& p : model.data->primitives) {
            int material = o.material >= 0   ? o.material
                           : p.material >= 0 ? model.materialOffset + p.material
                                             : fallback;
            items.push_back({&p.mesh, placed * p.transform, material});
        }
    }
    return items;
}

Scene sceneForModel(const Scene& base, const fs::path& modelFile) {
    auto model = std::make_shared<const ModelData>(loadGltf(modelFile));
    if (model->primitives.empty()) throw Error(modelFile.string() + ": the model has no meshes");
    Scene scene = base;
    scene.objects.clear();
    scene.models.clear();
    scene.materials.clear();
    ObjectDesc object;
    object.model = addModel(scene, model);
    object.material = -1;
    scene.objects.push_back(object);

    const glm::dvec3 lo = model->boundsMin(), hi = model->boundsMax();
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const double radius = std::max(0.5 * glm::length(hi - lo), 1e-6);
    // base frames a unit sphere at its target: keep its view, scale distances by the radius.
    // Keep base's view direction; back off until every corner of the bounds is inside the
    // field of view (a square image assumed), with a 5% margin.
    const glm::dvec3 forward = glm::normalize(base.camera.target - base.camera.position);
    glm::dvec3 right = glm::cross(forward, glm::dvec3(0, 1, 0));
    if (glm::length(right) < 1e-9) right = glm::dvec3(1, 0, 0);  // looking straight down/up
    right = glm::normalize(right);
    const glm::dvec3 up = glm::cross(right, forward);
    const double tanHalf = std::tan(glm::radians(0.5 * base.camera.fovY));
    double distance = 0;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p = glm::dvec3(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y,
                                        corner & 4 ? hi.z : lo.z) -
                             centre;
        const double across = std::max(std::abs(glm::dot(p, right)), std::abs(glm::dot(p, up)));
        distance = std::max(distance, across / tanHalf - glm::dot(p, forward));
    }
    scene.camera.target = centre;
    scene.camera.position = centre - forward * std::max(distance * 1.05, 2 * radius / 60);
    for (PointLightDesc& light : scene.lights) {
        light.position = centre + (light.position - base.camera.target) * radius;
        light.color *= radius * radius;
    }
    scene.file = modelFile;
    return scene;
}

}  // namespace pbrlab
