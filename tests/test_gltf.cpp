// glTF loading: the project's own generated asset, tangent generation, and bad files as
// errors (a small deterministic fuzz run over truncations and byte flips).
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <random>

#include "assets/gltf.h"
#include "test_support.h"
#include "util/error.h"

using namespace pbrlab;
namespace fs = std::filesystem;

TEST(Gltf, GeneratedSphereGridHasTheLessonsLayout) {
    test::TempDir dir;
    writeSphereGridGlb(dir.path / "grid.glb");
    ModelData m = loadGltf(dir.path / "grid.glb");
    ASSERT_EQ(m.primitives.size(), 49u);
    ASSERT_EQ(m.materials.size(), 49u);
    EXPECT_EQ(m.meshCount, 49);
    EXPECT_EQ(m.images.size(), 0u);
    for (const auto& p : m.primitives) {
        const ModelMaterial& mat = m.materials.at(size_t(p.material));
        glm::dvec3 at(p.transform[3]);
        int col = int(std::lround(at.x / 2.5)) + 3, row = int(std::lround(at.y / 2.5)) + 3;
        EXPECT_NEAR(mat.metallicFactor, row / 7.0, 1e-6);
        EXPECT_NEAR(mat.roughnessFactor, std::clamp(col / 7.0, 0.05, 1.0), 1e-6);
        EXPECT_EQ(mat.baseColorFactor, glm::dvec4(0.5, 0, 0, 1));
        EXPECT_FALSE(p.generatedTangents);  // written with tangents
        EXPECT_EQ(p.mesh.indices.size() % 3, 0u);
    }
}

TEST(Gltf, GeneratedTangentsAreUnitPerpendicularAndFollowU) {
    MeshData sphere = makeUvSphere(32, 16);
    MeshData generated = sphere;
    generateTangents(generated);
    for (size_t i = 0; i < sphere.vertices.size(); ++i) {
        const Vertex& v = generated.vertices[i];
        glm::vec3 t(v.tangent);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(t, v.normal), 0.0f, 1e-5f);
        EXPECT_EQ(std::abs(v.tangent.w), 1.0f);
        // Away from the poles the analytic tangent (d position / du) is the answer.
        if (std::abs(v.normal.y) < 0.9f) {
            EXPECT_GT(glm::dot(t, glm::vec3(sphere.vertices[i].tangent)), 0.99f) << i;
            EXPECT_EQ(v.tangent.w, sphere.vertices[i].tangent.w) << i;
        }
    }
    // Mirrored uvs flip the handedness.
    MeshData mirrored = sphere;
    for (auto& v : mirrored.vertices) v.uv.x = 1 - v.uv.x;
    generateTangents(mirrored);
    EXPECT_EQ(mirrored.vertices[sphere.vertices.size() / 2].tangent.w, -1.0f);
}

TEST(Gltf, BrokenFilesAreErrorsNamingTheFile) {
    test::TempDir dir;
    writeSphereGridGlb(dir.path / "grid.glb");
    std::ifstream in(dir.path / "grid.glb", std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto expectError = [&](const std::string& content, const std::string& name) {
        fs::path f = dir.path / name;
        std::ofstream(f, std::ios::binary) << content;
        try {
            loadGltf(f);
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(f.string()), std::string::npos) << e.what();
            return true;
        }
        return false;
    };
    EXPECT_TRUE(expectError(bytes.substr(0, bytes.size() / 2), "half.glb"));
    EXPECT_TRUE(expectError(bytes.substr(0, 20), "header.glb"));
    EXPECT_TRUE(expectError("", "empty.glb"));
    EXPECT_TRUE(expectError("{ \"asset\": ", "cut.gltf"));
    EXPECT_THROW(loadGltf(dir.path / "missing.glb"), Error);
    // Fuzz: random truncations and byte flips must load or throw pbrlab::Error, never crash.
    std::mt19937 rng(7);
    for (int i = 0; i < 200; ++i) {
        std::string b = bytes;
        if (i % 2) b.resize(1 + rng() % (b.size() - 1));  // never empty: flips need a byte
        for (int k = 0; k < 8; ++k) b[rng() % b.size()] = char(rng());
        fs::path f = dir.path / "fuzz.glb";
        std::ofstream(f, std::ios::binary) << b;
        try {
            loadGltf(f);
        } catch (const Error&) {
        }
    }
}

