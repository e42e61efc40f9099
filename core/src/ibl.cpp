#include "ibl.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "pbrlab/contract.h"
#include "pbrlab/error.h"
#include "pbrlab/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

const char* const kCubeFaceNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};

const DerivedMap kDerivedMaps[3] = {
    {"uIrradianceMap", "irradiance"}, {"uPrefilterMap", "prefilter"}, {"uBrdfLut", "brdf_lut"}};

std::string IblSettings::key() const {
    return "env" + std::to_string(environmentSize) + "_irr" + std::to_string(irradianceSize) +
           "_pre" + std::to_string(prefilterSize) + "x" + std::to_string(prefilterMips) + "s" +
           std::to_string(prefilterSamples) + "_lut" + std::to_string(lutSize) + "s" +
           std::to_string(lutSamples) + (filteredSampling ? "_fis" : "");
}

namespace {

gl::Handle makeCube(int size, bool mips) {
    gl::Handle cube = gl::makeTexture();
    gl::BindTexture(GL_TEXTURE_CUBE_MAP, cube.id());
    int levels = mips ? int(std::floor(std::log2(size))) + 1 : 1;
    for (int level = 0; level < levels; ++level)
        for (int face = 0; face < 6; ++face)
            gl::TexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, level, GL_RGBA32F,
                           std::max(size >> level, 1), std::max(size >> level, 1), 0, GL_RGBA,
                           GL_FLOAT, nullptr);
    gl::TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER,
                      mips ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    gl::TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        gl::TexParameteri(GL_TEXTURE_CUBE_MAP, wrap, GL_CLAMP_TO_EDGE);
    gl::TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, levels - 1);
    gl::checkError("creating a cube map");
    return cube;
}

class PassTimer {
public:
    PassTimer(IblMaps& maps, std::string name,
              const std::function<void(const std::string&)>& onPass = {})
        : maps_(maps), name_(std::move(name)) {
        if (onPass) onPass("[" + std::to_string(maps.milliseconds.size() + 1) + "/4] " + name_);
        gl::Finish();
        start_ = std::chrono::steady_clock::now();
    }
    ~PassTimer() {
        gl::Finish();
        double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
                .count();
        maps_.milliseconds[name_] = ms;
        countEvent(Counter::PrecomputePasses);
        logLine("precompute", name_ + " " + std::to_string(ms) + " ms");
    }

private:
    IblMaps& maps_;
    std::string name_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace

IblPrecompute::IblPrecompute(ProgramCache& programs, fs::path shaders, fs::path labs)
    : programs_(programs), shaders_(std::move(shaders)), labs_(std::move(labs)) {}

std::shared_ptr<Program> IblPrecompute::program(const std::string& pass,
                                                const std::string& contractId,
                                                const Defines& extra) {
    ProgramRecipe r;
    r.label = "precompute " + pass;
    r.vertex = {shaders_ / "fullscreen.vert"};
    r.fragment.push_back(shaders_ / "common.glsl");
    if (!contractId.empty())
        for (const ContractStep* step : contractClosure(contractId, {}))
            r.fragment.push_back(labs_ / step->folder() / "solution.glsl");
    r.fragment.push_back(shaders_ / "ibl" / (pass + ".frag"));
    r.defines = extra;
    r.defines["PBRLAB_IBL"] = "1";
    return programs_.get(r);
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
    gl::checkError(pass.c_str());
}

fs::path IblDiskCache::defaultRoot() {
    if (const char* c = std::getenv("PBRLAB_CACHE"); c && *c) return c;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "pbrlab";
    const char* home = std::getenv("HOME");
    return fs::path(home ? home : ".") / ".cache" / "pbrlab";
}

namespace {

// FNV-1a, 64 bits: stable across runs and compilers (std::hash is not promised to be).
struct Fnv {
    std::uint64_t h = 1469598103934665603ull;
    void add(const void* data, size_t n) {
        auto p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    }
    void add(const std::string& s) { add(s.data(), s.size()); }
};

constexpr char kCacheMagic[8] = {'P', 'B', 'R', 'L', 'C', 'U', 'B', '1'};

// levels x faces square RGBA32F images, as read back.
void writeMaps(const fs::path& file, const std::vector<std::vector<Image>>& levels) {
    fs::path tmp = file;
    tmp += ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        out.write(kCacheMagic, 8);
        std::int32_t header[2] = {std::int32_t(levels.size()), std::int32_t(levels[0].size())};
        out.write(reinterpret_cast<const char*>(header), sizeof header);
        for (const auto& faces : levels)
            for (const Image& im : faces) {
                std::int32_t size = im.width;
                out.write(reinterpret_cast<const char*>(&size), sizeof size);
                out.write(reinterpret_cast<const char*>(im.pixels.data()),
                          std::streamsize(im.pixels.size() * sizeof(float)));
            }
        if (!out) throw Error(tmp.string() + ": cannot write the IBL cache");
    }
    fs::rename(tmp, file);
}

bool readMaps(const fs::path& file, std::vector<std::vector<Image>>& levels) {
    std::ifstream in(file, std::ios::binary);
    char magic[8];
    std::int32_t header[2];
    if (!in.read(magic, 8) || std::memcmp(magic, kCacheMagic, 8) != 0 ||
        !in.read(reinterpret_cast<char*>(header), sizeof header) || header[0] < 1 ||
        header[0] > 16 || (header[1] != 1 && header[1] != 6))
        return false;
    levels.assign(size_t(header[0]), {});
    for (auto& faces : levels)
        for (int f = 0; f < header[1]; ++f) {
            std::int32_t size = 0;
            if (!in.read(reinterpret_cast<char*>(&size), sizeof size) || size < 1 || size > 8192)
                return false;
            Image im;
            im.width = im.height = size;
            im.channels = 4;
            im.pixels.resize(size_t(size) * size * 4);
            if (!in.read(reinterpret_cast<char*>(im.pixels.data()),
                         std::streamsize(im.pixels.size() * sizeof(float))))
                return false;
            faces.push_back(std::move(im));
        }
    return true;
}

gl::Handle uploadCube(const std::vector<std::vector<Image>>& levels, int allocatedLevels) {
    gl::Handle cube = makeCube(levels[0][0].width, allocatedLevels > 1);
    gl::BindTexture(GL_TEXTURE_CUBE_MAP, cube.id());
    for (size_t level = 0; level < levels.size(); ++level)
        for (int face = 0; face < 6; ++face) {
            const Image& im = levels[level][size_t(face)];
            gl::TexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face, GLint(level), GL_RGBA32F,
                           im.width, im.height, 0, GL_RGBA, GL_FLOAT, im.pixels.data());
        }
    gl::TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, GLint(levels.size()) - 1);
    return cube;
}

}  // namespace

