// glTF models end to end: the project's own assets (counts, regeneration), images read only
// when sampled, the shader permutations a scene compiles, framing, and emission checked
// against the CPU reference.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <set>

#include "assets/gltf.h"
#include "gl/context.h"
#include "render/evaluate.h"
#include "render/renderer.h"
#include "test_support.h"
#include "util/error.h"
#include "util/log.h"

using namespace pbrlab;
namespace fs = std::filesystem;

namespace {

const fs::path kModels = fs::path(PBRLAB_SOURCE_DIR) / "assets/models";

struct Headless {
    std::unique_ptr<GlContext> context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ModuleRegistry modules{PBRLAB_MODULE_DIR};
    LabRenderer renderer{paths};

    // Renders `id` on the scene (32x32: only what compiles and loads matters here) and returns
    // the G-buffer permutations that render used (each compiled once, then cached).
    std::set<std::string> gbufferDefines(const std::string& id, const Scene& scene) {
        const LoadedModule& m = modules.find(id);
        renderer.renderScene(m, ParamValues(m.desc->params), scene, {}, 32, 32, false);
        std::set<std::string> used;
        for (const DrawItem& item : drawItems(scene))
            used.insert(definesText(
                renderer.gbufferRecipe(scene.materials.at(size_t(item.material)), m.desc->needs)
                    .defines));
        // Whatever was used was compiled, under exactly these defines.
        std::set<std::string> compiled;
        for (const CompiledProgram& p : renderer.programs().compiled())
            if (p.label == "G-buffer") compiled.insert(p.defines);
        for (const std::string& d : used) EXPECT_EQ(compiled.count(d), 1u) << "{" << d << "}";
        return used;
    }
};

Scene modelScene(const Headless& h, const fs::path& model) {
    return sceneForModel(loadScene(h.paths.scene("sphere")), model);
}

// A 2x2 8-bit RGB PNG of one colour (code values 0..255): filtering cannot change it.
void writeConstantPng(const fs::path& file, glm::dvec3 codes, bool srgb) {
    Image im;
    im.width = im.height = 2;
    im.channels = 3;
    for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) im.pixels.push_back(float(codes[c] / 255));
    writeImage(file, im, FileDepth::Uint8, srgb);
}

// A one-triangle .gltf with an external buffer and the given material JSON and images.
fs::path writeTriangleGltf(const test::TempDir& dir, const std::string& material,
                           const std::string& images, const std::string& textures) {
    const float data[] = {0, 0, 0, 1, 0, 0, 0, 1, 0,  // positions
                          0, 0, 1, 0, 0, 1, 0, 0, 1,  // normals
                          0, 1, 1, 1, 0, 0};          // uvs
    std::ofstream(dir.path / "tri.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(data), sizeof data);
    return dir.write("tri.gltf", R"({"asset": {"version": "2.0"},
  "buffers": [{"uri": "tri.bin", "byteLength": 96}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 72, "byteLength": 24}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]},
                {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
                {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                               "material": 0}]}],
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0,
  "materials": [)" + material + R"(],
  "images": [)" + images + R"(], "textures": [)" +
                                     textures + "]}");
}

}  // namespace

