#include "renderer.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "cache_file.h"
#include "digest.h"
#include "pbrlab/color.h"
#include "pbrlab/contract.h"
#include "pbrlab/envgen.h"
#include "pbrlab/error.h"
#include "pbrlab/log.h"
#include "surface_io.h"

#ifndef PBRLAB_SOURCE_DIR
#error "PBRLAB_SOURCE_DIR must name the source tree"
#endif

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// What a scene's environment maps are kept by: their source and every setting they depend on.
std::string environmentKey(const Scene& scene, const IblSettings& settings) {
    return scene.environment + "|" + settings.key();
}

// The built-in unit sphere of JSON scenes (DrawItem::mesh == nullptr).
const MeshData& unitSphere() {
    static const MeshData sphere = makeUvSphere(96, 48);
    return sphere;
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

Scene applyParamBindings(Scene scene, const ModuleDesc& module, const ParamValues& values) {
    for (const auto& p : module.params)
        // A binding moves the scene only once the value leaves its default, so every module's
        // default view shows the scene as authored.
        if (p.binding == ParamBinding::LightDirection && !scene.lights.empty() &&
            values.vector(p.name) != p.defaultValue) {
            double distance = glm::length(scene.lights[0].position);
            scene.lights[0].position = values.vector(p.name) * (distance > 0 ? distance : 10.0);
        }
    return scene;
}

LabRenderer::LabRenderer(const DataPaths& paths, RendererOptions options)
    : paths_(paths),
      options_(std::move(options)),
      programs_(ShaderPreprocessor({paths.shaders(), paths.labs()})) {}

std::string parameterUniforms(const ModuleDesc& d) {
    std::string text;
    for (const ParamDecl& p : d.params) {
        const char* type = "float";
        switch (p.type) {
            case ParamType::Float:
                type = "float";
                break;
            case ParamType::Int:
            case ParamType::Bool:
            case ParamType::Enum:
                type = "int";
                break;
            case ParamType::Color:
            case ParamType::Direction:
                type = "vec3";
                break;
        }
        text += std::string("uniform ") + type + " " + p.uniformName() + ";\n";
    }
    return text;
}

ProgramRecipe LabRenderer::viewRecipe(const LoadedModule& module, const StudentSource& source,
                                      bool probe, int lightCount, const std::string& view) const {
    ProgramRecipe r;
    const ModuleDesc& d = *module.desc;
    r.label = "view " + d.id + (view.empty() ? "" : " (" + view + ")");
    r.vertex = {paths_.shaders() / "fullscreen.vert"};
    r.fragment.push_back(paths_.shaders() / "common.glsl");
    // The contract's promise: every contract function is callable from every step's file.
    // Prototypes first, so a step may call one that is defined after it.
    r.fragment.push_back(ShaderPart("<contract prototypes>", contractPrototypes()));
    r.fragment.push_back(paths_.shaders() / "fresnel_roughness.glsl");
    for (const ContractStep& step : contractSteps()) {
        ShaderPart part(step.folder / "solution.glsl");
        if (!source.dir.empty() && (step.id == d.id || source.cumulative)) {
            fs::path student = source.dir / (step.id + ".glsl");
            std::error_code ec;
            if (fs::exists(student, ec) || fs::is_symlink(student, ec)) {
                if (!isInside(student, source.dir))
                    throw Error(student.string() + ": refused, it points outside " +
                                source.dir.string());
                part = ShaderPart(student);
                part.includeRoots = {source.dir};  // never the reference solutions
            }
        }
        r.fragment.push_back(part);
    }
    r.fragment.push_back(paths_.shaders() / "surface.glsl");
    // The step's parameters, declared from its descriptor (set in runView): a view reads
    // u_<name> without declaring it.
    r.fragment.push_back(ShaderPart("<parameters of " + d.id + ">", parameterUniforms(d)));
    r.fragment.push_back(module.sourceDir / (view.empty() ? "view.glsl" : view + ".glsl"));
    r.fragment.push_back(paths_.shaders() / "view_main.frag");
    r.defines["NUM_LIGHTS"] = std::to_string(std::max(lightCount, 1));
    if (probe) r.defines["PBRLAB_PROBE"] = "1";
    // Every program declares the IBL samplers (contract names any step may call through the
    // IBL functions); only what the step may read is bound (see runView).
    r.defines["PBRLAB_IBL"] = "1";
    if ((d.needs & NeedsEnvironment) && d.skyBackground && !probe) r.defines["PBRLAB_SKY"] = "1";
    return r;
}

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

glm::mat4 LabRenderer::drawGBuffer(const Scene& scene, unsigned needs, int width, int height,
                                   bool cache) {
    if (!gbuffer_ || gbuffer_->width() != width || gbuffer_->height() != height) {
        gbuffer_ = std::make_unique<gl::RenderTarget>(width, height, kGBufferTextures);
        gbufferHolds_.clear();
    }
    const Camera& cam = scene.camera;
    // Near and far planes from the camera's distance, so models of any size keep depth
    // precision (a unit sphere at distance 3: 0.05 .. 200, as before).
    const double distance = glm::length(cam.position - cam.target);
    glm::mat4 view =
        glm::lookAt(glm::vec3(cam.position), glm::vec3(cam.target), glm::vec3(0, 1, 0));
    glm::mat4 proj = glm::perspective(glm::radians(float(cam.fovY)), float(width) / float(height),
                                      float(distance / 60), float(distance * 60));
    const glm::mat4 viewProjection = proj * view;
    for (const SceneModel& model : scene.models) keepModels_.insert(model.data);

    const std::vector<DrawItem> items = drawItems(scene);
    const fs::path cached =
        cache ? gbufferCacheFile(scene, items, needs, viewProjection) : fs::path();
    if (!cached.empty() && (cached == gbufferHolds_ || readGBuffer(cached))) {
        gbufferHolds_ = cached;
        // Compiled all the same: what a scene compiles stays observable (--stats, the GUI).
        programs_.get(gbufferRecipe(scene.materials.at(size_t(items[0].material)), needs));
        return viewProjection;
    }
    gbuffer_->bind();
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < kGBufferTextures; ++i) gl::ClearBufferfv(GL_COLOR, i, zero);
    gl::Clear(GL_DEPTH_BUFFER_BIT);
    gl::Enable(GL_DEPTH_TEST);
    gl::DepthFunc(GL_LESS);
    for (const DrawItem& item : items) {
        const MaterialDesc& m = scene.materials.at(size_t(item.material));
        auto program = programs_.get(gbufferRecipe(m, needs));
        program->use();
        const glm::mat4 model(item.transform);
        program->set("uModel", model);
        glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
        gl::UniformMatrix3fv(program->location("uNormalMatrix"), 1, GL_FALSE, &normalMatrix[0][0]);
        program->set("uViewProjection", viewProjection);
        program->set("uAlbedo", glm::vec3(m.albedo));
        // The albedo factor as an sRGB texture would store it (exact curve, no 8-bit rounding).
        program->set("uAlbedoTexel", glm::vec3(srgbEncode(m.albedo.r), srgbEncode(m.albedo.g),
                                               srgbEncode(m.albedo.b)));
        program->set("uMetallic", float(m.metallic));
        program->set("uRoughness", float(m.roughness));
        program->set("uAo", float(m.ao));
        program->set("uOcclusionStrength", float(m.occlusionStrength));
        program->set("uNormalScale", float(m.normalScale));
        program->set("uEmissive", glm::vec3(m.emissive));
        int unit = 0;
        for (const MaterialMap& map : materialMaps(m)) {
            if (!program->uses(map.sampler)) continue;  // not compiled in: never loaded
            gl::ActiveTexture(GL_TEXTURE0 + unit);
            gl::BindTexture(GL_TEXTURE_2D, texture(*map.source));
            // Wrapping is the map's, not the image's (two maps may share one image).
            gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, glWrap(map.source->wrapU));
            gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, glWrap(map.source->wrapV));
            program->set(map.sampler, unit++);
        }
        mesh(item.mesh).draw();
    }
    gl::Disable(GL_DEPTH_TEST);
    gl::checkError("G-buffer pass");
    if (!cached.empty()) writeGBuffer(cached);
    gbufferHolds_ = cached;
    return viewProjection;
}

