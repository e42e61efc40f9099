// The G-buffer pass of LabRenderer: a scene's draws into kGBufferTextures float targets, the
// materials' maps read and uploaded on first use, and the disk cache of G-buffers that read no
// image.
#include <algorithm>
#include <array>
#include <chrono>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <numbers>

#include "render/renderer.h"
#include "render/surface_io.h"
#include "util/cache_file.h"
#include "util/color.h"
#include "util/digest.h"
#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// The built-in unit sphere of JSON scenes (DrawItem::mesh == nullptr).
constexpr int kSphereSegments = 96;
const MeshData& unitSphere() {
    static const MeshData sphere = makeUvSphere(kSphereSegments, kSphereSegments / 2);
    return sphere;
}

// The radius in pixels of a built-in sphere drawn with `transform` (a unit sphere placed and
// scaled), seen from `camera` in a picture `height` pixels high; infinite (the full sphere)
// when the camera is inside it.
double sphereRadiusPixels(const glm::dmat4& transform, const Camera& camera, int height) {
    const double radius =
        std::max({glm::length(glm::dvec3(transform[0])), glm::length(glm::dvec3(transform[1])),
                  glm::length(glm::dvec3(transform[2]))});
    const glm::dvec3 toCentre = glm::dvec3(transform[3]) - camera.position;
    const double d2 = glm::dot(toCentre, toCentre) - radius * radius;  // tangent length^2
    if (d2 <= 0) return std::numeric_limits<double>::infinity();
    // tan of the angle the sphere subtends, over tan of half the field of view, times half
    // the height; doubled, a margin over the stretch towards the picture's corners (1.2 at a
    // field of view of 45 degrees).
    const double halfFov = std::tan(glm::radians(camera.fovY) / 2);
    return 2 * radius / std::sqrt(d2) / halfFov * height / 2;
}

GLint glWrap(TextureSource::Wrap wrap) {
    switch (wrap) {
        case TextureSource::Wrap::Clamp:
            return GL_CLAMP_TO_EDGE;
        case TextureSource::Wrap::Mirror:
            return GL_MIRRORED_REPEAT;
        case TextureSource::Wrap::Repeat:
            break;
    }
    return GL_REPEAT;
}

}  // namespace

GLuint LabRenderer::texture(const TextureSource& source) {
    auto it = textures_.find(source.key);
    if (it != textures_.end()) return it->second.id();
    auto start = std::chrono::steady_clock::now();
    Image image = readTexture(source);
    GLuint id = textures_.emplace(source.key, gl::uploadTexture(image, true)).first->second.id();
    countEvent(Counter::TextureLoads);
    double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    logLine("texture", source.key + " " + std::to_string(image.width) + "x" +
                           std::to_string(image.height) + " " +
                           std::to_string(image.sourceBitsPerChannel) + "-bit, " +
                           std::to_string(ms) + " ms");
    return id;
}

// A chord spanning 2 pi / n of a circle of radius r strays r (1 - cos(pi / n)), about
// r pi^2 / (2 n^2), from it: within half a pixel when n >= pi sqrt(r). The normals interpolated
// between the vertices' are the sphere's at the point drawn, which is as near the round
// sphere's: the shading moves by under a pixel with the outline (tests/test_live_view.cpp).
int sphereSegments(double radiusPixels) {
    for (int n : {16, 24, 32, 48, 64})
        if (n >= std::numbers::pi * std::sqrt(radiusPixels)) return n;
    return kSphereSegments;
}

const gl::GpuMesh& LabRenderer::mesh(const MeshData* data) {
    auto& slot = meshes_[data];
    if (!slot) slot = std::make_unique<gl::GpuMesh>(data ? *data : unitSphere());
    return *slot;
}

ProgramRecipe LabRenderer::gbufferRecipe(const MaterialDesc& m, unsigned needs) const {
    ProgramRecipe recipe;
    recipe.label = "G-buffer";
    recipe.vertex = {paths_.shaders() / "gbuffer.vert"};
    recipe.fragment = {paths_.shaders() / "gbuffer.frag"};
    for (const MaterialMap& map : materialMaps(m))
        if ((needs & map.need) && !map.source->empty()) recipe.defines[map.define] = "1";
    return recipe;
}

std::vector<LabRenderer::MaterialMap> LabRenderer::materialMaps(const MaterialDesc& m) {
    return {{NeedsAlbedo, &m.albedoMap, "HAS_ALBEDO_MAP", "uAlbedoMap"},
            {NeedsMetallic | NeedsRoughness, &m.metallicRoughnessMap, "HAS_METALLIC_ROUGHNESS_MAP",
             "uMetallicRoughnessMap"},
            {NeedsRoughness, &m.roughnessMap, "HAS_ROUGHNESS_MAP", "uRoughnessMap"},
            {NeedsMetallic, &m.metallicMap, "HAS_METALLIC_MAP", "uMetallicMap"},
            {NeedsAo, &m.aoMap, "HAS_AO_MAP", "uAoMap"},
            {NeedsNormalMap, &m.normalMap, "HAS_NORMAL_MAP", "uNormalMap"},
            {NeedsEmissive, &m.emissiveMap, "HAS_EMISSIVE_MAP", "uEmissiveMap"}};
}