TEST(Models, ShippedAssetsHaveTheExpectedCounts) {
    // A 48 x 24 uv sphere has 49 x 25 vertices (the seam and the poles are duplicated so every
    // vertex has one uv); 96 x 48 has 97 x 49.
    ModelData grid = loadGltf(kModels / "sphere-grid.glb");
    EXPECT_EQ(grid.primitives.size(), 49u);
    EXPECT_EQ(grid.vertexCount(), 49u * 49 * 25);
    EXPECT_EQ(grid.materials.size(), 49u);
    EXPECT_EQ(grid.images.size(), 0u);

    ModelData sphere = loadGltf(kModels / "textured-sphere.glb");
    ASSERT_EQ(sphere.primitives.size(), 1u);
    EXPECT_EQ(sphere.vertexCount(), 97u * 49);
    EXPECT_EQ(sphere.primitives[0].mesh.indices.size(), 96u * 48 * 6);
    EXPECT_TRUE(sphere.primitives[0].generatedTangents);  // written without TANGENT
    ASSERT_EQ(sphere.materials.size(), 1u);
    ASSERT_EQ(sphere.images.size(), 4u);
    const ModelMaterial& m = sphere.materials[0];
    // Occlusion shares the packed metallic-roughness image; the other maps are their own.
    EXPECT_EQ(m.occlusionTexture, m.metallicRoughnessTexture);
    std::set<int> distinct{m.baseColorTexture.image, m.metallicRoughnessTexture.image,
                           m.normalTexture.image, m.emissiveTexture.image};
    EXPECT_EQ(distinct.size(), 4u);
    EXPECT_EQ(distinct.count(-1), 0u);
    EXPECT_EQ(m.emissiveFactor, glm::dvec3(1.0, 0.45, 0.1));
    for (const TextureSource& image : sphere.images) {
        EXPECT_TRUE(image.encoded) << image.key;  // embedded, kept encoded
        Image decoded = readTexture(image);
        EXPECT_EQ(decoded.width, 128) << image.key;
        EXPECT_EQ(decoded.height, 128) << image.key;
    }
}

TEST(Models, ShippedAssetsAreWhatTheGeneratorMakes) {
    // assets/models is `pbrlab models` output, committed so a fresh clone needs no generation
    // step. Regenerating gives the same model: vertices to float rounding (another libm may
    // round a sin() differently), the same materials, image pixels to one 8-bit code value.
    test::TempDir dir;
    writeSphereGridGlb(dir.path / "sphere-grid.glb");
    writeTexturedSphereGlb(dir.path / "textured-sphere.glb");
    for (const char* name : {"sphere-grid.glb", "textured-sphere.glb"}) {
        ModelData fresh = loadGltf(dir.path / name), shipped = loadGltf(kModels / name);
        ASSERT_EQ(fresh.primitives.size(), shipped.primitives.size()) << name;
        for (size_t p = 0; p < fresh.primitives.size(); ++p) {
            const MeshData &a = fresh.primitives[p].mesh, &b = shipped.primitives[p].mesh;
            ASSERT_EQ(a.vertices.size(), b.vertices.size()) << name;
            EXPECT_EQ(a.indices, b.indices) << name;
            for (size_t i = 0; i < a.vertices.size(); ++i) {
                EXPECT_LE(glm::length(a.vertices[i].position - b.vertices[i].position), 1e-6f);
                EXPECT_LE(glm::length(a.vertices[i].uv - b.vertices[i].uv), 1e-6f);
            }
            EXPECT_EQ(fresh.primitives[p].transform, shipped.primitives[p].transform) << name;
        }
        ASSERT_EQ(fresh.materials.size(), shipped.materials.size()) << name;
        for (size_t i = 0; i < fresh.materials.size(); ++i) {
            EXPECT_EQ(fresh.materials[i].baseColorFactor, shipped.materials[i].baseColorFactor);
            EXPECT_EQ(fresh.materials[i].metallicFactor, shipped.materials[i].metallicFactor);
            EXPECT_EQ(fresh.materials[i].roughnessFactor, shipped.materials[i].roughnessFactor);
        }
        ASSERT_EQ(fresh.images.size(), shipped.images.size()) << name;
        for (size_t i = 0; i < fresh.images.size(); ++i) {
            Image a = readTexture(fresh.images[i]), b = readTexture(shipped.images[i]);
            ASSERT_EQ(a.pixels.size(), b.pixels.size());
            for (size_t k = 0; k < a.pixels.size(); ++k)
                ASSERT_LE(std::abs(a.pixels[k] - b.pixels[k]), 1.01f / 255) << name << " " << i;
        }
    }
}