// The G-buffer is a pure function of the program's source, the meshes, each item's transform
// and material factors, the camera, the size, the code that turns them into draws (the
// executable's build ID) and the GL driver; all of them are the key. Only draws that read no
// image: a map would bring the image decoder into the key.
fs::path LabRenderer::gbufferCacheFile(const Scene& scene, const std::vector<DrawItem>& items,
                                       unsigned needs, const glm::mat4& viewProjection) {
    if (options_.cacheRoot.empty() || items.empty()) return {};
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
    return options_.cacheRoot / "gbuffer" / (key.hex() + ".bin");
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
        image.pixels.resize(size_t(size[0]) * size_t(size[1]) * 4);
        if (!in.bytes(image.pixels.data(), image.pixels.size() * sizeof(float))) return false;
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

bool LabRenderer::mayRead(const ModuleDesc& d, const std::string& sampler) {
    if (!(d.needs & NeedsEnvironment)) return false;
    if (sampler == "uEnvironment") return true;
    for (const DerivedMap& map : kDerivedMaps)
        if (sampler == map.sampler) {
            // A map no step declares is the host's alone: any step that needs the environment
            // may read it.
            const ContractStep* producer = findProvider(sampler);
            return !producer || producer->step < d.step;
        }
    return false;
}

std::vector<std::string> LabRenderer::forbiddenSamplers(const ModuleDesc& d,
                                                        const Program& program) {
    std::vector<std::string> out;
    if (program.uses("uEnvironment") && !mayRead(d, "uEnvironment")) out.push_back("uEnvironment");
    for (const DerivedMap& map : kDerivedMaps)
        if (program.uses(map.sampler) && !mayRead(d, map.sampler)) out.push_back(map.sampler);
    return out;
}

GLuint LabRenderer::blackTexture(GLenum target) {
    gl::Handle& slot = target == GL_TEXTURE_CUBE_MAP ? blackCube_ : black2d_;
    if (!slot.id()) {
        slot = gl::makeTexture();
        gl::BindTexture(target, slot.id());
        const float black[4] = {0, 0, 0, 0};
        if (target == GL_TEXTURE_CUBE_MAP)
            for (int face = 0; face < 6; ++face)
                gl::TexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, 0, GL_RGBA32F, 1, 1, 0,
                               GL_RGBA, GL_FLOAT, black);
        else
            gl::TexImage2D(target, 0, GL_RGBA32F, 1, 1, 0, GL_RGBA, GL_FLOAT, black);
        gl::TexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl::TexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl::TexParameteri(target, GL_TEXTURE_MAX_LEVEL, 0);
    }
    return slot.id();
}

