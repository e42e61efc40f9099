// The precompute: the environment cube, then the maps derived from it, each by the method its
// settings choose: the host's own (CPU bins, a quadrature, a Riemann sum, filtered importance
// sampling) or the pass that the step providing the map declares in its folder (step.json
// "precompute": a kind of pass the host knows how to run, and the step's shader). The host
// names maps (samplers), never steps. Settings: ibl/settings.cpp; CPU maps: ibl/cpu_maps.cpp;
// disk cache and keys: ibl/map_cache.cpp.
#include "ibl/precompute.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "ibl/cpu_maps.h"
#include "ibl/map_cache.h"
#include "steps/contract.h"
#include "util/error.h"
#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

const char* const kCubeFaceNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};

using PassKind = ContractStep::PrecomputePass::Kind;

const DerivedMap kDerivedMaps[3] = {{"uIrradianceMap", PassKind::Cube},
                                    {"uPrefilterMap", PassKind::CubeMips},
                                    {"uBrdfLut", PassKind::Square}};

namespace {

const char* kindName(PassKind kind) {
    switch (kind) {
        case PassKind::Cube:
            return "cube";
        case PassKind::CubeMips:
            return "cube_mips";
        case PassKind::Square:
            return "square";
    }
    return "";
}

// The step whose reference solutions compute the map, with its declared pass checked against
// the kind of map the host binds to that sampler. Throws when no step provides the map: the
// settings then ask for a method that only a step can supply.
const ContractStep& providerOf(const char* sampler, bool needsPass) {
    const ContractStep* step = findProvider(sampler);
    if (!step)
        throw Error(std::string("no step provides ") + sampler +
                    " (step.json \"precompute\"): choose one of the host's own methods for it");
    const DerivedMap* map = nullptr;
    for (const DerivedMap& m : kDerivedMaps)
        if (std::string(m.sampler) == sampler) map = &m;
    if (needsPass && !step->precompute)
        throw Error((step->folder / "step.json").string() + ": provides " + sampler +
                    " but declares no \"precompute\" pass for it");
    if (step->precompute && map && step->precompute->kind != map->kind)
        throw Error((step->folder / "step.json").string() + ": \"precompute\" \"kind\" is " +
                    kindName(step->precompute->kind) + ", but " + sampler + " is a " +
                    kindName(map->kind) + " map");
    return *step;
}

}  // namespace

double IblMaps::milliseconds(const std::string& map) const {
    double ms = 0;
    for (const IblPass& p : passes)
        if (p.map == map) ms += p.milliseconds;
    return ms;
}
namespace {

int fullMipCount(int size) {
    return int(std::floor(std::log2(size))) + 1;
}

// A cube map with `levels` mips of immutable storage (allocated once; filled by passes).
gl::Handle makeCube(int size, int levels) {
    gl::Handle cube = gl::makeTexture();
    gl::BindTexture(GL_TEXTURE_CUBE_MAP, cube.id());
    gl::TexStorage2D(GL_TEXTURE_CUBE_MAP, levels, GL_RGBA32F, size, size);
    gl::TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER,
                      levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    gl::TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        gl::TexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
    gl::TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, levels - 1);
    gl::checkError("creating a cube map");
    return cube;
}

// levels[mip][face] (RGBA, row 0 = t = 0) into mips first.. of `cube`.
void uploadCube(GLuint cube, const std::vector<std::vector<Image>>& levels, int first = 0) {
    gl::BindTexture(GL_TEXTURE_CUBE_MAP, cube);
    gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (size_t level = 0; level < levels.size(); ++level)
        for (int face = 0; face < 6; ++face) {
            const Image& im = levels[level][size_t(face)];
            gl::TexSubImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, first + GLint(level), 0, 0,
                              im.width, im.height, GL_RGBA, GL_FLOAT, im.pixels.data());
        }
    gl::checkError("uploading a cube map");
}

