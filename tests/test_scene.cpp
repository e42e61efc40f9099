#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "assets/scene.h"
#include "test_support.h"
#include "util/error.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {
std::string loadError(const std::string& json) {
    test::TempDir dir;
    auto file = dir.write("scene.json", json);
    try {
        loadScene(file);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}
const char* kLight = R"("lights": [{"position": [0, 0, 5], "color": [1, 1, 1]}])";
}  // namespace

TEST(Scene, LoadsTheProjectScenes) {
    int count = 0;
    for (const auto& entry :
         fs::directory_iterator(fs::path(PBRLAB_SOURCE_DIR) / "assets/scenes")) {
        Scene s = loadScene(entry.path());
        EXPECT_FALSE(s.objects.empty()) << entry.path();
        EXPECT_FALSE(s.lights.empty()) << entry.path();
        EXPECT_FALSE(drawItems(s).empty()) << entry.path();
        ++count;
    }
    EXPECT_GE(count, 4);  // sphere, sphere-untextured, sphere-grid, models
    // models.json: two glTF objects (one primitive each) and a built-in sphere.
    Scene models = loadScene(fs::path(PBRLAB_SOURCE_DIR) / "assets/scenes/models.json");
    EXPECT_EQ(models.models.size(), 2u);
    EXPECT_EQ(drawItems(models).size(), 3u);
}

TEST(Scene, ErrorsNameTheFileAndTheField) {
    std::string m =
        loadError(std::string("{") + kLight + R"(, "objects": [{"material": {"roughness": 2}}]})");
    EXPECT_NE(m.find("scene.json: field 'objects[0].material.roughness'"), std::string::npos) << m;
    m = loadError(std::string("{") + kLight + R"(, "objects": [{"material": "steel"}]})");
    EXPECT_NE(m.find("'objects[0].material': no material named \"steel\""), std::string::npos) << m;
    m = loadError(R"({"lights": [], "objects": []})");
    EXPECT_NE(m.find("'lights'"), std::string::npos) << m;
    m = loadError(std::string("{") + kLight + R"(, "objects": [{"material": {}, "colour": 1}]})");
    EXPECT_NE(m.find("'objects[0].colour': unknown field"), std::string::npos) << m;
    m = loadError(std::string("{") + kLight +
                  R"(, "objects": [{"material": {"albedoMap": "missing.png"}}]})");
    EXPECT_NE(m.find("missing.png does not exist"), std::string::npos) << m;
    m = loadError("{ not json");
    EXPECT_NE(m.find("scene.json: not valid JSON"), std::string::npos) << m;
    EXPECT_NE(loadError("").find("not valid JSON"), std::string::npos);
}

TEST(Scene, PlacesGltfModelsWithTheirOwnOrAGivenMaterial) {
    test::TempDir dir;
    const std::string model = std::string(PBRLAB_SOURCE_DIR) + "/assets/models/textured-sphere.glb";
    auto file = dir.write("scene.json", std::string("{") + kLight + R"(,
        "materials": {"gold": {"albedo": [1, 0.8, 0.3], "metallic": 1, "roughness": 0.3}},
        "objects": [{"model": ")" + model + R"(", "translate": [2, 0, 0]},
                    {"model": ")" + model + R"(", "material": "gold", "scale": 0.5},
                    {"material": "gold"}]})");
    Scene s = loadScene(file);
    ASSERT_EQ(s.models.size(), 2u);
    ASSERT_EQ(s.objects.size(), 3u);
    std::vector<DrawItem> items = drawItems(s);
    ASSERT_EQ(items.size(), 3u);  // one primitive per model, one sphere
    // The first keeps the model's material (maps from the file), the second wears gold.
    const MaterialDesc& own = s.materials.at(size_t(items[0].material));
    EXPECT_FALSE(own.albedoMap.empty());
    EXPECT_FALSE(own.metallicRoughnessMap.empty());
    EXPECT_EQ(own.aoMap.key, own.metallicRoughnessMap.key);  // one image, two maps
    EXPECT_EQ(own.emissive, glm::dvec3(1.0, 0.45, 0.1));
    EXPECT_EQ(s.materials.at(size_t(items[1].material)).name, "gold");
    EXPECT_EQ(items[2].mesh, nullptr);  // the built-in sphere
    EXPECT_EQ(glm::dvec3(items[0].transform[3]), glm::dvec3(2, 0, 0));
    EXPECT_EQ(items[1].transform[0][0], 0.5);
}

TEST(Scene, MapsMultiplyTheirFactorsAndAloneMeanFactorOne) {
    test::TempDir dir;
    const std::string tex = std::string(PBRLAB_SOURCE_DIR) + "/assets/textures/metal-plates/";
    auto file = dir.write("scene.json", std::string("{") + kLight + R"(, "objects": [
        {"material": {"roughnessMap": ")" + tex +
                                            R"(roughness.png"}},
        {"material": {"roughnessMap": ")" + tex +
                                            R"(roughness.png", "roughness": 0.5,
                      "emissive": [2, 0, 0]}},
        {"material": {"metallic": 0.25}}]})");
    Scene s = loadScene(file);
    EXPECT_EQ(s.materials[0].roughness, 1.0);  // the map alone decides
    EXPECT_EQ(s.materials[1].roughness, 0.5);  // halves the map
    EXPECT_EQ(s.materials[1].emissive, glm::dvec3(2, 0, 0));
    EXPECT_EQ(s.materials[2].metallic, 0.25);
    EXPECT_TRUE(s.materials[2].roughnessMap.empty());
}