double LabRenderer::runView(const RenderRequest& request, const Scene& scene, bool probe,
                            const std::vector<GLuint>& inputs, int width, int height,
                            const glm::mat4& viewProjection) {
    const LoadedModule& module = *request.module;
    const ModuleDesc& d = *module.desc;
    // reloadIfChanged: an edited student file is recompiled; if that fails, the error is thrown
    // and the last good program stays cached for the next call.
    auto program = programs_.reloadIfChanged(
        viewRecipe(module, request.source, probe, int(scene.lights.size()), request.view));
    // The environment and the maps the view may read, built before anything is bound (the
    // precompute passes use the texture units). A derived map is readable only by steps after
    // the one whose reference solution computes it; every other sampler the program uses
    // reads black (the contract declares them all).
    struct Binding {
        const char* name;
        GLenum target;
        GLuint texture;
    };
    std::vector<Binding> bindings;
    if (program->uses("uEnvironment"))
        bindings.push_back({"uEnvironment", GL_TEXTURE_CUBE_MAP,
                            mayRead(d, "uEnvironment")
                                ? environment(scene, request.ibl, false).maps->environment.id()
                                : 0});
    for (const DerivedMap& map : kDerivedMaps) {
        if (!program->uses(map.sampler)) continue;
        const GLenum target =
            std::string(map.sampler) == "uBrdfLut" ? GL_TEXTURE_2D : GL_TEXTURE_CUBE_MAP;
        GLuint texture = 0;
        if (mayRead(d, map.sampler)) {
            const IblMaps& maps = *environment(scene, request.ibl, true).maps;
            texture = target == GL_TEXTURE_2D                        ? maps.lut.id()
                      : std::string(map.sampler) == "uIrradianceMap" ? maps.irradiance.id()
                                                                     : maps.prefilter.id();
        }
        bindings.push_back({map.sampler, target, texture});
    }
    for (Binding& b : bindings)
        if (!b.texture) b.texture = blackTexture(b.target);
    if (!valueTarget_ || valueTarget_->width() != width || valueTarget_->height() != height)
        valueTarget_ = std::make_unique<gl::RenderTarget>(width, height, 1, false);
    valueTarget_->bind();
    program->use();
    for (size_t i = 0; i < inputs.size(); ++i) {
        gl::ActiveTexture(GLenum(GL_TEXTURE0 + i));
        gl::BindTexture(GL_TEXTURE_2D, inputs[i]);
        program->set("uSurface" + std::to_string(i), int(i));
    }
    std::vector<glm::vec3> positions, colors;
    for (const auto& l : scene.lights) {
        positions.emplace_back(l.position);
        colors.emplace_back(l.color);
    }
    program->set("uLightPositions", positions);
    program->set("uLightColors", colors);
    if (program->uses("uCameraPosition"))
        program->set("uCameraPosition", glm::vec3(scene.camera.position));
    int unit = int(inputs.size());
    for (const Binding& b : bindings) {
        gl::ActiveTexture(GLenum(GL_TEXTURE0 + unit));
        gl::BindTexture(b.target, b.texture);
        program->set(b.name, unit++);
    }
    if (program->uses("uPrefilterMaxLod")) {
        const auto it = environments_.find(environmentKey(scene, request.ibl));
        const bool derived =
            it != environments_.end() && it->second.maps && it->second.maps->derived;
        program->set("uPrefilterMaxLod", derived ? it->second.maps->prefilterMaxLod : 0.f);
    }
    if (program->uses("uInverseViewProjection")) {
        program->set("uInverseViewProjection", glm::inverse(viewProjection));
        program->set("uViewportSize", glm::vec2(float(width), float(height)));
    }
    for (const ParamDecl& p : d.params) {
        glm::dvec3 v = request.params->vector(p.name);
        const std::string u = p.uniformName();
        switch (p.type) {
            case ParamType::Float:
                program->set(u, float(v.x));
                break;
            case ParamType::Int:
            case ParamType::Bool:
            case ParamType::Enum:
                program->set(u, int(v.x));
                break;
            case ParamType::Color:
            case ParamType::Direction:
                program->set(u, glm::vec3(v));
                break;
        }
    }
    if (request.extraUniforms) request.extraUniforms(*program);
    if (request.seamlessCubes)
        gl::Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    else
        gl::Disable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    gl::Finish();
    auto start = std::chrono::steady_clock::now();
    fullscreen_.draw();
    gl::Finish();
    double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    gl::checkError("view pass");
    return ms;
}