std::string IblPrecompute::cacheKey(const Image& equirect, const IblSettings& s) const {
    Fnv f;
    f.add(equirect.pixels.data(), equirect.pixels.size() * sizeof(float));
    f.add(std::to_string(equirect.width) + "x" + std::to_string(equirect.height) + s.key());
    std::vector<fs::path> sources = {shaders_ / "common.glsl", shaders_ / "fullscreen.vert"};
    for (const auto& e : fs::directory_iterator(shaders_ / "ibl")) sources.push_back(e.path());
    for (const char* id : {"irradiance", "prefilter", "brdf_lut"})
        for (const ContractStep* step : contractClosure(id, {}))
            sources.push_back(labs_ / step->folder() / "solution.glsl");
    std::sort(sources.begin(), sources.end());
    for (const auto& p : sources) {
        std::ifstream in(p, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        f.add(p.filename().string() + text.str());
    }
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(f.h));
    return hex;
}

bool IblPrecompute::loadCached(const fs::path& dir, IblMaps& maps) const {
    std::vector<std::vector<Image>> irradiance, prefilter, lut;
    if (!readMaps(dir / "irradiance.bin", irradiance) ||
        !readMaps(dir / "prefilter.bin", prefilter) || !readMaps(dir / "lut.bin", lut) ||
        irradiance[0][0].width != maps.settings.irradianceSize ||
        prefilter.size() != size_t(maps.settings.prefilterMips) ||
        lut[0][0].width != maps.settings.lutSize)
        return false;
    maps.irradiance = uploadCube(irradiance, 1);
    maps.prefilter = uploadCube(prefilter, 2);
    maps.prefilterMaxLod = float(maps.settings.prefilterMips - 1);
    maps.lut = gl::uploadTexture(lut[0][0], false, GL_RG32F);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl::checkError("loading cached IBL maps");
    return true;
}

void IblPrecompute::storeCached(const fs::path& dir, const IblMaps& maps) const {
    const IblSettings& s = maps.settings;
    fs::create_directories(dir);
    writeMaps(dir / "irradiance.bin", readCube(maps.irradiance.id(), s.irradianceSize, 1));
    writeMaps(dir / "prefilter.bin",
              readCube(maps.prefilter.id(), s.prefilterSize, s.prefilterMips));
    writeMaps(dir / "lut.bin", {{readTexture(maps.lut.id(), s.lutSize, s.lutSize)}});
}