namespace {

// The camera's view-projection for a picture of this size. Near and far planes from the
// camera's distance, so models of any size keep depth precision (a unit sphere at distance 3:
// 0.05 .. 200, as before).
glm::mat4 gbufferViewProjection(const Camera& cam, int width, int height) {
    const double distance = glm::length(cam.position - cam.target);
    glm::mat4 view =
        glm::lookAt(glm::vec3(cam.position), glm::vec3(cam.target), glm::vec3(0, 1, 0));
    glm::mat4 proj = glm::perspective(glm::radians(float(cam.fovY)), float(width) / float(height),
                                      float(distance / 60), float(distance * 60));
    return proj * view;
}

// A draw's transforms and its material's factors, as the G-buffer program reads them.
void setMaterialUniforms(const Program& program, const glm::mat4& model,
                         const glm::mat4& viewProjection, const MaterialDesc& m) {
    program.set("uModel", model);
    glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
    gl::UniformMatrix3fv(program.location("uNormalMatrix"), 1, GL_FALSE, &normalMatrix[0][0]);
    program.set("uViewProjection", viewProjection);
    program.set("uAlbedo", glm::vec3(m.albedo));
    // The albedo factor as an sRGB texture would store it (exact curve, no 8-bit rounding).
    program.set("uAlbedoTexel",
                glm::vec3(srgbEncode(m.albedo.r), srgbEncode(m.albedo.g), srgbEncode(m.albedo.b)));
    program.set("uMetallic", float(m.metallic));
    program.set("uRoughness", float(m.roughness));
    program.set("uAo", float(m.ao));
    program.set("uOcclusionStrength", float(m.occlusionStrength));
    program.set("uNormalScale", float(m.normalScale));
    program.set("uEmissive", glm::vec3(m.emissive));
}

}  // namespace

// The material's maps that the program compiled in, each on a unit of its own.
void LabRenderer::bindMaterialMaps(const Program& program, const MaterialDesc& m) {
    int unit = 0;
    for (const MaterialMap& map : materialMaps(m)) {
        if (!program.uses(map.sampler)) continue;  // not compiled in: never loaded
        gl::ActiveTexture(GL_TEXTURE0 + unit);
        gl::BindTexture(GL_TEXTURE_2D, texture(*map.source));
        // Wrapping is the map's, not the image's (two maps may share one image).
        gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, glWrap(map.source->wrapU));
        gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, glWrap(map.source->wrapV));
        program.set(map.sampler, unit++);
    }
}

// A draw's mesh: a built-in sphere with fewer segments where coarse spheres are asked for and
// keep its outline, else the full mesh.
void LabRenderer::drawItemMesh(const DrawItem& item, const Camera& camera, int height,
                               bool coarseSpheres) {
    const int segments = coarseSpheres && !item.mesh
                             ? sphereSegments(sphereRadiusPixels(item.transform, camera, height))
                             : kSphereSegments;
    if (segments < kSphereSegments) {
        auto& sphere = coarseSpheres_[segments];
        if (!sphere) sphere = std::make_unique<gl::GpuMesh>(makeUvSphere(segments, segments / 2));
        sphere->draw();
    } else {
        mesh(item.mesh).draw();
    }
}

glm::mat4 LabRenderer::drawGBuffer(const Scene& scene, unsigned needs, int width, int height,
                                   const RenderRequest& request) {
    const bool coarseSpheres = request.coarseSpheres;
    std::unique_ptr<gl::RenderTarget>& target = gbufferFor(coarseSpheres);
    if (!target || target->width() != width || target->height() != height) {
        target = std::make_unique<gl::RenderTarget>(width, height, kGBufferTextures);
        if (!coarseSpheres) gbufferHolds_.clear();
    }
    const glm::mat4 viewProjection = gbufferViewProjection(scene.camera, width, height);
    for (const SceneModel& model : scene.models) keepModels_.insert(model.data);

    const std::vector<DrawItem> items = drawItems(scene);
    const std::string key = (request.cacheGBuffer || request.reuseGBuffer) && !coarseSpheres
                                ? gbufferKey(scene, items, needs, viewProjection)
                                : std::string();
    const fs::path file = request.cacheGBuffer && !key.empty() && !options_.cacheRoot.empty()
                              ? options_.cacheRoot / "gbuffer" / (key + ".bin")
                              : fs::path();
    if (!key.empty() && (key == gbufferHolds_ || (!file.empty() && readGBuffer(file)))) {
        gbufferHolds_ = key;
        // Compiled all the same: what a scene compiles stays observable (--stats, the GUI).
        programs_.get(gbufferRecipe(scene.materials.at(size_t(items[0].material)), needs));
        return viewProjection;
    }
    target->bind();
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < kGBufferTextures; ++i) gl::ClearBufferfv(GL_COLOR, i, zero);
    gl::Clear(GL_DEPTH_BUFFER_BIT);
    gl::Enable(GL_DEPTH_TEST);
    gl::DepthFunc(GL_LESS);
    for (const DrawItem& item : items) {
        const MaterialDesc& m = scene.materials.at(size_t(item.material));
        auto program = programs_.get(gbufferRecipe(m, needs));
        program->use();
        setMaterialUniforms(*program, glm::mat4(item.transform), viewProjection, m);
        bindMaterialMaps(*program, m);
        drawItemMesh(item, scene.camera, height, coarseSpheres);
    }
    gl::Disable(GL_DEPTH_TEST);
    gl::checkError("G-buffer pass");
    if (!file.empty()) writeGBuffer(file);
    if (!coarseSpheres) gbufferHolds_ = key;
    return viewProjection;
}

