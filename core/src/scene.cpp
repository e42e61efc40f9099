#include "pbrlab/scene.h"

#include <fstream>
#include <nlohmann/json.hpp>

#include "pbrlab/error.h"

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
    fs::path texture(const json& j, const std::string& field) const {
        if (!j.is_string()) fail(field, "expected a file path");
        fs::path p = file.parent_path() / j.get<std::string>();
        if (!fs::exists(p)) fail(field, "texture " + p.string() + " does not exist");
        return p;
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
                  {"albedo", "metallic", "roughness", "ao", "albedoMap", "roughnessMap",
                   "metallicMap", "aoMap", "normalMap"});
        MaterialDesc m;
        m.name = name;
        if (j.contains("albedo")) m.albedo = vec3(j["albedo"], field + ".albedo");
        if (j.contains("metallic")) m.metallic = unit(j["metallic"], field + ".metallic");
        if (j.contains("roughness")) m.roughness = unit(j["roughness"], field + ".roughness");
        if (j.contains("ao")) m.ao = unit(j["ao"], field + ".ao");
        for (int i = 0; i < 3; ++i)
            if (m.albedo[i] < 0 || m.albedo[i] > 1) fail(field + ".albedo", "components in [0, 1]");
        std::pair<const char*, fs::path*> maps[] = {{"albedoMap", &m.albedoMap},
                                                    {"roughnessMap", &m.roughnessMap},
                                                    {"metallicMap", &m.metallicMap},
                                                    {"aoMap", &m.aoMap},
                                                    {"normalMap", &m.normalMap}};
        for (auto& [key, path] : maps)
            if (j.contains(key)) *path = texture(j[key], field + "." + key);
        return m;
    }
};

}  // namespace

Scene loadScene(const fs::path& file) {
    Reader r{file};
    std::ifstream in(file);
    if (!in) throw Error(file.string() + ": cannot open scene file");
    json doc;
    try {
        doc = json::parse(in);
    } catch (const json::parse_error& e) {
        throw Error(file.string() + ": not valid JSON (" + e.what() + ")");
    }
    if (!doc.is_object()) r.fail("(top level)", "expected an object");
    r.onlyKnown(doc, "",
                {"description", "camera", "lights", "materials", "objects", "environment"});
    Scene scene;
    scene.file = file;

    if (doc.contains("environment")) {
        if (!doc["environment"].is_string())
            r.fail("environment", "expected \"sky\" or a file path");
        std::string env = doc["environment"].get<std::string>();
        if (env != "sky") {
            fs::path p = file.parent_path() / env;
            if (!fs::exists(p)) r.fail("environment", p.string() + " does not exist");
            env = p.string();
        }
        scene.environment = env;
    }

    if (doc.contains("camera")) {
        const json& c = doc["camera"];
        r.onlyKnown(c, "camera", {"position", "target", "fov"});
        if (c.contains("position"))
            scene.camera.position = r.vec3(c["position"], "camera.position");
        if (c.contains("target")) scene.camera.target = r.vec3(c["target"], "camera.target");
        if (c.contains("fov")) scene.camera.fovY = r.number(c["fov"], "camera.fov");
        if (scene.camera.fovY <= 1 || scene.camera.fovY >= 179)
            r.fail("camera.fov", "expected degrees in (1, 179)");
        if (glm::length(scene.camera.position - scene.camera.target) < 1e-9)
            r.fail("camera.target", "equals the camera position");
    }

    if (!doc.contains("lights") || !doc["lights"].is_array() || doc["lights"].empty())
        r.fail("lights", "expected a non-empty array of point lights");
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

    std::vector<std::string> names;
    if (doc.contains("materials")) {
        if (!doc["materials"].is_object())
            r.fail("materials", "expected an object of name: material");
        for (const auto& [name, m] : doc["materials"].items()) {
            scene.materials.push_back(r.material(m, "materials." + name, name));
            names.push_back(name);
        }
    }

    if (!doc.contains("objects") || !doc["objects"].is_array() || doc["objects"].empty())
        r.fail("objects", "expected a non-empty array");
    for (size_t i = 0; i < doc["objects"].size(); ++i) {
        std::string f = "objects[" + std::to_string(i) + "]";
        const json& o = doc["objects"][i];
        if (!o.is_object()) r.fail(f, "expected an object");
        r.onlyKnown(o, f, {"primitive", "translate", "scale", "material"});
        ObjectDesc obj;
        if (o.contains("primitive")) {
            if (!o["primitive"].is_string() || o["primitive"] != "sphere")
                r.fail(f + ".primitive", "expected \"sphere\"");
        }
        if (o.contains("translate")) obj.translate = r.vec3(o["translate"], f + ".translate");
        if (o.contains("scale")) obj.scale = r.number(o["scale"], f + ".scale");
        if (obj.scale <= 0) r.fail(f + ".scale", "must be > 0");
        if (!o.contains("material")) r.fail(f + ".material", "missing");
        const json& m = o["material"];
        if (m.is_string()) {
            auto it = std::find(names.begin(), names.end(), m.get<std::string>());
            if (it == names.end()) r.fail(f + ".material", "no material named " + m.dump());
            obj.material = int(it - names.begin());
        } else {
            scene.materials.push_back(r.material(m, f + ".material", f));
            obj.material = int(scene.materials.size() - 1);
        }
        scene.objects.push_back(obj);
    }
    return scene;
}

}  // namespace pbrlab