namespace {

// Each texel of a packed input as a q x q block (q = 2: the isolated points' quads; packing is
// per point, so this equals packing every point q x q times), rows bottom-up as GL texture rows
// run, like gl_FragCoord: one pass, whatever the number of points.
Image quadsBottomUp(const Image& image, int q) {
    const Image flipped = flipRows(image);  // the small one: q^2 times fewer rows to move
    Image out;
    out.width = image.width * q;
    out.height = image.height * q;
    out.channels = image.channels;
    out.pixels.resize(size_t(out.width) * size_t(out.height) * size_t(out.channels));
    const size_t c = size_t(image.channels), row = size_t(out.width) * c;
    for (int y = 0; y < flipped.height; ++y) {
        const float* in = flipped.pixels.data() + size_t(y) * size_t(flipped.width) * c;
        float* first = out.pixels.data() + size_t(q * y) * row;
        for (int x = 0; x < flipped.width; ++x)
            for (int k = 0; k < q; ++k)
                std::copy_n(in + size_t(x) * c, c, first + (size_t(x) * size_t(q) + size_t(k)) * c);
        for (int k = 1; k < q; ++k) std::copy_n(first, row, first + size_t(k) * row);
    }
    return out;
}

// The scene's float-rounded camera and first light: what the shader saw.
glm::dvec3 asFloat(const glm::dvec3& v) {
    return glm::dvec3(glm::vec3(v));
}

}  // namespace