// The G-buffer is a pure function of the program's source, the meshes, each item's transform
// and material factors, the camera, the size, the code that turns them into draws (the
// executable's build ID) and the GL driver; all of them are the key. Only draws that read no
// image: a map would bring the image decoder into the key.
std::string LabRenderer::gbufferKey(const Scene& scene, const std::vector<DrawItem>& items,
                                    unsigned needs, const glm::mat4& viewProjection) {
    if (items.empty()) return {};
    const ProgramRecipe recipe =
        gbufferRecipe(scene.materials.at(size_t(items[0].material)), needs);
    for (const DrawItem& item : items)
        if (!gbufferRecipe(scene.materials.at(size_t(item.material)), needs).defines.empty())
            return {};  // a map is read
    static const std::string code = buildIds({""});
    if (code.empty()) return {};
    Digest key;
    key.add(std::string("G-buffer v1"));
    key.add(code);
    for (GLenum name : {GL_VENDOR, GL_RENDERER, GL_VERSION})
        key.add(std::string(reinterpret_cast<const char*>(gl::GetString(name))));
    key.add(std::array<int, 2>{gbuffer_->width(), gbuffer_->height()});
    key.add(viewProjection);
    key.add(programs_.preprocessor().expand(recipe.vertex, recipe.defines).text);
    key.add(programs_.preprocessor().expand(recipe.fragment, recipe.defines).text);
    for (const DrawItem& item : items) {
        const MaterialDesc& m = scene.materials.at(size_t(item.material));
        key.add(item.transform);
        key.add(m.albedo), key.add(m.metallic), key.add(m.roughness), key.add(m.ao);
        key.add(m.occlusionStrength), key.add(m.normalScale), key.add(m.emissive);
        auto [digest, missing] = meshDigests_.try_emplace(item.mesh, 0);
        if (missing) {
            const MeshData& mesh = item.mesh ? *item.mesh : unitSphere();
            Digest d;
            d.add(mesh.vertices.data(), mesh.vertices.size() * sizeof(Vertex));
            d.add(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t));
            digest->second = d.h;
        }
        key.add(digest->second);
    }
    return key.hex();
}

namespace {

// Cached G-buffers on disk: "PBRLGBF1", width, height, attachment count, the attachments' RGBA
// floats (row 0 at the top, as read back) and a digest of them (a torn file is drawn again).
constexpr char kGBufferMagic[8] = {'P', 'B', 'R', 'L', 'G', 'B', 'F', '2'};

}  // namespace

bool LabRenderer::readGBuffer(const fs::path& file) {
    CacheReader in(file, kGBufferMagic);
    std::int32_t size[3] = {0, 0, 0};
    if (!in.get(size) || size[0] != gbuffer_->width() || size[1] != gbuffer_->height() ||
        size[2] != kGBufferTextures)
        return false;
    std::vector<Image> images(kGBufferTextures);
    for (Image& image : images) {
        image.width = size[0];
        image.height = size[1];
        image.channels = 4;
        if (!in.floats(image.pixels, size_t(size[0]) * size_t(size[1]) * 4)) return false;
    }
    if (!in.atEnd()) return false;
    for (int i = 0; i < kGBufferTextures; ++i) {
        // The attachments' storage is respecified with the same size and format.
        gl::BindTexture(GL_TEXTURE_2D, gbuffer_->colorTexture(i));
        gl::TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, size[0], size[1], 0, GL_RGBA, GL_FLOAT,
                       flipRows(images[size_t(i)]).pixels.data());
    }
    gl::checkError("G-buffer from the cache");
    logLine("gbuffer", "from " + file.string());
    return true;
}

void LabRenderer::writeGBuffer(const fs::path& file) const {
    CacheWriter out(kGBufferMagic);
    out.put(std::array<std::int32_t, 3>{gbuffer_->width(), gbuffer_->height(), kGBufferTextures});
    for (int i = 0; i < kGBufferTextures; ++i) {
        const Image image = gbuffer_->read(i);
        out.bytes(image.pixels.data(), image.pixels.size() * sizeof(float));
    }
    out.commit(file);
}

}  // namespace pbrlab
