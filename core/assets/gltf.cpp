#include "assets/gltf.h"

#include <tiny_gltf.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "assets/texgen.h"
#include "util/error.h"
#include "util/fs.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& why) {
    throw Error(file.string() + ": " + why);
}

// The accessor `index`, checked: it exists, is not sparse, and its buffer view lies inside its
// buffer. Returns the accessor with its first byte and stride.
struct AccessorData {
    const tinygltf::Accessor* accessor;
    const unsigned char* first;
    size_t stride;
};

AccessorData accessorData(const tinygltf::Model& m, int index, size_t elementBytes,
                          const fs::path& file, const std::string& what) {
    if (index < 0 || index >= int(m.accessors.size())) fail(file, what + ": no such accessor");
    const auto& a = m.accessors[size_t(index)];
    if (a.sparse.isSparse) fail(file, what + ": sparse accessors are not supported");
    if (a.bufferView < 0 || a.bufferView >= int(m.bufferViews.size()))
        fail(file, what + ": no buffer view");
    const auto& view = m.bufferViews[size_t(a.bufferView)];
    if (view.buffer < 0 || view.buffer >= int(m.buffers.size())) fail(file, what + ": no buffer");
    const auto& buffer = m.buffers[size_t(view.buffer)].data;
    const size_t stride = view.byteStride ? view.byteStride : elementBytes;
    const size_t begin = view.byteOffset + a.byteOffset;
    if (a.count > 0 && (begin > buffer.size() || (a.count - 1) > buffer.size() / stride ||
                        begin + stride * (a.count - 1) + elementBytes > buffer.size()))
        fail(file, what + ": data runs past the end of its buffer");
    return {&a, buffer.data() + begin, stride};
}

// Reads accessor `index` as `components` floats per element, honouring byte strides. Float
// data, or (texture coordinates) normalized unsigned bytes or shorts, as glTF allows.
std::vector<float> readFloats(const tinygltf::Model& m, int index, int components,
                              const fs::path& file, const std::string& what,
                              bool normalizedIntegers = false) {
    if (index < 0 || index >= int(m.accessors.size())) fail(file, what + ": no such accessor");
    const int type = m.accessors[size_t(index)].componentType;
    const size_t size = type == TINYGLTF_COMPONENT_TYPE_FLOAT            ? 4
                        : !normalizedIntegers                            ? 0
                        : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE  ? 1
                        : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                                                                         : 0;
    if (!size)
        fail(file, what + (normalizedIntegers
                               ? ": expected float or normalized unsigned byte/short components"
                               : ": expected float components"));
    if (tinygltf::GetNumComponentsInType(uint32_t(m.accessors[size_t(index)].type)) != components)
        fail(file, what + ": expected " + std::to_string(components) + " components");
    const AccessorData d = accessorData(m, index, size * size_t(components), file, what);
    std::vector<float> out(d.accessor->count * size_t(components));
    for (size_t i = 0; i < d.accessor->count; ++i)
        for (int c = 0; c < components; ++c) {
            const unsigned char* at = d.first + i * d.stride + size_t(c) * size;
            float& v = out[i * size_t(components) + size_t(c)];
            if (size == 4) {
                std::memcpy(&v, at, 4);
            } else if (size == 1) {
                v = float(at[0]) / 255.0f;
            } else {
                std::uint16_t u;
                std::memcpy(&u, at, 2);  // little-endian, as glTF stores it
                v = float(u) / 65535.0f;
            }
        }
    return out;
}

// The primitive's vertex indices as stored (or 0..n-1 when it has none).
std::vector<std::uint32_t> readIndices(const tinygltf::Model& m, int index, size_t vertexCount,
                                       const fs::path& file) {
    std::vector<std::uint32_t> out;
    if (index < 0) {
        for (size_t i = 0; i < vertexCount; ++i) out.push_back(std::uint32_t(i));
        return out;
    }
    if (index >= int(m.accessors.size())) fail(file, "indices: no such accessor");
    const int type = m.accessors[size_t(index)].componentType;
    const size_t size = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                        : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                        : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                         : 0;
    if (!size) fail(file, "indices: expected unsigned integers");
    const AccessorData d = accessorData(m, index, size, file, "indices");
    for (size_t i = 0; i < d.accessor->count; ++i) {
        std::uint32_t v = 0;
        std::memcpy(&v, d.first + i * d.stride, size);  // little-endian
        if (v >= vertexCount) fail(file, "index " + std::to_string(v) + " past the vertices");
        out.push_back(v);
    }
    return out;
}