RenderResult LabRenderer::render(const RenderRequest& request) {
    const ModuleDesc& d = *request.module->desc;
    Scene scene = applyParamBindings(*request.scene, d, *request.params);
    RenderResult result;
    std::vector<GLuint> inputs;
    if (!request.surfaces) {
        const glm::mat4 viewProjection =
            drawGBuffer(scene, d.needs, request.width, request.height, request.cacheGBuffer);
        for (int i = 0; i < kGBufferTextures; ++i) inputs.push_back(gbuffer_->colorTexture(i));
        result.milliseconds =
            runView(request, scene, false, inputs, request.width, request.height, viewProjection);
        result.valueTexture = valueTarget_->colorTexture(0);
        if (request.readValue) result.value = valueTarget_->read(0);
        if (request.readSurfaces) {
            std::vector<Image> textures;
            for (int i = 0; i < kGBufferTextures; ++i) textures.push_back(gbuffer_->read(i));
            ref::PointLight first{asFloat(scene.lights[0].position),
                                  asFloat(scene.lights[0].color)};
            result.surfaces = unpackSurfaces(textures, asFloat(scene.camera.position), first);
        }
        return result;
    }
    const std::vector<Image> packed =
        packSurfaces(*request.surfaces, request.width, request.height);
    const int q = request.isolatePoints ? 2 : 1;  // quad side per point
    probeInputs_.clear();
    for (const Image& image : packed) {
        probeInputs_.push_back(gl::uploadTexture(quadsBottomUp(image, q), false, GL_RGBA32F));
        inputs.push_back(probeInputs_.back().id());
    }
    result.milliseconds =
        runView(request, scene, true, inputs, q * request.width, q * request.height, glm::mat4(1));
    result.value = valueTarget_->read(0);
    if (q > 1) {  // one value per quad (all four are the same point)
        Image value = result.value;
        value.width = request.width;
        value.height = request.height;
        value.pixels.resize(size_t(value.width) * size_t(value.height) * 4);
        for (int y = 0; y < value.height; ++y)
            for (int x = 0; x < value.width; ++x)
                for (int c = 0; c < 4; ++c) value.at(x, y, c) = result.value.at(2 * x, 2 * y, c);
        result.value = std::move(value);
    }
    if (request.readSurfaces) result.surfaces = unpackSurfaces(packed, {}, {});
    return result;
}

RenderResult LabRenderer::renderScene(const LoadedModule& module, const ParamValues& params,
                                      const Scene& scene, const StudentSource& source, int width,
                                      int height, bool readSurfaces) {
    RenderRequest r{&module, &params, &scene, source, nullptr, width, height};
    r.readSurfaces = readSurfaces;
    return render(r);
}

Image loadEnvironmentImage(const std::string& source, const fs::path& cache) {
    const bool generated = source == "sky" || source == "sky-soft" || source == "smooth";
    if (!generated) {
        Image image = readImage(source);
        if (image.width != 2 * image.height || image.channels < 3)
            throw Error(source +
                        ": expected an equirectangular RGB image (width = 2 x height), got " +
                        std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                        std::to_string(image.channels));
        return image;
    }
    auto generate = [&] {
        if (source == "sky") return generateSkyEnvironment(512);
        if (source == "sky-soft") return generateSkyEnvironment(512, true);
        return generateSmoothEnvironment(256);
    };
    if (cache.empty()) return generate();
    // Its size and floats (cache_file.h); the generator's version is in the name, so an edit to
    // it never reads a stale image.
    const fs::path file =
        cache / "environments" / (source + "-v" + std::to_string(kEnvironmentVersion) + ".bin");
    constexpr char kMagic[8] = {'P', 'B', 'R', 'L', 'E', 'N', 'V', '1'};
    CacheReader in(file, kMagic);
    std::int32_t size[2] = {0, 0};
    if (in.get(size) && size[0] > 0 && size[0] <= 8192 && size[1] > 0 && size[1] <= 8192) {
        Image image;
        image.width = size[0];
        image.height = size[1];
        image.channels = 3;
        image.pixels.resize(size_t(size[0]) * size_t(size[1]) * 3);
        if (in.bytes(image.pixels.data(), image.pixels.size() * sizeof(float)) && in.atEnd())
            return image;
    }
    Image image = generate();
    CacheWriter out(kMagic);
    out.put(std::array<std::int32_t, 2>{image.width, image.height});
    out.bytes(image.pixels.data(), image.pixels.size() * sizeof(float));
    out.commit(file);  // no cache: fine
    return image;
}

