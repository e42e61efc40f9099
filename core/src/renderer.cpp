#include "renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>

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

// A linear factor as an 8-bit-free sRGB texture would store it (exact curve).
glm::dvec3 srgbEncode(const glm::dvec3& linear) {
    glm::dvec3 e;
    for (int c = 0; c < 3; ++c) {
        double v = std::clamp(linear[c], 0.0, 1.0);
        e[c] = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
    }
    return e;
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

fs::path DataPaths::scene(const std::string& name) const {
    if (name.find('/') != std::string::npos || fs::path(name).extension() == ".json") return name;
    return assets() / "scenes" / (name + ".json");
}

DataPaths DataPaths::locate() {
    if (const char* env = std::getenv("PBRLAB_DATA"); env && *env) return {env};
    return {PBRLAB_SOURCE_DIR};
}

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

LabRenderer::LabRenderer(const DataPaths& paths)
    : paths_(paths), programs_(ShaderPreprocessor({paths.shaders(), paths.labs()})) {}

ProgramRecipe LabRenderer::viewRecipe(const LoadedModule& module, const StudentSource& source,
                                      bool probe, int lightCount) const {
    ProgramRecipe r;
    r.label = "view " + module.desc->id;
    r.vertex = {paths_.shaders() / "fullscreen.vert"};
    r.fragment.push_back(paths_.shaders() / "common.glsl");
    const ModuleDesc& d = *module.desc;
    // The IBL lab's contract adds fresnelSchlickRoughness to the reference library.
    if (d.lab == "ibl") r.fragment.push_back(paths_.shaders() / "fresnel_roughness.glsl");
    for (const ContractStep* step : contractClosure(d.id, d.uses)) {
        ShaderPart part(paths_.labs() / step->folder() / "solution.glsl");
        if (!source.dir.empty() && (step->id == d.id || source.cumulative)) {
            fs::path student = source.dir / (step->id + ".glsl");
            if (fs::exists(student)) {
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
    r.fragment.push_back(module.sourceDir / "view.glsl");
    r.fragment.push_back(paths_.shaders() / "view_main.frag");
    r.defines["NUM_LIGHTS"] = std::to_string(std::max(lightCount, 1));
    if (probe) r.defines["PBRLAB_PROBE"] = "1";
    // The IBL lab's programs include its earlier steps, some of which name the IBL samplers:
    // every IBL-lab program declares them; only modules that need the environment get maps.
    if ((d.needs & NeedsEnvironment) || d.lab == "ibl") r.defines["PBRLAB_IBL"] = "1";
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
    if (!slot) slot = std::make_unique<gl::GpuMesh>(data ? *data : makeUvSphere(96, 48));
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

void LabRenderer::drawGBuffer(const Scene& scene, unsigned needs, int width, int height) {
    if (!gbuffer_ || gbuffer_->width() != width || gbuffer_->height() != height)
        gbuffer_ = std::make_unique<gl::RenderTarget>(width, height, kGBufferTextures);
    gbuffer_->bind();
    const float zero[4] = {0, 0, 0, 0};
    for (int i = 0; i < kGBufferTextures; ++i) gl::ClearBufferfv(GL_COLOR, i, zero);
    gl::Clear(GL_DEPTH_BUFFER_BIT);
    gl::Enable(GL_DEPTH_TEST);
    gl::DepthFunc(GL_LESS);

    const Camera& cam = scene.camera;
    // Near and far planes from the camera's distance, so models of any size keep depth
    // precision (a unit sphere at distance 3: 0.05 .. 200, as before).
    const double distance = glm::length(cam.position - cam.target);
    glm::mat4 view =
        glm::lookAt(glm::vec3(cam.position), glm::vec3(cam.target), glm::vec3(0, 1, 0));
    glm::mat4 proj = glm::perspective(glm::radians(float(cam.fovY)), float(width) / float(height),
                                      float(distance / 60), float(distance * 60));
    viewProjection_ = proj * view;
    for (const SceneModel& model : scene.models) keepModels_.insert(model.data);

    for (const DrawItem& item : drawItems(scene)) {
        const MaterialDesc& m = scene.materials.at(size_t(item.material));
        auto program = programs_.get(gbufferRecipe(m, needs));
        program->use();
        const glm::mat4 model(item.transform);
        program->set("uModel", model);
        glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(model)));
        gl::UniformMatrix3fv(program->location("uNormalMatrix"), 1, GL_FALSE, &normalMatrix[0][0]);
        program->set("uViewProjection", viewProjection_);
        program->set("uAlbedo", glm::vec3(m.albedo));
        program->set("uAlbedoTexel", glm::vec3(srgbEncode(m.albedo)));
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
}

double LabRenderer::runView(const LoadedModule& module, const ParamValues& params,
                            const Scene& scene, const StudentSource& source, bool probe,
                            const std::vector<GLuint>& inputs, int width, int height) {
    // reloadIfChanged: an edited student file is recompiled; if that fails, the error is thrown
    // and the last good program stays cached for the next call.
    // Precompute (on first use) before binding anything: its passes use the texture units.
    if (module.desc->needs & NeedsEnvironment) environmentMaps(scene);
    auto program =
        programs_.reloadIfChanged(viewRecipe(module, source, probe, int(scene.lights.size())));
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
    if (module.desc->needs & NeedsEnvironment) {
        const IblMaps& maps = environmentMaps(scene);  // built before anything was bound
        struct Binding {
            const char* name;
            GLenum target;
            GLuint texture;
        };
        const Binding bindings[] = {{"uEnvironment", GL_TEXTURE_CUBE_MAP, maps.environment.id()},
                                    {"uIrradianceMap", GL_TEXTURE_CUBE_MAP, maps.irradiance.id()},
                                    {"uPrefilterMap", GL_TEXTURE_CUBE_MAP, maps.prefilter.id()},
                                    {"uBrdfLut", GL_TEXTURE_2D, maps.lut.id()}};
        int unit = int(inputs.size());
        for (const Binding& b : bindings) {
            if (!program->uses(b.name)) continue;
            gl::ActiveTexture(GLenum(GL_TEXTURE0 + unit));
            gl::BindTexture(b.target, b.texture);
            program->set(b.name, unit++);
        }
        program->set("uPrefilterMaxLod", maps.prefilterMaxLod);
        if (program->uses("uInverseViewProjection")) {
            program->set("uInverseViewProjection", glm::inverse(viewProjection_));
            program->set("uViewportSize", glm::vec2(float(width), float(height)));
        }
    }
    for (const ParamDecl& p : module.desc->params) {
        glm::dvec3 v = params.vector(p.name);
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
    if (extraUniforms_) extraUniforms_(*program);
    if (seamlessCubes_)
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

// The scene's float-rounded camera and first light: what the shader saw.
glm::dvec3 asFloat(const glm::dvec3& v) {
    return glm::dvec3(glm::vec3(v));
}

}  // namespace

RenderResult LabRenderer::renderScene(const LoadedModule& module, const ParamValues& params,
                                      const Scene& sceneIn, const StudentSource& source, int width,
                                      int height, bool readSurfaces) {
    Scene scene = applyParamBindings(sceneIn, *module.desc, params);
    drawGBuffer(scene, module.desc->needs, width, height);
    std::vector<GLuint> inputs;
    for (int i = 0; i < kGBufferTextures; ++i) inputs.push_back(gbuffer_->colorTexture(i));
    RenderResult result;
    result.milliseconds = runView(module, params, scene, source, false, inputs, width, height);
    result.value = valueTarget_->read(0);
    if (readSurfaces) {
        std::vector<Image> textures;
        for (int i = 0; i < kGBufferTextures; ++i) textures.push_back(gbuffer_->read(i));
        ref::PointLight first{asFloat(scene.lights[0].position), asFloat(scene.lights[0].color)};
        result.surfaces = unpackSurfaces(textures, asFloat(scene.camera.position), first);
    }
    return result;
}

Image loadEnvironmentImage(const std::string& source) {
    if (source == "sky") return generateSkyEnvironment(512);
    Image image = readImage(source);
    if (image.width != 2 * image.height || image.channels < 3)
        throw Error(source + ": expected an equirectangular RGB image (width = 2 x height), got " +
                    std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                    std::to_string(image.channels));
    return image;
}

const IblMaps& LabRenderer::environmentMaps(const Scene& scene) {
    std::string key = scene.environment + "|" + iblSettings_.key();
    Environment& env = environments_[key];
    if (!env.maps) {
        if (!precompute_)
            precompute_ =
                std::make_unique<IblPrecompute>(programs_, paths_.shaders(), paths_.labs());
        logLine("environment", scene.environment + " (" + iblSettings_.key() + ")");
        precompute_->onPass = precomputeProgress_;
        IblDiskCache cache(iblCache_);
        env.maps = precompute_->build(loadEnvironmentImage(scene.environment), iblSettings_,
                                      iblCache_.empty() ? nullptr : &cache);
    }
    return *env.maps;
}

const IblInputs& LabRenderer::environmentInputs(const Scene& scene) {
    const IblMaps& maps = environmentMaps(scene);
    Environment& env = environments_[scene.environment + "|" + iblSettings_.key()];
    if (!env.cpu) {
        auto cpu = std::make_unique<IblInputs>();
        auto cube = [](GLuint texture, int size, int levels) {
            return CubeSampler(IblPrecompute::readCube(texture, size, levels));
        };
        const IblSettings& s = maps.settings;
        cpu->environment = cube(maps.environment.id(), s.environmentSize,
                                int(std::floor(std::log2(s.environmentSize))) + 1);
        cpu->irradiance = cube(maps.irradiance.id(), s.irradianceSize, 1);
        cpu->prefilter = cube(maps.prefilter.id(), s.prefilterSize, s.prefilterMips);
        cpu->prefilterMaxLod = maps.prefilterMaxLod;
        cpu->lut = IblPrecompute::readTexture(maps.lut.id(), s.lutSize, s.lutSize);
        env.cpu = std::move(cpu);
    }
    return *env.cpu;
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
                                         const Scene& sceneIn, const StudentSource& source,
                                         const std::vector<Surface>& surfaces, int width,
                                         int height) {
    Scene scene = applyParamBindings(sceneIn, *module.desc, params);
    std::vector<Image> packed = packSurfaces(surfaces, width, height);
    probeInputs_.clear();
    std::vector<GLuint> inputs;
    for (const Image& image : packed) {
        // GL texture rows run bottom-up, like gl_FragCoord.
        Image flipped = image;
        const size_t row = size_t(image.width) * 4;
        for (int y = 0; y < image.height; ++y)
            std::copy_n(image.pixels.data() + size_t(image.height - 1 - y) * row, row,
                        flipped.pixels.data() + size_t(y) * row);
        probeInputs_.push_back(gl::uploadTexture(flipped, false, GL_RGBA32F));
        inputs.push_back(probeInputs_.back().id());
    }
    RenderResult result;
    result.milliseconds = runView(module, params, scene, source, true, inputs, width, height);
    result.value = valueTarget_->read(0);
    result.surfaces = unpackSurfaces(packed, {}, {});
    return result;
}

}  // namespace pbrlab