TEST(Models, ImagesAreNotDecodedUntilSampled) {
    test::TempDir dir;
    // Not a PNG at all: loading the model must not notice, decoding must name the file.
    dir.write("albedo.png", "this is not an image");
    fs::path file = writeTriangleGltf(dir, R"({"pbrMetallicRoughness": {"baseColorTexture":
                                              {"index": 0}}})",
                                      R"({"uri": "albedo.png"})", R"({"source": 0})");
    ModelData model = loadGltf(file);
    ASSERT_EQ(model.images.size(), 1u);
    EXPECT_FALSE(model.images[0].encoded);  // external: remembered by path, not held
    EXPECT_EQ(model.images[0].file, dir.path / "albedo.png");
    try {
        readTexture(model.images[0]);
        FAIL() << "decoded a text file";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("albedo.png"), std::string::npos) << e.what();
    }

    // The renderer: a module that does not read the base colour never touches the image.
    Headless h;
    resetCounters();
    Scene scene = modelScene(h, file);
    EXPECT_EQ(h.gbufferDefines("ndotl", scene), std::set<std::string>{""});
    EXPECT_EQ(eventCount(Counter::TextureLoads), 0);
    try {
        h.gbufferDefines("albedo", scene);
        FAIL() << "rendered with an undecodable base colour";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("albedo.png"), std::string::npos) << e.what();
    }
}

TEST(Models, EmissiveStrengthAppliesAndUnsupportedExtensionsAreNamed) {
    test::TempDir dir;
    fs::path file = writeTriangleGltf(dir, R"({"emissiveFactor": [1, 0.5, 0],
                 "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 4}}})",
                                      "", "");
    // The writer has no extensionsUsed; add them to the JSON.
    std::ifstream in(file);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    text.insert(1, R"("extensionsUsed": ["KHR_materials_emissive_strength",
                                         "KHR_texture_transform"], )");
    std::ofstream(file) << text;
    ModelData model = loadGltf(file);
    ASSERT_EQ(model.materials.size(), 1u);
    EXPECT_EQ(model.materials[0].emissiveFactor, glm::dvec3(4, 2, 0));
    ASSERT_EQ(model.warnings.size(), 1u);
    EXPECT_NE(model.warnings[0].find("KHR_texture_transform"), std::string::npos);
}

namespace {

// A .gltf of three primitives sharing one buffer: a unit quad as a triangle strip with uvs as
// normalized unsigned shorts, a four-triangle fan, and the quad's outline as lines; none
// has normals. `meshes` and `accessor0Extra` let a test break it.
fs::path writeShapesGltf(const test::TempDir& dir, const std::string& meshes,
                         const std::string& accessor0Extra = "") {
    std::vector<unsigned char> bin(124);
    const float quad[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    const std::uint16_t uv[] = {0, 65535, 65535, 65535, 0, 0, 65535, 0};
    const float fan[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
    std::memcpy(bin.data(), quad, 48);
    std::memcpy(bin.data() + 48, uv, 16);
    std::memcpy(bin.data() + 64, fan, 60);
    std::ofstream(dir.path / "shapes.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
    writeConstantPng(dir.path / "base.png", {255, 255, 255}, true);
    return dir.write("shapes.gltf", R"({"asset": {"version": "2.0"},
  "buffers": [{"uri": "shapes.bin", "byteLength": 124}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                  {"buffer": 0, "byteOffset": 48, "byteLength": 16},
                  {"buffer": 0, "byteOffset": 64, "byteLength": 60}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0])" +
                                        accessor0Extra + R"(},
                {"bufferView": 1, "componentType": 5123, "normalized": true, "count": 4,
                 "type": "VEC2"},
                {"bufferView": 2, "componentType": 5126, "count": 5, "type": "VEC3",
                 "min": [-1, -1, 0], "max": [1, 1, 0]}],
  "meshes": [{"primitives": [)" + meshes +
                                        R"(]}],
  "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0,
  "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
  "samplers": [{"wrapS": 33071, "wrapT": 33648}],
  "images": [{"uri": "base.png"}], "textures": [{"source": 0, "sampler": 0}]})");
}

const char* kStrip =
    R"({"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "mode": 5, "material": 0})";
const char* kFan = R"({"attributes": {"POSITION": 2}, "mode": 6})";
const char* kLines = R"({"attributes": {"POSITION": 0}, "mode": 1})";

}  // namespace