gl::Handle makeLutTexture(int width, int height) {
    gl::Handle lut = gl::makeTexture();
    gl::BindTexture(GL_TEXTURE_2D, lut.id());
    gl::TexStorage2D(GL_TEXTURE_2D, 1, GL_RG32F, width, height);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl::checkError("creating the LUT");
    return lut;
}

// A LUT texture holding an image read back from one (RGBA: its red and green are the texture's).
// Uploaded as red and green only: OpenGL ES (WebGL 2) takes no RGBA data into an RG texture.
gl::Handle uploadLut(const Image& rgba) {
    gl::Handle lut = makeLutTexture(rgba.width, rgba.height);
    std::vector<float> rg(size_t(rgba.width) * size_t(rgba.height) * 2);
    for (size_t i = 0; i < rg.size() / 2; ++i)
        for (size_t c = 0; c < 2; ++c) rg[2 * i + c] = rgba.pixels[i * size_t(rgba.channels) + c];
    gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl::TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, rgba.width, rgba.height, GL_RG, GL_FLOAT, rg.data());
    gl::checkError("uploading the LUT");
    return lut;
}

class PassTimer {
public:
    PassTimer(IblMaps& maps, std::string map, std::string label,
              const std::function<void(const std::string&)>& onPass = {})
        : maps_(maps), map_(std::move(map)), label_(std::move(label)) {
        if (onPass) onPass("[" + std::to_string(maps.passes.size() + 1) + "] " + label_);
        gl::Finish();
        start_ = std::chrono::steady_clock::now();
    }
    ~PassTimer() {
        gl::Finish();
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
                .count();
        maps_.passes.push_back({map_, label_, ms, false});
        countEvent(Counter::PrecomputePasses);
        logLine("precompute", label_ + " " + std::to_string(ms) + " ms");
    }

private:
    IblMaps& maps_;
    std::string map_, label_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace

IblPrecompute::IblPrecompute(ProgramCache& programs, fs::path shaders)
    : programs_(programs), shaders_(std::move(shaders)) {}

// A host shader of shaders/ibl/ (by its stem), linked with the reference solutions of the
// step that provides `linkedSampler` ("" none: the shader calls no contract function).
std::shared_ptr<Program> IblPrecompute::hostProgram(const std::string& shader,
                                                    const char* linkedSampler,
                                                    const Defines& extra) {
    const ContractStep* linked = linkedSampler ? &providerOf(linkedSampler, false) : nullptr;
    return program("precompute " + shader, shaders_ / "ibl" / (shader + ".frag"), linked, extra);
}

// The pass the step that provides `sampler` declares, linked with that step's solutions.
std::shared_ptr<Program> IblPrecompute::stepProgram(const char* sampler) {
    const ContractStep& step = providerOf(sampler, true);
    return program("precompute " + step.id, step.precompute->shader, &step, {});
}

std::shared_ptr<Program> IblPrecompute::program(const std::string& label, const fs::path& fragment,
                                                const ContractStep* linked, const Defines& extra) {
    ProgramRecipe r;
    r.label = label;
    r.vertex = {shaders_ / "fullscreen.vert"};
    r.fragment.push_back(shaders_ / "common.glsl");
    bool studentsFile = false;  // a withheld solution's stand-in, which the student edits
    if (linked)
        for (const ContractStep* step : contractClosure(linked->id, {})) {
            r.fragment.push_back(referenceImplementation(*step));
            studentsFile = studentsFile || solutionWithheld(*step);
        }
    r.fragment.push_back(fragment);
    r.defines = extra;
    r.defines["PBRLAB_IBL"] = "1";
    return studentsFile ? programs_.reloadIfChanged(r) : programs_.get(r);
}

void IblPrecompute::renderCube(GLuint cube, int size, int mip, const Program& program,
                               const std::string& pass) {
    gl::Handle fbo = gl::makeFramebuffer();
    gl::BindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    const int faceSize = std::max(size >> mip, 1);
    gl::Viewport(0, 0, faceSize, faceSize);
    GLenum buffer = GL_COLOR_ATTACHMENT0;
    gl::DrawBuffers(1, &buffer);
    program.use();
    program.set("uSize", float(faceSize));
    for (int face = 0; face < 6; ++face) {
        gl::FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                 GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, cube, mip);
        if (gl::CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw Error(pass + ": cube face target incomplete");
        program.set("uFace", face);
        fullscreen_.draw();
    }
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkError(pass.c_str());
}

std::unique_ptr<IblMaps> IblPrecompute::makeMaps(const IblSettings& settings) {
    auto maps = std::make_unique<IblMaps>();
    maps->settings = settings;
    return maps;
}

std::unique_ptr<IblMaps> IblPrecompute::build(const Image& equirect, const IblSettings& s,
                                              const IblDiskCache* cache) {
    const EquirectSource source(equirect);  // keyed once
    auto maps = buildEnvironment(source, s, cache);
    buildDerived(*maps, source, cache);
    return maps;
}

std::unique_ptr<IblMaps> IblPrecompute::buildEnvironment(const EquirectSource& equirect,
                                                         const IblSettings& s,
                                                         const IblDiskCache* cache) {
    auto maps = makeMaps(s);
    const int levels = fullMipCount(s.environmentSize);
    maps->environment = makeCube(s.environmentSize, levels);
    // The resampling is a third of a second for a 256 cube, and a grade reads the same few
    // environments in every step's process.
    const fs::path file = cache ? cache->root_ / "ibl-environment" /
                                      environmentKey(equirect, s.environmentSize, levels) /
                                      "environment.bin"
                                : fs::path();
    std::vector<std::vector<Image>> cube;
    if (cache && readMaps(file, cube) && sizesAre(cube, s.environmentSize, levels)) {
        uploadCube(maps->environment.id(), cube);
        maps->passes.push_back({"environment", "environment cube (cached)", 0, true});
        logLine("precompute", "environment cube from " + file.string());
        maps->environmentTexels = std::move(cube);
        return maps;
    }
    {
        PassTimer timer(*maps, "environment",
                        "environment cube " + std::to_string(s.environmentSize), onPass);
        cube = equirectToCube(equirect.image(), s.environmentSize, levels);
        uploadCube(maps->environment.id(), cube);
    }
    if (cache) storeQuietly(file, cube);
    maps->environmentTexels = std::move(cube);
    return maps;
}

// What the passes of one buildDerived share, made on first use: the source cube the GPU
// passes read, and the environment's bins (the CPU convolution's input).
struct IblPrecompute::Inputs {
    const EquirectSource& equirect;
    const IblMaps& maps;
    std::vector<std::vector<Image>> sourceLevels;  // when made here
    gl::Handle ownSource;
    GLuint source = 0;
    std::unique_ptr<EnvironmentBins> binned;