// Strips and fans as triangle lists, counter-clockwise kept (the glTF specification's rules).
std::vector<std::uint32_t> triangleList(const std::vector<std::uint32_t>& in, int mode) {
    std::vector<std::uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 0; i + 2 < in.size(); ++i) {
            const size_t odd = i % 2;
            out.insert(out.end(), {in[i], in[i + 1 + odd], in[i + 2 - odd]});
        }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (size_t i = 0; i + 2 < in.size(); ++i)
            out.insert(out.end(), {in[i + 1], in[i + 2], in[0]});
    } else {
        out.assign(in.begin(), in.end() - std::ptrdiff_t(in.size() % 3));
    }
    return out;
}

// Each triangle gets its own three vertices with the face normal: the glTF specification's
// "flat normals" for primitives without NORMAL.
void flatNormals(MeshData& mesh) {
    MeshData flat;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        Vertex v[3] = {mesh.vertices[mesh.indices[i]], mesh.vertices[mesh.indices[i + 1]],
                       mesh.vertices[mesh.indices[i + 2]]};
        glm::dvec3 n = glm::cross(glm::dvec3(v[1].position - v[0].position),
                                  glm::dvec3(v[2].position - v[0].position));
        const double length = glm::length(n);
        const glm::vec3 normal = length > 0 ? glm::vec3(n / length) : glm::vec3(0, 0, 1);
        for (Vertex& corner : v) {
            corner.normal = normal;
            flat.indices.push_back(std::uint32_t(flat.vertices.size()));
            flat.vertices.push_back(corner);
        }
    }
    mesh = std::move(flat);
}

TextureSource::Wrap wrapMode(int glWrap) {
    switch (glWrap) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
            return TextureSource::Wrap::Clamp;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
            return TextureSource::Wrap::Mirror;
        default:
            return TextureSource::Wrap::Repeat;
    }
}

glm::dmat4 nodeMatrix(const tinygltf::Node& n) {
    if (n.matrix.size() == 16) return glm::make_mat4(n.matrix.data());
    glm::dmat4 m(1);
    if (n.translation.size() == 3) m = glm::translate(m, glm::make_vec3(n.translation.data()));
    if (n.rotation.size() == 4)
        m *= glm::mat4_cast(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]));
    if (n.scale.size() == 3) m = glm::scale(m, glm::make_vec3(n.scale.data()));
    return m;
}