TEST(Models, StripsFansFlatNormalsIntegerUvsAndSamplersAreRead) {
    test::TempDir dir;
    ModelData model =
        loadGltf(writeShapesGltf(dir, std::string(kStrip) + ", " + kFan + ", " + kLines));
    ASSERT_EQ(model.primitives.size(), 2u);  // the lines are left out...
    ASSERT_EQ(model.warnings.size(), 1u);    // ...and said so
    EXPECT_NE(model.warnings[0].find("1 point or line primitives"), std::string::npos);
    // Strip of 4: two triangles, flat: one vertex per corner, all facing +z (the strip's
    // odd triangles are flipped back to counter-clockwise).
    const ModelPrimitive& strip = model.primitives[0];
    EXPECT_TRUE(strip.generatedNormals);
    EXPECT_EQ(strip.mesh.indices.size(), 6u);
    EXPECT_EQ(strip.mesh.vertices.size(), 6u);
    for (const Vertex& v : strip.mesh.vertices) {
        EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
        // uv from normalized shorts: 0 or 65535 / 65535 = exactly 0 or 1, v = 1 - y here.
        EXPECT_EQ(v.uv, glm::vec2(v.position.x, 1 - v.position.y));
    }
    // Fan of 5: three triangles around vertex 0, also facing +z.
    const ModelPrimitive& fan = model.primitives[1];
    EXPECT_EQ(fan.mesh.indices.size(), 9u);
    for (const Vertex& v : fan.mesh.vertices) EXPECT_EQ(v.normal, glm::vec3(0, 0, 1));
    EXPECT_EQ(fan.material, -1);  // glTF's default material
    // The sampler's wrap modes reach the map.
    const ModelMaterial::Map& base = model.materials.at(0).baseColorTexture;
    EXPECT_EQ(base.wrapU, TextureSource::Wrap::Clamp);
    EXPECT_EQ(base.wrapV, TextureSource::Wrap::Mirror);
}

TEST(Models, UnreadableShapesAreErrors) {
    test::TempDir dir;
    auto error = [&](const std::string& meshes, const std::string& extra = "") {
        try {
            loadGltf(writeShapesGltf(dir, meshes, extra));
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(error(kLines).find("no triangles to draw"), std::string::npos);
    const std::string sparse =
        R"(, "sparse": {"count": 1, "indices": {"bufferView": 1, "componentType": 5123},
                        "values": {"bufferView": 0}})";
    EXPECT_NE(error(kStrip, sparse).find("POSITION: sparse accessors are not supported"),
              std::string::npos)
        << error(kStrip, sparse);
}

TEST(Models, MissingImageFileIsAnErrorNamingIt) {
    test::TempDir dir;
    fs::path file = writeTriangleGltf(dir, R"({"normalTexture": {"index": 0}})",
                                      R"({"uri": "gone%20away.png"})", R"({"source": 0})");
    try {
        loadGltf(file);
        FAIL() << "loaded a model whose image is missing";
    } catch (const Error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find(file.string()), std::string::npos) << m;
        EXPECT_NE(m.find("gone%20away.png"), std::string::npos) << m;
    }
}

TEST(Models, SceneWithoutTexturesCompilesNoTextureSamplingAndLoadsNoImage) {
    Headless h;
    resetCounters();
    Scene scene = loadScene(h.paths.scene("sphere-untextured"));
    for (const auto& m : h.modules.modules()) {
        if (m.desc->needs & NeedsEnvironment) continue;  // precompute has its own tests
        EXPECT_EQ(h.gbufferDefines(m.desc->id, scene), std::set<std::string>{""}) << m.desc->id;
    }
    int gbuffers = 0;
    for (const CompiledProgram& p : h.renderer.programs().compiled()) {
        EXPECT_EQ(p.defines.find("_MAP"), std::string::npos) << p.label << " {" << p.defines << "}";
        gbuffers += p.label == "G-buffer";
    }
    EXPECT_EQ(gbuffers, 1);  // one permutation serves every direct-lab module
    EXPECT_EQ(eventCount(Counter::TextureLoads), 0);
    EXPECT_EQ(eventCount(Counter::PrecomputePasses), 0);
}