TEST(Gltf, LoadsTheSharedTangentTestModelWhenPresent) {
    fs::path file = fs::path(PBRLAB_SOURCE_DIR) / "../shared/data/gltf/NormalTangentTest.glb";
    if (!fs::exists(file)) GTEST_SKIP() << "shared data absent";
    ModelData m = loadGltf(file);
    EXPECT_FALSE(m.primitives.empty());
    EXPECT_FALSE(m.materials.empty());
    EXPECT_GE(m.materials[0].normalTexture.image, 0);
}

namespace {

// The message of loadGltf(file)'s error ("" when it loads), and that it came back at all in a
// generous bound: a node loop once ran for a minute and 20 GB before failing.
std::string gltfError(const fs::path& file) {
    const auto start = std::chrono::steady_clock::now();
    std::string message;
    try {
        loadGltf(file);
    } catch (const Error& e) {
        message = e.what();
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20)) << file;
    return message;
}

// dir/name, a .gltf of one triangle (its buffer dir/tri.bin, named by `bufferUri`) drawn by
// `nodes`, with `scenes` and `images`.
fs::path writeNodesGltf(const fs::path& dir, const std::string& name, const std::string& nodes,
                        const std::string& scenes = R"([{"nodes": [0]}])",
                        const std::string& bufferUri = "tri.bin",
                        const std::string& images = "[]") {
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    fs::create_directories(dir);
    std::ofstream(dir / "tri.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(positions), sizeof positions);
    std::ofstream(dir / name, std::ios::binary) << R"({"asset": {"version": "2.0"},
  "buffers": [{"uri": ")" + bufferUri + R"(", "byteLength": 36}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "images": )" + images + R"(,
  "nodes": )" + nodes + R"(, "scenes": )" + scenes + R"(, "scene": 0})";
    return dir / name;
}

}  // namespace

TEST(Gltf, NodeLoopsAndSharedNodesAreErrorsNamingTheNodes) {
    test::TempDir dir;
    auto expect = [&](const std::string& name, const std::string& nodes, const std::string& scenes,
                      const std::vector<std::string>& said) {
        const fs::path file = writeNodesGltf(dir.path, name, nodes, scenes);
        const std::string m = gltfError(file);
        EXPECT_NE(m.find(file.string()), std::string::npos) << m;
        for (const std::string& s : said) EXPECT_NE(m.find(s), std::string::npos) << m;
    };
    expect("self.gltf", R"([{"name": "knot", "mesh": 0, "children": [0]}])", R"([{"nodes": [0]}])",
           {"node 0 ('knot') lists itself as a child", "node 0 ('knot') -> node 0 ('knot')"});
    expect("two.gltf", R"([{"mesh": 0, "children": [1]}, {"mesh": 0, "children": [0]}])",
           R"([{"nodes": [0]}])", {"the nodes loop: node 0 -> node 1 -> node 0"});
    // A loop no scene reaches is refused all the same.
    expect("three.gltf",
           R"([{"mesh": 0}, {"children": [2]}, {"children": [3]}, {"children": [1]}])",
           R"([{"nodes": [0]}])", {"the nodes loop: node 1 -> node 2 -> node 3 -> node 1"});
    expect("shared.gltf", R"([{"children": [2]}, {"children": [2]}, {"name": "wheel", "mesh": 0}])",
           R"([{"nodes": [0, 1]}])", {"node 2 ('wheel') has two parents, node 0 and node 1"});
    expect("twice.gltf", R"([{"children": [1, 1]}, {"mesh": 0}])", R"([{"nodes": [0]}])",
           {"node 0 lists node 1 twice as a child"});
    // Each node listing the next twice: 2^40 paths walked as given.
    std::string doubling = "[";
    for (int i = 0; i < 40; ++i)
        doubling += R"({"mesh": 0, "children": [)" + std::to_string(i + 1) + ", " +
                    std::to_string(i + 1) + "]}, ";
    expect("doubling.gltf", doubling + R"({"mesh": 0}])", R"([{"nodes": [0]}])",
           {"node 0 lists node 1 twice as a child"});
    expect("roots.gltf", R"([{"mesh": 0}])", R"([{"nodes": [0, 0]}])",
           {"scene 0 lists node 0 twice"});
    expect("rootchild.gltf", R"([{"children": [1]}, {"mesh": 0}])", R"([{"nodes": [0, 1]}])",
           {"scene 0 lists node 1 as a root, but it is a child of node 0"});
    expect("nochild.gltf", R"([{"children": [7]}])", R"([{"nodes": [0]}])",
           {"node 0 lists child 7, which does not exist"});
    // A node in two scenes is allowed (the default scene is drawn), as is a deep chain.
    std::string chain = "[";
    for (int i = 0; i < 5000; ++i) chain += R"({"children": [)" + std::to_string(i + 1) + "]}, ";
    EXPECT_EQ(gltfError(writeNodesGltf(dir.path, "chain.gltf", chain + R"({"mesh": 0}])")), "");
    EXPECT_EQ(gltfError(writeNodesGltf(dir.path, "scenes.gltf", R"([{"mesh": 0}])",
                                       R"([{"nodes": [0]}, {"nodes": [0]}])")),
              "");
}