// "%20" -> " ": glTF URIs are percent-encoded.
std::string percentDecode(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(uint8_t(uri[i + 1])) &&
            std::isxdigit(uint8_t(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

// True when `uri` (percent-decoded, relative to the model's folder `dir`) names a file inside
// that folder or below it: not absolute, not climbing out with "..", not a link leading out.
bool besideModel(const fs::path& dir, const std::string& uri) {
    const fs::path relative(uri);
    if (relative.has_root_path()) return false;
    return isInside(dir / relative, dir);
}

// What the file-reading callbacks below need: the model's folder (nothing outside it is read)
// and the external image files, left unread.
struct ModelFiles {
    fs::path dir;
    std::set<fs::path> images;  // canonical
};

// The model's external files, from its JSON read before tinygltf reads anything: each buffer
// and image URI must lie in the model's folder (else an error saying so), and the image files
// are remembered so that the file-reading callback below can leave them unread. JSON that
// does not parse: nothing checked here, and tinygltf reports the error itself.
ModelFiles externalFiles(const fs::path& file) {
    // The model's folder ("." for a bare file name: tinygltf then looks there too).
    ModelFiles files{file.has_parent_path() ? file.parent_path() : fs::path("."), {}};
    nlohmann::json doc;
    try {
        std::ifstream in(file, std::ios::binary);
        std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::string text = bytes;
        if (bytes.size() >= 20 && bytes.compare(0, 4, "glTF") == 0) {  // binary: chunk 0 is JSON
            uint32_t length = 0;
            std::memcpy(&length, bytes.data() + 12, 4);
            if (length > bytes.size() - 20) return files;
            text = bytes.substr(20, length);
        }
        doc = nlohmann::json::parse(text);
    } catch (const std::exception&) {
        return files;
    }
    if (!doc.is_object()) return files;
    for (const char* kind : {"buffers", "images"}) {
        const auto list = doc.value(kind, nlohmann::json::array());
        if (!list.is_array()) continue;
        for (size_t i = 0; i < list.size(); ++i) {
            const auto& item = list[i];
            if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
            const std::string uri = item["uri"].get<std::string>();
            if (uri.rfind("data:", 0) == 0) continue;
            const std::string decoded = percentDecode(uri);
            const std::string what = std::string(kind).substr(0, std::strlen(kind) - 1) + " " +
                                     std::to_string(i) + " ('" + uri + "')";
            if (!besideModel(files.dir, decoded))
                fail(file, what + ": refused: " + decoded + " lies outside the model's folder " +
                               fs::absolute(files.dir).lexically_normal().string() +
                               " (a model may only read files beside it)");
            std::error_code ec;
            if (std::string(kind) == "images")
                files.images.insert(fs::weakly_canonical(files.dir / decoded, ec));
        }
    }
    return files;
}

// Reads what tinygltf asks for, except the external image files: for those it hands back one
// placeholder byte (tinygltf refuses an empty read) and the image is read on first use.
bool readWholeFileExceptImages(std::vector<unsigned char>* out, std::string* err,
                               const std::string& path, void* userData) {
    const auto* files = static_cast<const ModelFiles*>(userData);
    std::error_code ec;
    if (files->images.count(fs::weakly_canonical(path, ec)) && fs::is_regular_file(path, ec)) {
        out->assign(1, 0);
        return true;
    }
    return tinygltf::ReadWholeFile(out, err, path, nullptr);
}

// tinygltf's own check opens the file; a stat is enough (and leaves image files unopened).
// Nothing outside the model's folder exists for tinygltf: not even the file of the same name
// in the working directory, where tinygltf looks when the model's folder lacks it.
bool fileExists(const std::string& path, void* userData) {
    const auto* files = static_cast<const ModelFiles*>(userData);
    std::error_code ec;
    return fs::is_regular_file(path, ec) && isInside(path, files->dir);
}

// Keeps images encoded: embedded bytes are copied (decoded later, if ever), external files
// are remembered by path. Nothing is decoded here.
struct ImageCollector {
    fs::path file;
    std::map<int, TextureSource> images;  // by image index
};

bool collectImage(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                  const unsigned char* bytes, int size, void* userData) {
    auto* c = static_cast<ImageCollector*>(userData);
    TextureSource& t = c->images[index];
    if (!image->uri.empty() && image->uri.rfind("data:", 0) != 0) {
        t.file = c->file.parent_path() / percentDecode(image->uri);
        t.key = t.file.string();
    } else {
        t.key = c->file.string() + "#image " + std::to_string(index) +
                (image->name.empty() ? "" : " (" + image->name + ")");
        t.encoded = std::make_shared<const std::vector<unsigned char>>(bytes, bytes + size);
        t.extension = image->mimeType == "image/jpeg" ? ".jpg" : ".png";
    }
    return true;
}

// "node 3 ('arm')": a node as an error message names it.
std::string nodeName(const tinygltf::Model& m, int index) {
    const std::string& name = m.nodes[size_t(index)].name;
    return "node " + std::to_string(index) + (name.empty() ? "" : " ('" + name + "')");
}

// The node hierarchy is a forest, as glTF requires, checked before anything walks it: every
// child exists and has one parent, no node is its own ancestor, and each scene's roots exist,
// are distinct and are nobody's child. (Walked as given, a loop never ends and a node shared
// by parents is drawn once per path: exponentially many.)
void checkNodeForest(const tinygltf::Model& m, const fs::path& file) {
    const int count = int(m.nodes.size());
    std::vector<int> parent(size_t(count), -1);
    for (int p = 0; p < count; ++p)
        for (int c : m.nodes[size_t(p)].children) {
            if (c < 0 || c >= count)
                fail(file, nodeName(m, p) + " lists child " + std::to_string(c) +
                               ", which does not exist");
            if (c == p)
                fail(file, nodeName(m, p) + " lists itself as a child: the nodes loop (" +
                               nodeName(m, p) + " -> " + nodeName(m, p) + ")");
            if (parent[size_t(c)] == p)
                fail(file, nodeName(m, p) + " lists " + nodeName(m, c) + " twice as a child");
            if (parent[size_t(c)] >= 0)
                fail(file, nodeName(m, c) + " has two parents, " + nodeName(m, parent[size_t(c)]) +
                               " and " + nodeName(m, p) + " (glTF allows a node one parent)");
            parent[size_t(c)] = p;
        }
    // One parent each: following parents from any node either reaches a root or goes round a
    // loop. 0: not seen, 1: on the chain being followed, 2: leads to a root.
    std::vector<char> state(size_t(count), 0);
    for (int start = 0; start < count; ++start) {
        std::vector<int> chain;
        int n = start;
        while (n >= 0 && state[size_t(n)] == 0) {
            state[size_t(n)] = 1;
            chain.push_back(n);
            n = parent[size_t(n)];
        }
        if (n >= 0 && state[size_t(n)] == 1) {  // back on the chain: n is its own ancestor
            // The chain runs child to parent, n first on the loop; said parent to child.
            std::string loop = nodeName(m, n);
            for (auto it = chain.rbegin(); *it != n; ++it) loop += " -> " + nodeName(m, *it);
            fail(file, "the nodes loop: " + loop + " -> " + nodeName(m, n));
        }
        for (int c : chain) state[size_t(c)] = 2;
    }
    for (size_t s = 0; s < m.scenes.size(); ++s) {
        std::set<int> roots;
        const std::string scene = "scene " + std::to_string(s);
        for (int r : m.scenes[s].nodes) {
            if (r < 0 || r >= count)
                fail(file, scene + " lists node " + std::to_string(r) + ", which does not exist");
            if (parent[size_t(r)] >= 0)
                fail(file, scene + " lists " + nodeName(m, r) +
                               " as a root, but it is a child of " +
                               nodeName(m, parent[size_t(r)]));
            if (!roots.insert(r).second) fail(file, scene + " lists " + nodeName(m, r) + " twice");
        }
    }
}

// The document as tinygltf reads it, with its images left encoded in `collector`. Buffers and
// images outside the model's folder are refused before anything is read.
tinygltf::Model readDocument(const fs::path& file, ImageCollector& collector) {
    ModelFiles files = externalFiles(file);  // throws for a file outside the model's folder
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(collectImage, &collector);
    loader.SetFsCallbacks({&fileExists, &tinygltf::ExpandFilePath, &readWholeFileExceptImages,
                           &tinygltf::WriteWholeFile, &files});
    tinygltf::Model model;
    std::string err, warn;
    bool binary = file.extension() == ".glb";
    bool ok = binary ? loader.LoadBinaryFromFile(&model, &err, &warn, file.string())
                     : loader.LoadASCIIFromFile(&model, &err, &warn, file.string());
    if (!ok)
        fail(file, "not a valid glTF " + std::string(binary ? "binary" : "file") +
                       (err.empty() ? "" : ": " + err));
    return model;
}

// The model's images in file order, as collected; an image missing from the collection is an
// error naming it.
std::vector<TextureSource> collectedImages(const tinygltf::Model& model, ImageCollector& collector,
                                           const fs::path& file) {
    std::vector<TextureSource> images;
    for (size_t i = 0; i < model.images.size(); ++i) {
        auto it = collector.images.find(int(i));
        // tinygltf skips the callback for an external file it could not find.
        if (it == collector.images.end())
            fail(file, "image " + std::to_string(i) + " ('" + model.images[i].uri +
                           "'): file not found or not readable");
        images.push_back(std::move(it->second));
    }
    return images;
}

// Reads the materials: their maps index `data.images` (already read), and what a map uses
// that is not drawn goes to `data.warnings`.
struct MaterialReader {
    const tinygltf::Model& model;
    const fs::path& file;
    ModelData& data;

    // The texture `info` names, checked to exist and to have an image, with its sampler's wrap.
    ModelMaterial::Map map(const tinygltf::TextureInfo& info, const std::string& what) const {
        ModelMaterial::Map map;
        if (info.index < 0) return map;
        if (info.texCoord != 0)
            data.warnings.push_back(what + " uses TEXCOORD_" + std::to_string(info.texCoord) +
                                    "; pbrlab reads TEXCOORD_0");
        if (info.index >= int(model.textures.size()))
            fail(file, what + ": texture " + std::to_string(info.index) + " does not exist");
        const tinygltf::Texture& texture = model.textures[size_t(info.index)];
        if (texture.source < 0 || texture.source >= int(data.images.size()))
            fail(file, what + ": texture " + std::to_string(info.index) + " has no image");
        map.image = texture.source;
        if (texture.sampler >= 0 && texture.sampler < int(model.samplers.size())) {
            map.wrapU = wrapMode(model.samplers[size_t(texture.sampler)].wrapS);
            map.wrapV = wrapMode(model.samplers[size_t(texture.sampler)].wrapT);
        }
        return map;
    }

    // One glTF material's factors and maps.
    ModelMaterial material(const tinygltf::Material& mat) const {
        ModelMaterial mm;
        mm.name = mat.name;
        const auto& pbr = mat.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() == 4)
            mm.baseColorFactor = glm::make_vec4(pbr.baseColorFactor.data());
        mm.metallicFactor = pbr.metallicFactor;
        mm.roughnessFactor = pbr.roughnessFactor;
        if (mat.emissiveFactor.size() == 3)
            mm.emissiveFactor = glm::make_vec3(mat.emissiveFactor.data());
        mm.normalScale = mat.normalTexture.scale;
        mm.occlusionStrength = mat.occlusionTexture.strength;
        const std::string what = "material '" + mat.name + "'";
        mm.baseColorTexture = map(pbr.baseColorTexture, what + " baseColorTexture");
        mm.metallicRoughnessTexture =
            map(pbr.metallicRoughnessTexture, what + " metallicRoughnessTexture");
        tinygltf::TextureInfo normal, occlusion;
        normal.index = mat.normalTexture.index;
        normal.texCoord = mat.normalTexture.texCoord;
        occlusion.index = mat.occlusionTexture.index;
        occlusion.texCoord = mat.occlusionTexture.texCoord;
        mm.normalTexture = map(normal, what + " normalTexture");
        mm.occlusionTexture = map(occlusion, what + " occlusionTexture");
        mm.emissiveTexture = map(mat.emissiveTexture, what + " emissiveTexture");
        // Emission brighter than 1: the factor times this strength
        // (KHR_materials_emissive_strength).
        if (auto it = mat.extensions.find("KHR_materials_emissive_strength");
            it != mat.extensions.end() && it->second.IsObject() &&
            it->second.Has("emissiveStrength") && it->second.Get("emissiveStrength").IsNumber()) {
            const double strength = it->second.Get("emissiveStrength").GetNumberAsDouble();
            if (!(strength >= 0) || !std::isfinite(strength))
                fail(file, what + ": emissiveStrength must be finite and >= 0");
            mm.emissiveFactor *= strength;
        }
        if (mat.alphaMode != "OPAQUE" && !mat.alphaMode.empty())
            data.warnings.push_back(what + ": alphaMode " + mat.alphaMode + " is drawn opaque");
        return mm;
    }
};

// The default scene's root nodes (none when the file has no such scene).
std::vector<int> defaultSceneRoots(const tinygltf::Model& model) {
    std::vector<int> roots;
    const int sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (sceneIndex < int(model.scenes.size())) roots = model.scenes[size_t(sceneIndex)].nodes;
    return roots;
}

// Every primitive is a draw: more than a scene may draw is refused before any is read.
void checkDrawCount(const tinygltf::Model& model, const std::vector<int>& roots,
                    const fs::path& file) {
    size_t primitives = 0;
    for (std::vector<int> open = roots; !open.empty();) {
        const auto& node = model.nodes[size_t(open.back())];
        open.pop_back();
        open.insert(open.end(), node.children.begin(), node.children.end());
        if (node.mesh < 0) continue;
        if (node.mesh >= int(model.meshes.size())) fail(file, "node mesh index out of range");
        primitives += model.meshes[size_t(node.mesh)].primitives.size();
    }
    if (primitives > kMaxDrawnMeshes)
        fail(file, "its scene draws " + std::to_string(primitives) +
                       " primitives (a mesh's primitives, once per node that places it), more "
                       "than pbrlab draws (at most " +
                       std::to_string(kMaxDrawnMeshes) + ")");
}

// The accessor index of the primitive's attribute `name`, -1 when it has none.
int attributeAccessor(const tinygltf::Primitive& prim, const char* name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
}

// A primitive's vertex attributes as floats; those it lacks are zeros (tangents: none).
struct VertexAttributes {
    std::vector<float> positions, normals, uvs, tangents;
    size_t count = 0;
    bool hasNormals = false, hasTangents = false;
};

// The primitive's attributes read, and checked to have as many elements as POSITION.
VertexAttributes readAttributes(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                const fs::path& file) {
    VertexAttributes a;
    a.positions = readFloats(model, attributeAccessor(prim, "POSITION"), 3, file, "POSITION");
    a.count = a.positions.size() / 3;
    a.hasNormals = attributeAccessor(prim, "NORMAL") >= 0;
    a.normals = a.hasNormals
                    ? readFloats(model, attributeAccessor(prim, "NORMAL"), 3, file, "NORMAL")
                    : std::vector<float>(a.count * 3, 0.0f);
    a.uvs =
        attributeAccessor(prim, "TEXCOORD_0") >= 0
            ? readFloats(model, attributeAccessor(prim, "TEXCOORD_0"), 2, file, "TEXCOORD_0", true)
            : std::vector<float>(a.count * 2, 0.0f);
    // Tangents only mean something next to the normals they were made for.
    a.hasTangents = a.hasNormals && attributeAccessor(prim, "TANGENT") >= 0;
    a.tangents = a.hasTangents
                     ? readFloats(model, attributeAccessor(prim, "TANGENT"), 4, file, "TANGENT")
                     : std::vector<float>();
    if (a.normals.size() != a.count * 3 || a.uvs.size() != a.count * 2 ||
        (a.hasTangents && a.tangents.size() != a.count * 4))
        fail(file, "attribute counts differ from POSITION's");
    return a;
}

// The attributes as vertices (tangent (1, 0, 0, 1) where the file has none).
std::vector<Vertex> vertices(const VertexAttributes& a) {
    std::vector<Vertex> out;
    for (size_t i = 0; i < a.count; ++i) {
        Vertex v;
        v.position = glm::make_vec3(&a.positions[i * 3]);
        v.normal = glm::make_vec3(&a.normals[i * 3]);
        v.uv = glm::make_vec2(&a.uvs[i * 2]);
        v.tangent = a.hasTangents ? glm::make_vec4(&a.tangents[i * 4]) : glm::vec4(1, 0, 0, 1);
        out.push_back(v);
    }
    return out;
}

// What the scene has that is not drawn, for the warnings.
struct UndrawnFeatures {
    int skippedPrimitives = 0;
    bool usesVertexColours = false;
};

// One primitive placed by `world` as a triangle mesh in `data.primitives`, with normals and
// tangents generated where the file has none; points and lines are counted in `undrawn`.
void readPrimitive(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                   const glm::dmat4& world, const fs::path& file, ModelData& data,
                   UndrawnFeatures& undrawn) {
    const int mode = prim.mode == -1 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        undrawn.skippedPrimitives++;
        return;
    }
    if (attributeAccessor(prim, "POSITION") < 0) fail(file, "a primitive has no POSITION");
    if (attributeAccessor(prim, "COLOR_0") >= 0) undrawn.usesVertexColours = true;
    const VertexAttributes attributes = readAttributes(model, prim, file);
    ModelPrimitive p;
    p.transform = world;
    if (prim.material >= int(data.materials.size()))
        fail(file, "a primitive names material " + std::to_string(prim.material) +
                       ", which does not exist");
    p.material = prim.material;
    p.mesh.vertices = vertices(attributes);
    p.mesh.indices = triangleList(readIndices(model, prim.indices, attributes.count, file), mode);
    if (p.mesh.indices.empty()) return;  // fewer than three vertices: nothing to draw
    if (!attributes.hasNormals) {
        flatNormals(p.mesh);
        p.generatedNormals = true;
    }
    if (!attributes.hasTangents) {
        generateTangents(p.mesh);
        p.generatedTangents = true;
    }
    data.primitives.push_back(std::move(p));
}

// Walks the nodes from `roots`, applying their transforms, and reads the primitives of each
// mesh a node places.
void readPlacedMeshes(const tinygltf::Model& model, const std::vector<int>& roots,
                      const fs::path& file, ModelData& data, UndrawnFeatures& undrawn) {
    std::vector<std::pair<int, glm::dmat4>> stack;
    for (int n : roots) stack.push_back({n, glm::dmat4(1)});
    while (!stack.empty()) {
        auto [index, parent] = stack.back();
        stack.pop_back();
        const auto& node = model.nodes[size_t(index)];
        glm::dmat4 world = parent * nodeMatrix(node);
        for (int c : node.children) stack.push_back({c, world});
        if (node.mesh < 0) continue;
        for (const auto& prim : model.meshes[size_t(node.mesh)].primitives)
            readPrimitive(model, prim, world, file, data, undrawn);
    }
}

}  // namespace