TEST(Models, TexturedModelCompilesExactlyTheMapsEachModuleReads) {
    Headless h;
    resetCounters();
    Scene scene = modelScene(h, kModels / "textured-sphere.glb");
    EXPECT_EQ(h.gbufferDefines("ndotl", scene), std::set<std::string>{""});
    EXPECT_EQ(eventCount(Counter::TextureLoads), 0);
    EXPECT_EQ(h.gbufferDefines("albedo", scene), std::set<std::string>{"HAS_ALBEDO_MAP=1"});
    EXPECT_EQ(eventCount(Counter::TextureLoads), 1);
    EXPECT_EQ(h.gbufferDefines("ndf", scene),
              std::set<std::string>{"HAS_METALLIC_ROUGHNESS_MAP=1"});
    EXPECT_EQ(h.gbufferDefines("normalmap", scene), std::set<std::string>{"HAS_NORMAL_MAP=1"});
    EXPECT_EQ(eventCount(Counter::TextureLoads), 3);
    // The final picture reads base colour, metallic-roughness, occlusion (the same image as
    // metallic-roughness: not loaded twice) and emission.
    EXPECT_EQ(h.gbufferDefines("reflectance", scene),
              std::set<std::string>{"HAS_ALBEDO_MAP=1 HAS_AO_MAP=1 HAS_EMISSIVE_MAP=1 "
                                    "HAS_METALLIC_ROUGHNESS_MAP=1"});
    EXPECT_EQ(eventCount(Counter::TextureLoads), 4);
    // Rendering again compiles and loads nothing.
    const size_t compiled = h.renderer.programs().compiled().size();
    h.gbufferDefines("reflectance", scene);
    EXPECT_EQ(h.renderer.programs().compiled().size(), compiled);
    EXPECT_EQ(eventCount(Counter::TextureLoads), 4);
    EXPECT_EQ(eventCount(Counter::PrecomputePasses), 0);
}

TEST(Models, GltfWithSomeMapsCompilesExactlyThoseDefines) {
    test::TempDir dir;
    writeConstantPng(dir.path / "base.png", {128, 128, 128}, true);
    writeConstantPng(dir.path / "normal.png", {128, 128, 255}, false);
    fs::path file = writeTriangleGltf(
        dir, R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}},
                 "normalTexture": {"index": 1}})",
        R"({"uri": "base.png"}, {"uri": "normal.png"})", R"({"source": 0}, {"source": 1})");
    Headless h;
    Scene scene = modelScene(h, file);
    std::set<std::string> all;
    for (const auto& m : h.modules.modules()) {
        if (m.desc->needs & NeedsEnvironment) continue;
        for (const std::string& d : h.gbufferDefines(m.desc->id, scene)) all.insert(d);
    }
    EXPECT_EQ(all, (std::set<std::string>{"", "HAS_ALBEDO_MAP=1", "HAS_NORMAL_MAP=1"}));
}