TEST(Gltf, FilesOutsideTheModelsFolderAreRefusedNotRead) {
    test::TempDir dir;
    // The model in dir/model/; a readable buffer and image beside that folder, in dir.
    const fs::path model = dir.path / "model";
    writeNodesGltf(dir.path, "unused.gltf", "[]");  // dir/tri.bin
    dir.write("secret.png", "\x89PNG\r\n\x1a\n");
    auto refused = [&](const std::string& bufferUri, const std::string& images,
                       const std::string& said) {
        const fs::path file = writeNodesGltf(model, "m.gltf", R"([{"mesh": 0}])",
                                             R"([{"nodes": [0]}])", bufferUri, images);
        const std::string m = gltfError(file);
        EXPECT_NE(m.find(file.string()), std::string::npos) << m;
        EXPECT_NE(m.find(said + ": refused"), std::string::npos) << m;
        EXPECT_NE(m.find("lies outside the model's folder " + model.string()), std::string::npos)
            << m;
        EXPECT_EQ(m.find("not found"), std::string::npos) << m;
    };
    const std::string absolute = (dir.path / "tri.bin").string();
    refused(absolute, "[]", "buffer 0 ('" + absolute + "')");
    refused("/etc/passwd", "[]", "buffer 0 ('/etc/passwd')");
    refused("../tri.bin", "[]", "buffer 0 ('../tri.bin')");
    refused("sub/../../tri.bin", "[]", "buffer 0 ('sub/../../tri.bin')");
    refused("%2E%2E/tri.bin", "[]", "buffer 0 ('%2E%2E/tri.bin')");
    refused("tri.bin", R"([{"uri": "../secret.png"}])", "image 0 ('../secret.png')");
    // A link beside the model that leads out of its folder is outside too.
    fs::create_symlink(dir.path / "tri.bin", model / "link.bin");
    refused("link.bin", "[]", "buffer 0 ('link.bin')");
    // Beside it, in a folder below it, or percent-encoded: read.
    EXPECT_EQ(gltfError(writeNodesGltf(model, "m.gltf", R"([{"mesh": 0}])")), "");
    fs::create_directories(model / "data dir");
    fs::copy_file(model / "tri.bin", model / "data dir/tri.bin");
    EXPECT_EQ(gltfError(writeNodesGltf(model, "m.gltf", R"([{"mesh": 0}])", R"([{"nodes": [0]}])",
                                       "data%20dir/./tri.bin")),
              "");
    // tinygltf looks in the working directory for a file its model's folder lacks: not here.
    writeNodesGltf(model, "m.gltf", R"([{"mesh": 0}])");
    fs::remove(model / "tri.bin");
    const fs::path cwd = fs::current_path();
    fs::current_path(dir.path);  // which holds a tri.bin
    const std::string m = gltfError(model / "m.gltf");
    fs::current_path(cwd);
    EXPECT_NE(m.find("tri.bin"), std::string::npos) << m;
}

TEST(Gltf, ModelsDrawingMoreThanTheLimitAreRefused) {
    test::TempDir dir;
    auto nodes = [](size_t count) {
        std::string list = "[", roots = "[";
        for (size_t i = 0; i < count; ++i) {
            list += std::string(i ? ", " : "") + R"({"mesh": 0})";
            roots += (i ? ", " : "") + std::to_string(i);
        }
        return std::pair{list + "]", R"([{"nodes": )" + roots + "]}]"};
    };
    auto [over, overScenes] = nodes(kMaxDrawnMeshes + 1);
    const fs::path file = writeNodesGltf(dir.path, "many.gltf", over, overScenes);
    const std::string m = gltfError(file);
    EXPECT_NE(m.find(file.string()), std::string::npos) << m;
    EXPECT_NE(m.find("draws " + std::to_string(kMaxDrawnMeshes + 1) + " primitives"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("at most " + std::to_string(kMaxDrawnMeshes)), std::string::npos) << m;
    auto [at, atScenes] = nodes(kMaxDrawnMeshes);
    EXPECT_EQ(loadGltf(writeNodesGltf(dir.path, "limit.gltf", at, atScenes)).primitives.size(),
              kMaxDrawnMeshes);
}