void generateTangents(MeshData& mesh) {
    std::vector<glm::dvec3> t(mesh.vertices.size(), glm::dvec3(0)), b = t;
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const Vertex* v[3] = {&mesh.vertices[mesh.indices[i]], &mesh.vertices[mesh.indices[i + 1]],
                              &mesh.vertices[mesh.indices[i + 2]]};
        glm::dvec3 e1 = glm::dvec3(v[1]->position - v[0]->position),
                   e2 = glm::dvec3(v[2]->position - v[0]->position);
        glm::dvec2 d1 = glm::dvec2(v[1]->uv - v[0]->uv), d2 = glm::dvec2(v[2]->uv - v[0]->uv);
        double det = d1.x * d2.y - d2.x * d1.y;
        if (std::abs(det) < 1e-20) continue;  // no uv extent: contributes no direction
        glm::dvec3 tangent = (e1 * d2.y - e2 * d1.y) / det,
                   bitangent = (e2 * d1.x - e1 * d2.x) / det;
        for (int k = 0; k < 3; ++k) {
            t[mesh.indices[i + size_t(k)]] += tangent;
            b[mesh.indices[i + size_t(k)]] += bitangent;
        }
    }
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
        glm::dvec3 n = glm::normalize(glm::dvec3(mesh.vertices[i].normal));
        glm::dvec3 tangent = t[i] - n * glm::dot(n, t[i]);
        if (glm::dot(tangent, tangent) < 1e-24)  // any perpendicular keeps the frame valid
            tangent =
                glm::cross(n, std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0));
        tangent = glm::normalize(tangent);
        // glTF uv has v = 0 at the image top, and a normal map's +Y points up the image: the
        // bitangent cross(N, T) * w must point towards decreasing v, i.e. against d P / d v.
        double w = glm::dot(glm::cross(n, tangent), -b[i]) < 0 ? -1.0 : 1.0;
        mesh.vertices[i].tangent = glm::vec4(glm::vec3(tangent), float(w));
    }
}

