// The project's own glTF test models (writeSphereGridGlb, writeTexturedSphereGlb in
// assets/gltf.h), written with tinygltf: small, deterministic, made by the project's code.
#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <vector>

#include "assets/gltf.h"
#include "assets/texgen.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// Builds a one-buffer glTF binary: one view per attribute keeps the file simple to read back.
struct GlbWriter {
    tinygltf::Model m;
    tinygltf::Buffer buffer;

    GlbWriter() {
        m.asset.version = "2.0";
        m.asset.generator = "pbrlab";
    }
    size_t append(const void* data, size_t bytes) {
        size_t offset = buffer.data.size();
        auto p = static_cast<const unsigned char*>(data);
        buffer.data.insert(buffer.data.end(), p, p + bytes);
        while (buffer.data.size() % 4) buffer.data.push_back(0);
        return offset;
    }
    int addView(const void* data, size_t bytes, int target) {
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = append(data, bytes);
        v.byteLength = bytes;
        v.target = target;
        m.bufferViews.push_back(v);
        return int(m.bufferViews.size() - 1);
    }
    int addAccessor(const std::vector<float>& values, int type, int components) {
        tinygltf::Accessor a;
        a.bufferView = addView(values.data(), values.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER);
        a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        a.count = values.size() / size_t(components);
        a.type = type;
        m.accessors.push_back(a);
        return int(m.accessors.size() - 1);
    }
    tinygltf::Primitive addMesh(const MeshData& mesh, bool withTangents) {
        std::vector<float> pos, nor, uv, tan;
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const auto& v : mesh.vertices) {
            pos.insert(pos.end(), {v.position.x, v.position.y, v.position.z});
            nor.insert(nor.end(), {v.normal.x, v.normal.y, v.normal.z});
            uv.insert(uv.end(), {v.uv.x, v.uv.y});
            tan.insert(tan.end(), {v.tangent.x, v.tangent.y, v.tangent.z, v.tangent.w});
            lo = glm::min(lo, v.position);
            hi = glm::max(hi, v.position);
        }
        tinygltf::Primitive prim;
        prim.attributes["POSITION"] = addAccessor(pos, TINYGLTF_TYPE_VEC3, 3);
        m.accessors.back().minValues = {lo.x, lo.y, lo.z};  // required for POSITION
        m.accessors.back().maxValues = {hi.x, hi.y, hi.z};
        prim.attributes["NORMAL"] = addAccessor(nor, TINYGLTF_TYPE_VEC3, 3);
        prim.attributes["TEXCOORD_0"] = addAccessor(uv, TINYGLTF_TYPE_VEC2, 2);
        if (withTangents) prim.attributes["TANGENT"] = addAccessor(tan, TINYGLTF_TYPE_VEC4, 4);
        tinygltf::Accessor a;
        a.bufferView = addView(mesh.indices.data(), mesh.indices.size() * 4,
                               TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
        a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        a.count = mesh.indices.size();
        a.type = TINYGLTF_TYPE_SCALAR;
        m.accessors.push_back(a);
        prim.indices = int(m.accessors.size() - 1);
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        return prim;
    }
    // An embedded PNG; returns the texture index.
    int addPng(const fs::path& pngFile, const std::string& name) {
        std::ifstream in(pngFile, std::ios::binary);
        std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                         std::istreambuf_iterator<char>());
        if (bytes.empty()) throw Error(pngFile.string() + ": cannot read the image to embed");
        tinygltf::Image image;
        image.name = name;
        image.mimeType = "image/png";
        image.bufferView = addView(bytes.data(), bytes.size(), 0);
        m.images.push_back(image);
        tinygltf::Texture texture;
        texture.source = int(m.images.size() - 1);
        m.textures.push_back(texture);
        return int(m.textures.size() - 1);
    }
    void addNode(int mesh, const std::vector<double>& translation, tinygltf::Scene& scene) {
        tinygltf::Node node;
        node.mesh = mesh;
        node.translation = translation;
        m.nodes.push_back(node);
        scene.nodes.push_back(int(m.nodes.size() - 1));
    }
    void write(const fs::path& file, tinygltf::Scene scene) {
        m.buffers.push_back(buffer);
        m.scenes.push_back(std::move(scene));
        m.defaultScene = 0;
        fs::create_directories(file.parent_path().empty() ? "." : file.parent_path());
        tinygltf::TinyGLTF writer;
        if (!writer.WriteGltfSceneToFile(&m, file.string(), true, true, false, true))
            throw Error(file.string() + ": cannot write the glTF binary");
    }
};

}  // namespace