    GLuint sourceCube() {
        if (source) return source;
        const IblSettings& s = maps.settings;
        const int n = s.source();
        if (maps.environment && s.environmentSize == n) return source = maps.environment.id();
        sourceLevels = equirectToCube(equirect.image(), n, fullMipCount(n));
        ownSource = makeCube(n, fullMipCount(n));
        uploadCube(ownSource.id(), sourceLevels);
        return source = ownSource.id();
    }
    const EnvironmentBins& bins() {
        if (!binned)
            binned = std::make_unique<EnvironmentBins>(
                binEnvironment(equirect.image(), std::clamp(maps.settings.bins, 1, 64)));
        return *binned;
    }
};

void IblPrecompute::buildDerived(IblMaps& maps, const EquirectSource& equirect,
                                 const IblDiskCache* cache) {
    if (maps.derived) return;
    maps.derived = true;
    const IblSettings& s = maps.settings;
    gl::Disable(GL_DEPTH_TEST);
    gl::setSeamlessCubeFiltering(true);  // precomputed maps never depend on the caller
    maps.prefilterMaxLod = float(s.prefilterMips - 1);

    const fs::path mapsDir = cache ? cache->root_ / "ibl" / mapsKey(equirect, s) : fs::path();
    std::vector<std::vector<Image>> irradiance, prefilter;
    if (cache && readMaps(mapsDir / "irradiance.bin", irradiance) &&
        readMaps(mapsDir / "prefilter.bin", prefilter) &&
        sizesAre(irradiance, s.irradianceSize, 1) &&
        sizesAre(prefilter, s.prefilterSize, s.prefilterMips)) {
        maps.irradiance = makeCube(s.irradianceSize, 1);
        uploadCube(maps.irradiance.id(), irradiance);
        maps.prefilter = makeCube(s.prefilterSize, s.prefilterMips);
        uploadCube(maps.prefilter.id(), prefilter);
        maps.passes.push_back({"irradiance", "irradiance (cached)", 0, true});
        maps.passes.push_back({"prefilter", "prefilter (cached)", 0, true});
        logLine("precompute", "irradiance and prefilter from " + mapsDir.string());
    } else {
        Inputs inputs{equirect, maps, {}, {}, 0, {}};
        {
            PassTimer timer(maps, "prefilter",
                            "prefilter " + std::to_string(s.prefilterSize) + " x" +
                                std::to_string(s.prefilterMips) + " by " + s.prefilterBy() +
                                (s.prefilterMirrorExact ? ", mip 0 resampled" : ""),
                            onPass);
            buildPrefilter(maps, inputs);
        }
        {
            PassTimer timer(
                maps, "irradiance",
                "irradiance " + std::to_string(s.irradianceSize) + " by " + s.irradianceBy(),
                onPass);
            buildIrradiance(maps, inputs);
        }
        if (cache) {
            storeQuietly(mapsDir / "irradiance.bin",
                         readCube(maps.irradiance.id(), s.irradianceSize, 1));
            storeQuietly(mapsDir / "prefilter.bin",
                         readCube(maps.prefilter.id(), s.prefilterSize, s.prefilterMips));
        }
    }

    const fs::path lutFile = cache ? cache->root_ / "ibl-lut" / lutKey(s) / "lut.bin" : fs::path();
    std::vector<std::vector<Image>> lut;
    if (cache && readMaps(lutFile, lut) && lut[0].size() == 1 && lut[0][0].width == s.lutWidth &&
        lut[0][0].height == s.lutHeight) {
        maps.lut = uploadLut(lut[0][0]);
        maps.passes.push_back({"lut", "brdf lut (cached)", 0, true});
        logLine("precompute", "LUT from " + lutFile.string());
    } else {
        buildLut(maps);
        if (cache) storeQuietly(lutFile, {{readLut(maps)}});
    }
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void IblPrecompute::buildPrefilter(IblMaps& maps, Inputs& inputs) {
    const IblSettings& s = maps.settings;
    maps.prefilter = makeCube(s.prefilterSize, s.prefilterMips);
    int firstSampled = 0;
    if (s.prefilterMirrorExact) {
        // Roughness 0 is a mirror: the map holds the environment itself, resampled at its size.
        const int k = std::max(s.mirrorSupersample, 1), extra = fullMipCount(k) - 1;
        if (k == 1 && s.source() == s.prefilterSize && s.prefilter != PrefilterMethod::Bins) {
            inputs.sourceCube();
            if (!inputs.sourceLevels.empty()) {
                uploadCube(maps.prefilter.id(), {inputs.sourceLevels[0]});
                firstSampled = 1;
            }
        }
        if (firstSampled == 0)
            uploadCube(maps.prefilter.id(),
                       {equirectToCube(inputs.equirect.image(), s.prefilterSize * k,
                                       extra + 1)[size_t(extra)]});
        firstSampled = 1;
    }
    if (firstSampled >= s.prefilterMips) return;
    const auto roughness = [&](int mip) {
        return s.prefilterMips > 1 ? double(mip) / double(s.prefilterMips - 1) : 0.0;
    };
    if (s.prefilter == PrefilterMethod::Bins) {
        for (int mip = firstSampled; mip < s.prefilterMips; ++mip)
            uploadCube(
                maps.prefilter.id(),
                {convolveBins(inputs.bins(), std::max(s.prefilterSize >> mip, 1), roughness(mip))},
                mip);
        return;
    }
    auto p = s.prefilter == PrefilterMethod::Filtered
                 ? hostProgram(kFilteredPrefilterShader, "uPrefilterMap")
                 : stepProgram("uPrefilterMap");
    const GLuint source = inputs.sourceCube();
    p->use();
    gl::ActiveTexture(GL_TEXTURE0);
    gl::BindTexture(GL_TEXTURE_CUBE_MAP, source);
    p->set("uEnvironment", 0);
    p->set("uLodBias", float(s.filteredLodBias));
    p->setUnsigned("uSampleCount", unsigned(s.prefilterSamples));
    for (int mip = firstSampled; mip < s.prefilterMips; ++mip) {
        p->set("uRoughness", float(roughness(mip)));
        renderCube(maps.prefilter.id(), s.prefilterSize, mip, *p, "prefilter");
    }
}

void IblPrecompute::buildIrradiance(IblMaps& maps, Inputs& inputs) {
    const IblSettings& s = maps.settings;
    maps.irradiance = makeCube(s.irradianceSize, 1);
    if (s.irradiance == IrradianceMethod::Bins) {
        // Roughness 1 is the cosine lobe: the prefilter's integral is E / pi there.
        uploadCube(maps.irradiance.id(), {convolveBins(inputs.bins(), s.irradianceSize, 1.0)});
        return;
    }
    auto p = s.irradiance == IrradianceMethod::Riemann
                 ? hostProgram(kRiemannIrradianceShader, nullptr)
                 : stepProgram("uIrradianceMap");
    const GLuint source = inputs.sourceCube();
    p->use();
    gl::ActiveTexture(GL_TEXTURE0);
    gl::BindTexture(GL_TEXTURE_CUBE_MAP, source);
    p->set("uEnvironment", 0);
    if (s.irradiance == IrradianceMethod::Riemann) p->set("uStep", float(s.riemannStep));
    renderCube(maps.irradiance.id(), s.irradianceSize, 0, *p, "irradiance");
}

void IblPrecompute::buildLut(IblMaps& maps) {
    const IblSettings& s = maps.settings;
    PassTimer timer(
        maps, "lut",
        "brdf lut " + std::to_string(s.lutWidth) + " x " + std::to_string(s.lutHeight) +
            (s.lut == LutMethod::Quadrature ? ", quadrature"
                                            : ", " + std::to_string(s.lutSamples) + " samples"),
        onPass);
    maps.lut = makeLutTexture(s.lutWidth, s.lutHeight);
    auto p = s.lut == LutMethod::Quadrature ? hostProgram(kQuadratureLutShader, "uBrdfLut")
                                            : stepProgram("uBrdfLut");
    p->use();
    p->setUnsigned("uSampleCount", unsigned(s.lutSamples));
    renderSquare(maps.lut.id(), s.lutWidth, s.lutHeight, *p, "brdf lut");
}

void IblPrecompute::renderSquare(GLuint texture, int width, int height, const Program& program,
                                 const std::string& pass) {
    gl::Handle fbo = gl::makeFramebuffer();
    gl::BindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    gl::FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, 0);
    if (gl::CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error(pass + ": target incomplete");
    GLenum buffer = GL_COLOR_ATTACHMENT0;
    gl::DrawBuffers(1, &buffer);
    gl::Viewport(0, 0, width, height);
    program.use();
    program.set("uSize", glm::vec2(float(width), float(height)));
    fullscreen_.draw();
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkError(pass.c_str());
}

namespace {

// Reads level `level` of a 2D texture or cube face (`target`) back as RGBA floats, memory row 0
// first: for a cube face its t = 0 row, the top of the face image.
Image readAttachment(GLenum target, GLuint texture, int level, int width, int height) {
    gl::Handle fbo = gl::makeFramebuffer();
    gl::BindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    gl::FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, target, texture, level);
    Image image;
    image.width = width;
    image.height = height;
    image.channels = 4;
    image.pixels.resize(size_t(width) * height * 4);
    gl::ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl::ReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, image.pixels.data());
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkError("reading a texture back");
    return image;
}

}  // namespace