TEST(Models, GltfMaterialsMeanWhatTheSpecificationSays) {
    // One triangle, every map a constant 8-bit colour (filtering cannot change a constant),
    // each with a factor: what reaches the G-buffer must be glTF's factor x map, from the
    // right channels, with the right colour space.
    test::TempDir dir;
    writeConstantPng(dir.path / "base.png", {128, 64, 255}, true);
    writeConstantPng(dir.path / "orm.png", {51, 64, 191},
                     false);  // R = occlusion, G = roughness, B = metallic
    writeConstantPng(dir.path / "normal.png", {255, 128, 200}, false);
    writeConstantPng(dir.path / "emissive.png", {255, 255, 255}, true);
    fs::path file =
        writeTriangleGltf(dir, R"({"pbrMetallicRoughness": {"baseColorFactor": [0.5, 1, 0.25, 1],
                   "baseColorTexture": {"index": 0}, "metallicFactor": 0.5,
                   "roughnessFactor": 0.8, "metallicRoughnessTexture": {"index": 1}},
                 "occlusionTexture": {"index": 1, "strength": 0.5},
                 "normalTexture": {"index": 2, "scale": 0.5},
                 "emissiveFactor": [0.2, 0.4, 0.6], "emissiveTexture": {"index": 3}})",
                          R"({"uri": "base.png"}, {"uri": "orm.png"}, {"uri": "normal.png"},
           {"uri": "emissive.png"})",
                          R"({"source": 0}, {"source": 1}, {"source": 2}, {"source": 3})");
    Headless h;
    Scene scene = modelScene(h, file);
    auto covered = [&](const std::string& id) {
        const LoadedModule& m = h.modules.find(id);
        RenderResult r =
            h.renderer.renderScene(m, ParamValues(m.desc->params), scene, {}, 48, 48, true);
        std::vector<Surface> out;
        for (const Surface& s : r.surfaces)
            if (s.covered) out.push_back(s);
        return out;
    };
    auto srgb = [](double code) {
        double c = code / 255;
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    const std::vector<Surface> shaded = covered("reflectance");
    ASSERT_GT(shaded.size(), 50u);
    for (const Surface& s : shaded) {
        EXPECT_NEAR(s.albedo.r, 0.5 * srgb(128), 1e-5);
        EXPECT_NEAR(s.albedo.g, 1.0 * srgb(64), 1e-5);
        EXPECT_NEAR(s.albedo.b, 0.25 * srgb(255), 1e-5);
        EXPECT_NEAR(s.roughness, 0.8 * 64 / 255, 1e-5);       // G
        EXPECT_NEAR(s.metallic, 0.5 * 191 / 255, 1e-5);       // B
        EXPECT_NEAR(s.ao, 1 + 0.5 * (51.0 / 255 - 1), 1e-5);  // R, with strength
        EXPECT_NEAR(s.emissive.r, 0.2, 1e-5);                 // sRGB white decodes to 1
        EXPECT_NEAR(s.emissive.g, 0.4, 1e-5);
        EXPECT_NEAR(s.emissive.b, 0.6, 1e-5);
    }
    for (const Surface& s : covered("normalmap")) {
        // x and y scaled about the middle of the texel range, z as stored.
        EXPECT_NEAR(s.normalTexel.x, (2 * 255.0 / 255 - 1) * 0.5 * 0.5 + 0.5, 1e-5);
        EXPECT_NEAR(s.normalTexel.y, (2 * 128.0 / 255 - 1) * 0.5 * 0.5 + 0.5, 1e-5);
        EXPECT_NEAR(s.normalTexel.z, 200.0 / 255, 1e-5);
    }
}

TEST(Models, ModelIsFramedAndLitLikeTheBaseScene) {
    Scene base = loadScene(fs::path(PBRLAB_SOURCE_DIR) / "assets/scenes/sphere.json");
    ModelData grid = loadGltf(kModels / "sphere-grid.glb");
    Scene scene = sceneForModel(base, kModels / "sphere-grid.glb");
    const glm::dvec3 lo = grid.boundsMin(), hi = grid.boundsMax(), centre = 0.5 * (lo + hi);
    EXPECT_EQ(scene.camera.target, centre);
    // Same view direction, and every corner of the bounds projects inside the image.
    EXPECT_NEAR(glm::dot(glm::normalize(scene.camera.position - scene.camera.target),
                         glm::normalize(base.camera.position - base.camera.target)),
                1.0, 1e-12);
    const glm::dmat4 viewProjection =
        glm::perspective(glm::radians(scene.camera.fovY), 1.0, 0.1, 1000.0) *
        glm::lookAt(scene.camera.position, scene.camera.target, glm::dvec3(0, 1, 0));
    double widest = 0;
    for (int c = 0; c < 8; ++c) {
        glm::dvec4 p = viewProjection *
                       glm::dvec4(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z, 1);
        widest = std::max({widest, std::abs(p.x / p.w), std::abs(p.y / p.w)});
    }
    EXPECT_LT(widest, 1.0);
    EXPECT_GT(widest, 0.8);  // and fills most of it
    // Each light gives the model's centre the irradiance base's light gave base's target.
    ASSERT_EQ(scene.lights.size(), base.lights.size());
    for (size_t i = 0; i < base.lights.size(); ++i) {
        auto irradiance = [](const PointLightDesc& l, const glm::dvec3& at) {
            glm::dvec3 d = l.position - at;
            return l.color / glm::dot(d, d);
        };
        glm::dvec3 a = irradiance(base.lights[i], base.camera.target),
                   b = irradiance(scene.lights[i], centre);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c] / a[c], 1.0, 1e-9);
    }
}