void writeSphereGridGlb(const fs::path& file) {
    GlbWriter w;
    const tinygltf::Primitive sphere = w.addMesh(makeUvSphere(48, 24), true);
    tinygltf::Scene scene;
    for (int row = 0; row < 7; ++row)
        for (int col = 0; col < 7; ++col) {
            tinygltf::Material mat;
            mat.name = "row" + std::to_string(row) + "-col" + std::to_string(col);
            mat.pbrMetallicRoughness.baseColorFactor = {0.5, 0, 0, 1};
            mat.pbrMetallicRoughness.metallicFactor = row / 7.0;
            mat.pbrMetallicRoughness.roughnessFactor = std::clamp(col / 7.0, 0.05, 1.0);
            w.m.materials.push_back(mat);
            tinygltf::Mesh mesh;
            tinygltf::Primitive p = sphere;
            p.material = int(w.m.materials.size() - 1);
            mesh.primitives.push_back(p);
            w.m.meshes.push_back(mesh);
            w.addNode(int(w.m.meshes.size() - 1), {(col - 3) * 2.5, (row - 3) * 2.5, 0.0}, scene);
        }
    w.write(file, scene);
}

void writeTexturedSphereGlb(const fs::path& file, int size) {
    // The maps are made by the texture generator, then repacked the way glTF wants them.
    const fs::path work =
        fs::temp_directory_path() / ("pbrlab-textured-sphere-" + std::to_string(::getpid()));
    fs::remove_all(work);
    generateMetalPlates(work, size);
    struct Cleanup {
        fs::path dir;
        ~Cleanup() {
            std::error_code ec;
            fs::remove_all(dir, ec);
        }
    } cleanup{work};
    const Image roughness = readImage(work / "roughness.png"),
                metallic = readImage(work / "metallic.png"), ao = readImage(work / "ao.png");
    Image orm = ao, emissive = ao;
    orm.channels = emissive.channels = 3;
    orm.pixels.assign(size_t(size) * size * 3, 0);
    emissive.pixels.assign(size_t(size) * size * 3, 0);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            orm.at(x, y, 0) = ao.at(x, y, 0);
            orm.at(x, y, 1) = roughness.at(x, y, 0);
            orm.at(x, y, 2) = metallic.at(x, y, 0);
            // Seams glow: the deepest grooves (lowest ao) emit, the plates do not.
            float glow = std::clamp((0.55f - ao.at(x, y, 0)) / 0.25f, 0.0f, 1.0f);
            for (int c = 0; c < 3; ++c) emissive.at(x, y, c) = glow;
        }
    // Linear data: no sRGB tag (glTF reads metallic-roughness and occlusion as linear).
    writeImage(work / "orm.png", orm, FileDepth::Uint8, false);
    writeImage(work / "emissive.png", emissive, FileDepth::Uint8, true);

    GlbWriter w;
    tinygltf::Material mat;
    mat.name = "metal-plates";
    mat.pbrMetallicRoughness.baseColorTexture.index = w.addPng(work / "albedo.png", "albedo");
    const int ormTexture = w.addPng(work / "orm.png", "occlusion-roughness-metallic");
    mat.pbrMetallicRoughness.metallicRoughnessTexture.index = ormTexture;
    mat.occlusionTexture.index = ormTexture;
    mat.normalTexture.index = w.addPng(work / "normal.png", "normal");
    mat.emissiveTexture.index = w.addPng(work / "emissive.png", "emissive seams");
    mat.emissiveFactor = {1.0, 0.45, 0.1};
    w.m.materials.push_back(mat);
    tinygltf::Mesh mesh;
    tinygltf::Primitive p = w.addMesh(makeUvSphere(96, 48), false);
    p.material = 0;
    mesh.primitives.push_back(p);
    w.m.meshes.push_back(mesh);
    tinygltf::Scene scene;
    w.addNode(0, {}, scene);
    w.write(file, scene);
}

}  // namespace pbrlab