Image IblPrecompute::readCubeFace(GLuint cube, int face, int mip, int size) {
    const int faceSize = std::max(size >> mip, 1);
    return readAttachment(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), cube, mip, faceSize,
                          faceSize);
}

std::vector<std::vector<Image>> IblPrecompute::readCube(GLuint cube, int size, int levels) {
    std::vector<std::vector<Image>> out;
    for (int level = 0; level < levels; ++level) {
        out.emplace_back();
        for (int face = 0; face < 6; ++face)
            out.back().push_back(readCubeFace(cube, face, level, size));
    }
    return out;
}

Image IblPrecompute::readTexture(GLuint texture, int width, int height) {
    return readAttachment(GL_TEXTURE_2D, texture, 0, width, height);
}

IblMapImages IblPrecompute::readImages(const IblMaps& maps) {
    const IblSettings& s = maps.settings;
    IblMapImages images;
    images.settings = s;
    images.environment =
        readCube(maps.environment.id(), s.environmentSize, fullMipCount(s.environmentSize));
    images.derived = maps.derived;
    if (!maps.derived) return images;
    images.irradiance = readCube(maps.irradiance.id(), s.irradianceSize, 1);
    images.prefilter = readCube(maps.prefilter.id(), s.prefilterSize, s.prefilterMips);
    images.lut = readLut(maps);
    images.prefilterMaxLod = maps.prefilterMaxLod;
    return images;
}

