// LabRenderer's requests: the view program of a step (the contract functions of its own and
// the earlier steps, the student's where graded), the view pass over the G-buffer
// (renderer_gbuffer.cpp) or uploaded points, with the IBL maps the step may read
// (renderer_environment.cpp) bound.
#include "render/renderer.h"

#include <algorithm>
#include <chrono>

#include "render/surface_io.h"
#include "steps/contract.h"
#include "util/error.h"

#ifndef PBRLAB_SOURCE_DIR
#error "PBRLAB_SOURCE_DIR must name the source tree"
#endif

namespace fs = std::filesystem;

namespace pbrlab {

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
      programs_(ShaderPreprocessor({paths.shaders(), paths.labs()}, options_.dialect)) {}

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

namespace {

// The light arrays' length (PBRLAB_LIGHT_SLOTS, common.glsl): a loop a student hard-codes to
// any count up to the most lights a scene has reads defined values.
size_t lightSlots(size_t lights) {
    return std::max(kMaxSceneLights, lights);
}

}  // namespace

ProgramRecipe LabRenderer::viewRecipe(const LoadedModule& module, const StudentSource& source,
                                      bool probe, int lightCount, const std::string& view) const {
    ProgramRecipe r;
    const ModuleDesc& d = *module.desc;
    r.label = "view " + d.id + (view.empty() ? "" : " (" + view + ")");
    r.vertex = {paths_.shaders() / "fullscreen.vert"};
    r.fragment.push_back(paths_.shaders() / "common.glsl");
    // What the step's file may call (docs/design.md, "Assignment contract"): the contract
    // functions of its own and every earlier step, and the helpers those steps introduce. Each
    // is declared just before its step's part, so a student's file (also an earlier one, with
    // --cumulative) sees no later step's function: the program holds no code that computes
    // the graded step except the student's own. The view calls only steps in that set.
    // A module outside the contract (the converge comparisons of shaders/converge) grades no
    // student's file: its view may call every step.
    const ContractStep* own = findContractStep(d.id);
    std::vector<const ContractStep*> visible;
    if (own) {
        visible = stepsVisibleFrom(*own);
        for (const std::string& used : d.uses) {
            const ContractStep* u = findContractStep(used);
            if (!u || u->step > own->step)
                throw Error("the view of " + d.id + " uses '" + used +
                            "', which is not an earlier step: a step's program holds no later "
                            "step");
        }
    } else {
        for (const ContractStep& step : contractSteps()) visible.push_back(&step);
    }
    for (const ContractStep* step : visible) {
        for (const ContractStep::Helper& helper : step->helpers)
            r.fragment.push_back(paths_.shaders() / helper.file);
        r.fragment.push_back(ShaderPart("<contract: " + step->id + ">", step->function + ";\n"));
        ShaderPart part(step->folder / "solution.glsl");
        part.solutionOf = functionName(step->function);
        auto studentPart = [&](const fs::path& folder) {
            const fs::path student = folder / (step->id + ".glsl");
            std::error_code ec;
            if (!fs::exists(student, ec) && !fs::is_symlink(student, ec)) return false;
            part = ShaderPart(student);
            part.studentFolder = folder;  // screened; never the reference solutions
            part.unreachable = unreachableFrom(*step);
            return true;
        };
        bool fromStudent = !source.dir.empty() && (step->id == d.id || source.cumulative) &&
                           studentPart(source.dir);
        // The diagnosis build traces the graded step's file only: a line it reports is one of
        // that file.
        part.traced = fromStudent && step->id == d.id && source.traceNonFinite;
        // A withheld solution (an assignment's site): the student's own file of that step
        // wherever the solution would be, else its starter.
        if (!fromStudent && solutionWithheld(*step)) {
            const fs::path folder = withheldStepsFolder();
            if (folder.empty() || !studentPart(folder))
                part = ShaderPart(step->folder / "starter.glsl");
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
    r.defines["PBRLAB_LIGHT_SLOTS"] = std::to_string(lightSlots(size_t(std::max(lightCount, 1))));
    if (probe) r.defines["PBRLAB_PROBE"] = "1";
    // Every program declares the IBL samplers (contract names any step may call through the
    // IBL functions); only what the step may read is bound (see runView).
    r.defines["PBRLAB_IBL"] = "1";
    if ((d.needs & NeedsEnvironment) && d.skyBackground && !probe) r.defines["PBRLAB_SKY"] = "1";
    if (source.traceNonFinite) r.defines[kTraceNonFinite] = "1";
    return r;
}

LoopLimits viewLoopLimits(const ModuleDesc& module, const ParamValues& params, size_t lights,
                          int environmentSize) {
    LoopLimits limits;
    limits.lightSlots = lightSlots(std::max<size_t>(lights, 1));
    // Not below the default environment's: a function's loops over the sky need not follow the
    // size of the cube it reads (a grid in angles, a fixed sample count), and the host's checks
    // with a small cube (16 x 16: is textureSize followed?) must judge the same loops as the
    // others, not cut them.
    if (LabRenderer::mayRead(module, "uEnvironment"))
        limits.environmentSize = std::max(environmentSize, IblSettings{}.environmentSize);
    for (const ParamDecl& p : module.params)
        if (p.type == ParamType::Int)
            limits.counts.push_back(module.estimator && module.estimator->samplesParam == p.name
                                        ? params.number(p.name)
                                        : p.max);
    return limits;
}

namespace {

// The view's inputs (the G-buffer's textures or the uploaded points), units 0 on, as
// uSurface0...
void bindSurfaceInputs(const Program& program, const std::vector<GLuint>& inputs) {
    for (size_t i = 0; i < inputs.size(); ++i) {
        gl::ActiveTexture(GLenum(GL_TEXTURE0 + i));
        gl::BindTexture(GL_TEXTURE_2D, inputs[i]);
        program.set("uSurface" + std::to_string(i), int(i));
    }
}

// The scene's lights, in every slot of the light arrays.
void setLightUniforms(const Program& program, const Scene& scene) {
    // Every slot past the scene's lights is a black light at the last one's position (see
    // common.glsl): it adds nothing, and no 0/0 where the real lights have none.
    std::vector<glm::vec3> positions, colors;
    for (const auto& l : scene.lights) {
        positions.emplace_back(l.position);
        colors.emplace_back(l.color);
    }
    const glm::vec3 padding = positions.empty() ? glm::vec3(0, 100, 0) : positions.back();
    positions.resize(lightSlots(scene.lights.size()), padding);
    colors.resize(positions.size(), glm::vec3(0));
    program.set("uLightPositions", positions);
    program.set("uLightColors", colors);
}

// The step's parameters, as the uniforms parameterUniforms declares.
void setParameterUniforms(const Program& program, const ModuleDesc& d, const ParamValues& params) {
    for (const ParamDecl& p : d.params) {
        glm::dvec3 v = params.vector(p.name);
        const std::string u = p.uniformName();
        switch (p.type) {
            case ParamType::Float:
                program.set(u, float(v.x));
                break;
            case ParamType::Int:
            case ParamType::Bool:
            case ParamType::Enum:
                program.set(u, int(v.x));
                break;
            case ParamType::Color:
            case ParamType::Direction:
                program.set(u, glm::vec3(v));
                break;
        }
    }
}

}  // namespace

// The environment and the maps the view may read, built before anything is bound (the
// precompute passes use the texture units). A derived map is readable only by steps after
// the one whose reference solution computes it; every other sampler the program uses
// reads black (the contract declares them all).
std::vector<LabRenderer::SamplerBinding> LabRenderer::iblBindings(const Program& program,
                                                                  const ModuleDesc& d,
                                                                  const Scene& scene,
                                                                  const IblSettings& ibl) {
    std::vector<SamplerBinding> bindings;
    if (program.uses("uEnvironment"))
        bindings.push_back({"uEnvironment", GL_TEXTURE_CUBE_MAP,
                            mayRead(d, "uEnvironment")
                                ? environment(scene, ibl, false).maps->environment.id()
                                : 0});
    for (const DerivedMap& map : kDerivedMaps) {
        if (!program.uses(map.sampler)) continue;
        const GLenum target =
            std::string(map.sampler) == "uBrdfLut" ? GL_TEXTURE_2D : GL_TEXTURE_CUBE_MAP;
        GLuint texture = 0;
        if (mayRead(d, map.sampler)) {
            const IblMaps& maps = *environment(scene, ibl, true).maps;
            texture = target == GL_TEXTURE_2D                        ? maps.lut.id()
                      : std::string(map.sampler) == "uIrradianceMap" ? maps.irradiance.id()
                                                                     : maps.prefilter.id();
        }
        bindings.push_back({map.sampler, target, texture});
    }
    for (SamplerBinding& b : bindings)
        if (!b.texture) b.texture = blackTexture(b.target);
    return bindings;
}

void LabRenderer::runView(const RenderRequest& request, const Scene& scene, bool probe,
                          const std::vector<GLuint>& inputs, int width, int height,
                          const glm::mat4& viewProjection, RenderResult& result) {
    const LoadedModule& module = *request.module;
    const ModuleDesc& d = *module.desc;
    // reloadIfChanged: an edited student file is recompiled; if that fails, the error is thrown
    // and the last good program stays cached for the next call.
    auto program = programs_.reloadIfChanged(
        viewRecipe(module, request.source, probe, int(scene.lights.size()), request.view));
    const std::vector<SamplerBinding> bindings = iblBindings(*program, d, scene, request.ibl);
    if (!valueTarget_ || valueTarget_->width() != width || valueTarget_->height() != height)
        valueTarget_ = std::make_unique<gl::RenderTarget>(width, height, 1, false);
    valueTarget_->bind();
    program->use();
    bindSurfaceInputs(*program, inputs);
    if (probe) program->set("uPointQuad", request.width > 0 ? width / request.width : 1);
    setLightUniforms(*program, scene);
    if (program->uses("uCameraPosition"))
        program->set("uCameraPosition", glm::vec3(scene.camera.position));
    int unit = int(inputs.size());
    for (const SamplerBinding& b : bindings) {
        gl::ActiveTexture(GLenum(GL_TEXTURE0 + unit));
        gl::BindTexture(b.target, b.texture);
        program->set(b.name, unit++);
    }
    if (program->uses("uPrefilterMaxLod"))
        program->set("uPrefilterMaxLod", prefilterMaxLod(scene, request.ibl));
    if (program->uses("uInverseViewProjection")) {
        program->set("uInverseViewProjection", glm::inverse(viewProjection));
        program->set("uViewportSize", glm::vec2(float(width), float(height)));
    }
    setParameterUniforms(*program, d, *request.params);
    result.loops = program->loops();
    result.loopBudget = 0;
    if (program->uses(kLoopBudgetUniform)) {
        result.loopBudget = loopBudget(
            viewLoopLimits(d, *request.params, scene.lights.size(), request.ibl.environmentSize));
        program->set(kLoopBudgetUniform, result.loopBudget);
    }
    if (request.extraUniforms) request.extraUniforms(*program);
    gl::setSeamlessCubeFiltering(request.seamlessCubes || options_.seamlessCubesAlways);
    gl::Finish();
    auto start = std::chrono::steady_clock::now();
    fullscreen_.draw();
    gl::Finish();
    result.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    gl::checkError("view pass");
}

namespace {

// The view's value read back, its time added to the picture's (the read-back waits for the GPU,
// where glFinish may not).
void readValueTimed(gl::RenderTarget& target, RenderResult& result) {
    const auto start = std::chrono::steady_clock::now();
    result.value = target.read(0);
    result.pictureMilliseconds +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
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
            drawGBuffer(scene, d.needs, request.width, request.height, request);
        const gl::RenderTarget& gbuffer = *gbufferFor(request.coarseSpheres);
        for (int i = 0; i < kGBufferTextures; ++i) inputs.push_back(gbuffer.colorTexture(i));
        runView(request, scene, false, inputs, request.width, request.height, viewProjection,
                result);
        result.valueTexture = valueTarget_->colorTexture(0);
        result.pictureMilliseconds = result.milliseconds;
        if (request.readValue) readValueTimed(*valueTarget_, result);
        if (request.readSurfaces) {
            std::vector<Image> textures;
            for (int i = 0; i < kGBufferTextures; ++i) textures.push_back(gbuffer.read(i));
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
        // Bottom-up (GL's rows), one texel a point: surface.glsl reads it for the point's quad.
        probeInputs_.push_back(gl::uploadTexture(flipRows(image), false, GL_RGBA32F));
        inputs.push_back(probeInputs_.back().id());
    }
    runView(request, scene, true, inputs, q * request.width, q * request.height, glm::mat4(1),
            result);
    result.pictureMilliseconds = result.milliseconds;
    readValueTimed(*valueTarget_, result);
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