TEST(Scene, BadModelsAreErrorsNamingSceneFieldAndModel) {
    test::TempDir dir;
    dir.write("broken.glb", "glTF but not really");
    std::string m =
        loadError(std::string("{") + kLight + R"(, "objects": [{"model": "nowhere.glb"}]})");
    EXPECT_NE(m.find("scene.json: field 'objects[0].model'"), std::string::npos) << m;
    EXPECT_NE(m.find("nowhere.glb"), std::string::npos) << m;
    auto file = dir.write("scene.json",
                          std::string("{") + kLight + R"(, "objects": [{"model": "broken.glb"}]})");
    try {
        loadScene(file);
        FAIL() << "loaded a broken model";
    } catch (const Error& e) {
        m = e.what();
    }
    EXPECT_NE(m.find("'objects[0].model'"), std::string::npos) << m;
    EXPECT_NE(m.find((dir.path / "broken.glb").string()), std::string::npos) << m;
    m = loadError(std::string("{") + kLight +
                  R"(, "objects": [{"primitive": "sphere", "model": "x.glb"}]})");
    EXPECT_NE(m.find("either \"primitive\" or \"model\""), std::string::npos) << m;
}

TEST(Scene, CorruptedSceneFilesGiveErrorsNotCrashes) {
    // Byte flips and cuts of a project scene: each load succeeds or throws pbrlab::Error
    // naming the file, never anything else.
    const fs::path original = fs::path(PBRLAB_SOURCE_DIR) / "assets/scenes/sphere.json";
    std::ifstream in(original, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    test::TempDir dir;
    // The texture paths are relative to the scene: keep them resolvable from the copy.
    fs::create_directories(dir.path / "scenes");
    fs::create_directory_symlink(fs::path(PBRLAB_SOURCE_DIR) / "assets/textures",
                                 dir.path / "textures");
    const fs::path file = dir.path / "scenes/mutated.json";
    std::mt19937 rng(3);
    int errors = 0;
    for (int i = 0; i < 300; ++i) {
        std::string b = bytes;
        if (i % 4 == 0) b.resize(1 + rng() % (b.size() - 1));  // never empty: flips need a byte
        for (int k = 0, n = 1 + int(rng() % 3); k < n; ++k) b[rng() % b.size()] = char(rng());
        std::ofstream(file, std::ios::binary) << b;
        try {
            loadScene(file);
        } catch (const Error& e) {
            ++errors;
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        }
    }
    EXPECT_GT(errors, 0);
}

namespace {
// A scene of `lights` lights and `objects` objects, each `object` (JSON).
std::string sceneJson(size_t lights, size_t objects,
                      const std::string& object = R"({"material": {"albedo": [0.5, 0.5, 0.5]}})") {
    std::string json = R"({"lights": [)";
    for (size_t i = 0; i < lights; ++i)
        json += std::string(i ? ", " : "") + R"({"position": [)" + std::to_string(i % 7) +
                R"(, 4, 5], "color": [1, 1, 1]})";
    json += R"(], "objects": [)";
    for (size_t i = 0; i < objects; ++i) json += (i ? ", " : "") + object;
    return json + "]}";
}
}  // namespace

TEST(Scene, MoreLightsThanTheShadersHoldIsAnErrorSayingTheLimit) {
    const std::string m = loadError(sceneJson(kMaxSceneLights + 1, 1));
    EXPECT_NE(m.find("scene.json: field 'lights': " + std::to_string(kMaxSceneLights + 1) +
                     " lights, more than the shaders hold (at most " +
                     std::to_string(kMaxSceneLights) + ")"),
              std::string::npos)
        << m;
    EXPECT_NE(loadError(sceneJson(100000, 1)).find("100000 lights"), std::string::npos);
    EXPECT_EQ(loadError(sceneJson(kMaxSceneLights, 1)), "");
}

TEST(Scene, MoreDrawsThanTheLimitIsAnErrorSayingTheLimit) {
    const std::string limit = "(at most " + std::to_string(kMaxDrawnMeshes) + ")";
    std::string m = loadError(sceneJson(1, kMaxDrawnMeshes + 1));
    EXPECT_NE(m.find("scene.json: field 'objects': " + std::to_string(kMaxDrawnMeshes + 1) +
                     " objects, more than pbrlab draws " + limit),
              std::string::npos)
        << m;
    EXPECT_EQ(loadError(sceneJson(1, kMaxDrawnMeshes)), "");
    // Each model object draws every primitive of its model: here 1000 (a triangle, 1000 nodes).
    test::TempDir dir;
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::ofstream(dir.path / "tri.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(positions), sizeof positions);
    std::string nodes, roots;
    for (int i = 0; i < 1000; ++i) {
        nodes += std::string(i ? ", " : "") + R"({"mesh": 0})";
        roots += (i ? ", " : "") + std::to_string(i);
    }
    dir.write("many.gltf", R"({"asset": {"version": "2.0"},
  "buffers": [{"uri": "tri.bin", "byteLength": 36}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "nodes": [)" + nodes + R"(], "scenes": [{"nodes": [)" +
                               roots + R"(]}], "scene": 0})");
    const size_t models = kMaxDrawnMeshes / 1000 + 1;
    const fs::path file =
        dir.write("scene.json", sceneJson(1, models, R"({"model": "many.gltf"})"));
    try {
        loadScene(file);
        FAIL() << "loaded a scene drawing " << models * 1000 << " meshes";
    } catch (const Error& e) {
        m = e.what();
    }
    EXPECT_NE(m.find(file.string() + ": field 'objects': they draw " +
                     std::to_string(models * 1000) + " meshes"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find(limit), std::string::npos) << m;
    dir.write("scene.json", sceneJson(1, kMaxDrawnMeshes / 1000, R"({"model": "many.gltf"})"));
    EXPECT_EQ(drawItems(loadScene(file)).size(), kMaxDrawnMeshes / 1000 * 1000);
}