std::unique_ptr<IblMaps> IblPrecompute::fromImages(const IblMapImages& images) {
    const IblSettings& s = images.settings;
    auto maps = makeMaps(s);
    maps->environment = makeCube(s.environmentSize, int(images.environment.size()));
    uploadCube(maps->environment.id(), images.environment);
    maps->passes.push_back({"environment", "environment cube, from another context", 0, true});
    if (!images.derived) return maps;
    maps->irradiance = makeCube(s.irradianceSize, int(images.irradiance.size()));
    uploadCube(maps->irradiance.id(), images.irradiance);
    maps->prefilter = makeCube(s.prefilterSize, int(images.prefilter.size()));
    uploadCube(maps->prefilter.id(), images.prefilter);
    maps->lut = uploadLut(images.lut);
    maps->prefilterMaxLod = images.prefilterMaxLod;
    maps->derived = true;
    maps->passes.push_back({"irradiance", "derived maps, from another context", 0, true});
    return maps;
}

Image IblPrecompute::readLut(const IblMaps& maps) {
    return readTexture(maps.lut.id(), maps.settings.lutWidth, maps.settings.lutHeight);
}

std::vector<glm::dvec3> IblPrecompute::sampleCube(GLuint cube, float lod,
                                                  const std::vector<glm::dvec3>& directions) {
    Image packed;
    packed.width = int(directions.size());
    packed.height = 1;
    packed.channels = 4;
    for (const glm::dvec3& d : directions)
        packed.pixels.insert(packed.pixels.end(), {float(d.x), float(d.y), float(d.z), 0.0f});
    gl::Handle source = gl::uploadTexture(packed, false);
    gl::RenderTarget target(packed.width, 1, 1, false);
    target.bind();
    gl::setSeamlessCubeFiltering(true);
    auto p = hostProgram("probe_cube", nullptr);
    p->use();
    gl::ActiveTexture(GL_TEXTURE0);
    gl::BindTexture(GL_TEXTURE_2D, source.id());
    p->set("uDirections", 0);
    gl::ActiveTexture(GL_TEXTURE1);
    gl::BindTexture(GL_TEXTURE_CUBE_MAP, cube);
    p->set("uMap", 1);
    p->set("uLod", lod);
    fullscreen_.draw();
    const Image values = target.read(0);
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::ActiveTexture(GL_TEXTURE0);
    std::vector<glm::dvec3> out;
    for (int i = 0; i < values.width; ++i)
        out.emplace_back(values.at(i, 0, 0), values.at(i, 0, 1), values.at(i, 0, 2));
    return out;
}

}  // namespace pbrlab