TEST(Models, EmissionIsCheckedAgainstTheCpuReference) {
    Headless h;
    const LoadedModule& m = h.modules.find("reflectance");
    Scene scene = modelScene(h, kModels / "textured-sphere.glb");
    ParamValues params(m.desc->params);
    EvalRequest request;
    request.render = {&m, &params, &scene, {}, nullptr, 128, 128};
    const Evaluation e = evaluate(h.renderer, request);
    EXPECT_TRUE(e.comparison.passes(m.desc->nonNegative, m.desc->tolerance.outlierFraction))
        << describe(e.comparison);
    // Not vacuous: the seams glow, and a reference without the emission would fail there.
    const std::vector<Surface>& surfaces = e.render.surfaces;
    size_t brightest = 0;
    for (size_t i = 0; i < surfaces.size(); ++i)
        if (surfaces[i].emissive.r > surfaces[brightest].emissive.r) brightest = i;
    Surface s = surfaces[brightest];
    ASSERT_GT(s.emissive.r, 0.5);
    const ReferenceContext context =
        referenceContext(h.renderer, *m.desc, scene, params, request.render.ibl);
    const double gpu = e.render.value.pixels[brightest * 4];
    const double withEmission = m.desc->reference(s, context).r;
    s.emissive = glm::dvec3(0);
    const double without = m.desc->reference(s, context).r;
    const double slack = e.band.slack[brightest].r;
    EXPECT_LE(std::abs(gpu - withEmission), slack);
    EXPECT_GT(std::abs(gpu - without), 100 * slack);
}

TEST(Models, CorruptedModelsAndEmbeddedImagesGiveErrorsNotCrashes) {
    // Deterministic byte flips and cuts of the textured sphere (its PNGs are embedded, so
    // the flips reach the image decoder too): load, then decode every image; each step must
    // succeed or throw pbrlab::Error naming the file.
    std::ifstream in(kModels / "textured-sphere.glb", std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    test::TempDir dir;
    const fs::path file = dir.path / "mutated.glb";
    std::mt19937 rng(11);
    int loadErrors = 0, decodeErrors = 0, decoded = 0;
    for (int i = 0; i < 120; ++i) {
        std::string b = bytes;
        if (i % 3 == 0) b.resize(1 + rng() % (b.size() - 1));  // never empty: flips need a byte
        for (int k = 0; k < 6; ++k) b[rng() % b.size()] = char(rng());
        std::ofstream(file, std::ios::binary) << b;
        ModelData model;
        try {
            model = loadGltf(file);
        } catch (const Error& e) {
            ++loadErrors;
            EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
            continue;
        }
        for (const TextureSource& image : model.images) {
            try {
                readTexture(image);
                ++decoded;
            } catch (const Error& e) {
                ++decodeErrors;
                EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
            }
        }
    }
    // Both paths were exercised (cuts fail the load; flips inside a PNG fail its decode).
    EXPECT_GT(loadErrors, 0);
    EXPECT_GT(decodeErrors, 0);
    EXPECT_GT(decoded, 0);
}