LabRenderer::Environment& LabRenderer::environment(const Scene& scene, const IblSettings& settings,
                                                   bool derived) {
    Environment& env = environments_[environmentKey(scene, settings)];
    if (!env.maps) {
        if (!precompute_)
            precompute_ = std::make_unique<IblPrecompute>(programs_, paths_.shaders());
        logLine("environment", scene.environment + " (" + settings.key() + ")");
        precompute_->onPass = options_.onPrecomputePass;
        env.equirect = loadEnvironmentImage(scene.environment, options_.cacheRoot);
        env.maps = precompute_->buildEnvironment(env.equirect, settings);
    }
    if (derived && !env.maps->derived) {
        precompute_->onPass = options_.onPrecomputePass;
        IblDiskCache cache(options_.cacheRoot);
        precompute_->buildDerived(*env.maps, env.equirect,
                                  options_.cacheRoot.empty() ? nullptr : &cache);
        env.equirect = Image();  // nothing reads it any more
    }
    return env;
}

bool LabRenderer::hasEnvironmentMaps(const Scene& scene, const IblSettings& settings) const {
    auto it = environments_.find(environmentKey(scene, settings));
    return it != environments_.end() && it->second.maps && it->second.maps->derived;
}

const IblMaps& LabRenderer::environmentMaps(const Scene& scene, const IblSettings& settings) {
    return *environment(scene, settings, true).maps;
}

const IblInputs& LabRenderer::environmentInputs(const Scene& scene, const IblSettings& settings,
                                                bool derived) {
    Environment& env = environment(scene, settings, derived);
    const IblMaps& maps = *env.maps;
    const IblSettings& s = maps.settings;
    auto add = [](Digest& digest, const Image& image) {
        digest.add(std::array<int, 3>{image.width, image.height, image.channels});
        digest.add(image.pixels.data(), image.pixels.size() * sizeof(float));
    };
    auto cube = [&](GLuint texture, int size, int levels, Digest& digest) {
        std::vector<std::vector<Image>> mips = IblPrecompute::readCube(texture, size, levels);
        for (const auto& faces : mips)
            for (const Image& face : faces) add(digest, face);
        return CubeSampler(std::move(mips));
    };
    if (!env.cpu) {
        env.cpu = std::make_unique<IblInputs>();
        Digest digest;
        env.cpu->environment = cube(maps.environment.id(), s.environmentSize,
                                    int(std::floor(std::log2(s.environmentSize))) + 1, digest);
        env.cubeDigest = digest.h;
    }
    if (derived && !env.cpuDerived) {
        Digest digest;
        env.cpu->irradiance = cube(maps.irradiance.id(), s.irradianceSize, 1, digest);
        env.cpu->prefilter = cube(maps.prefilter.id(), s.prefilterSize, s.prefilterMips, digest);
        env.cpu->prefilterMaxLod = maps.prefilterMaxLod;
        digest.add(env.cpu->prefilterMaxLod);
        env.cpu->lut = IblPrecompute::readLut(maps);
        add(digest, env.cpu->lut);
        env.derivedDigest = digest.h;
        env.cpuDerived = true;
    }
    return *env.cpu;
}

std::uint64_t LabRenderer::environmentDigest(const Scene& scene, const IblSettings& settings,
                                             bool derived) {
    environmentInputs(scene, settings, derived);
    const Environment& env = environments_[environmentKey(scene, settings)];
    Digest digest;
    digest.add(env.cubeDigest);
    if (derived) digest.add(env.derivedDigest);
    return digest.h;
}

std::vector<Surface> probeSurfaces(const Probe& probe) {
    std::vector<Surface> grid;
    for (int y = 0; y < probe.height; ++y)
        for (int x = 0; x < probe.width; ++x)
            grid.push_back(
                probe.at(double(x) / (probe.width - 1), 1.0 - double(y) / (probe.height - 1)));
    return grid;
}

RenderResult LabRenderer::renderProbe(const LoadedModule& module, const ParamValues& params,
                                      const Scene& scene, const StudentSource& source) {
    const Probe& probe = module.desc->probe;
    return renderSurfaces(module, params, scene, source, probeSurfaces(probe), probe.width,
                          probe.height);
}

RenderResult LabRenderer::renderSurfaces(const LoadedModule& module, const ParamValues& params,
                                         const Scene& scene, const StudentSource& source,
                                         const std::vector<Surface>& surfaces, int width,
                                         int height) {
    RenderRequest r{&module, &params, &scene, source, &surfaces, width, height};
    r.readSurfaces = true;
    return render(r);
}

}  // namespace pbrlab