ModelData loadGltf(const fs::path& file) {
    if (!fs::exists(file)) fail(file, "no such file");
    if (fs::is_directory(file)) fail(file, "is a directory, not a glTF file");
    ModelData data;
    data.file = file;
    ImageCollector collector{file, {}};
    const tinygltf::Model model = readDocument(file, collector);
    data.images = collectedImages(model, collector, file);
    // Extensions change what a file means; say which ones are drawn without their effect.
    for (const std::string& extension : model.extensionsUsed)
        if (extension != "KHR_materials_emissive_strength")
            data.warnings.push_back("extension " + extension +
                                    " is not supported: drawn without it");
    data.meshCount = int(model.meshes.size());
    const MaterialReader materials{model, file, data};
    for (const auto& mat : model.materials) data.materials.push_back(materials.material(mat));
    // Walk the default scene applying node transforms: a forest (checked), so each node once.
    checkNodeForest(model, file);
    const std::vector<int> roots = defaultSceneRoots(model);
    checkDrawCount(model, roots, file);
    UndrawnFeatures undrawn;
    readPlacedMeshes(model, roots, file, data, undrawn);
    if (undrawn.skippedPrimitives)
        data.warnings.push_back(std::to_string(undrawn.skippedPrimitives) +
                                " point or line primitives are not drawn");
    if (undrawn.usesVertexColours)
        data.warnings.push_back("vertex colours (COLOR_0) are not drawn");
    if (data.primitives.empty()) fail(file, "no triangles to draw");
    return data;
}

size_t ModelData::vertexCount() const {
    size_t n = 0;
    for (const auto& p : primitives) n += p.mesh.vertices.size();
    return n;
}

glm::dvec3 ModelData::boundsMin() const {
    glm::dvec3 lo(std::numeric_limits<double>::infinity());
    for (const auto& p : primitives)
        for (const auto& v : p.mesh.vertices)
            lo = glm::min(lo, glm::dvec3(p.transform * glm::dvec4(glm::dvec3(v.position), 1)));
    return lo;
}

glm::dvec3 ModelData::boundsMax() const {
    glm::dvec3 hi(-std::numeric_limits<double>::infinity());
    for (const auto& p : primitives)
        for (const auto& v : p.mesh.vertices)
            hi = glm::max(hi, glm::dvec3(p.transform * glm::dvec4(glm::dvec3(v.position), 1)));
    return hi;
}

}  // namespace pbrlab