std::unique_ptr<IblMaps> IblPrecompute::build(const Image& equirect, const IblSettings& s,
                                              const IblDiskCache* cache) {
    auto maps = buildEnvironment(equirect, s);
    buildDerived(*maps, equirect, cache);
    return maps;
}

std::unique_ptr<IblMaps> IblPrecompute::buildEnvironment(const Image& equirect,
                                                         const IblSettings& s) {
    auto maps = std::make_unique<IblMaps>();
    maps->settings = s;
    gl::Disable(GL_DEPTH_TEST);
    gl::Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);  // precomputed maps never depend on the caller
    {
        PassTimer timer(*maps, "environment cube " + std::to_string(s.environmentSize), onPass);
        gl::Handle source = gl::uploadTexture(equirect, false);
        gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        maps->environment = makeCube(s.environmentSize, true);
        auto p = program("equirect_to_cube", "");
        p->use();
        gl::ActiveTexture(GL_TEXTURE0);
        gl::BindTexture(GL_TEXTURE_2D, source.id());
        p->set("uEquirect", 0);
        renderCube(maps->environment.id(), s.environmentSize, 0, *p, "environment cube");
        gl::BindTexture(GL_TEXTURE_CUBE_MAP, maps->environment.id());
        gl::GenerateMipmap(GL_TEXTURE_CUBE_MAP);
    }
    return maps;
}

void IblPrecompute::buildDerived(IblMaps& mapsRef, const Image& equirect,
                                 const IblDiskCache* cache) {
    if (mapsRef.derived) return;
    IblMaps* maps = &mapsRef;
    const IblSettings& s = maps->settings;
    mapsRef.derived = true;
    fs::path cacheDir = cache ? cache->root_ / "ibl" / cacheKey(equirect, s) : fs::path();
    gl::Disable(GL_DEPTH_TEST);
    gl::Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);  // precomputed maps never depend on the caller
    if (cache && loadCached(cacheDir, *maps)) {
        logLine("precompute", "irradiance, prefilter and LUT from " + cacheDir.string());
        return;
    }
    auto bindEnvironment = [&](const Program& p) {
        p.use();
        gl::ActiveTexture(GL_TEXTURE0);
        gl::BindTexture(GL_TEXTURE_CUBE_MAP, maps->environment.id());
        p.set("uEnvironment", 0);
    };
    {
        PassTimer timer(*maps, "irradiance " + std::to_string(s.irradianceSize), onPass);
        maps->irradiance = makeCube(s.irradianceSize, false);
        auto p = program("irradiance", "irradiance");
        bindEnvironment(*p);
        renderCube(maps->irradiance.id(), s.irradianceSize, 0, *p, "irradiance");
    }
    {
        PassTimer timer(*maps,
                        "prefilter " + std::to_string(s.prefilterSize) + " x" +
                            std::to_string(s.prefilterMips) + " mips, " +
                            std::to_string(s.prefilterSamples) + " samples" +
                            (s.filteredSampling ? ", filtered" : ""),
                        onPass);
        maps->prefilter = makeCube(s.prefilterSize, true);
        gl::TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, s.prefilterMips - 1);
        maps->prefilterMaxLod = float(s.prefilterMips - 1);
        Defines fis;
        if (s.filteredSampling) fis["PBRLAB_FILTERED_IS"] = "1";
        auto p = program("prefilter", "prefilter", fis);
        bindEnvironment(*p);
        for (int mip = 0; mip < s.prefilterMips; ++mip) {
            p->set("uRoughness",
                   s.prefilterMips > 1 ? float(mip) / float(s.prefilterMips - 1) : 0.f);
            p->setUnsigned("uSampleCount", unsigned(s.prefilterSamples));
            renderCube(maps->prefilter.id(), s.prefilterSize, mip, *p, "prefilter");
        }
    }
    {
        PassTimer timer(*maps,
                        "brdf lut " + std::to_string(s.lutSize) + ", " +
                            std::to_string(s.lutSamples) + " samples",
                        onPass);
        gl::RenderTarget target(s.lutSize, s.lutSize, 1, false);
        target.bind();
        auto p = program("brdf_lut", "brdf_lut");
        p->use();
        p->set("uSize", float(s.lutSize));
        p->setUnsigned("uSampleCount", unsigned(s.lutSamples));
        fullscreen_.draw();
        // read() returns row 0 at the top; flip back so that t = roughness, as rendered.
        maps->lut = gl::uploadTexture(flipRows(target.read(0)), false, GL_RG32F);
        gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    }
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (cache) {
        try {
            storeCached(cacheDir, *maps);
        } catch (const std::exception& e) {
            logLine("precompute", std::string("cache not written: ") + e.what());
        }
    }
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

}  // namespace pbrlab
