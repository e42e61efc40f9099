// The IBL inputs of LabRenderer's views: environment images (generated or read), their maps
// per (environment, settings) built on first use, CPU copies and digests for references, and
// which of the maps a step may read (the rest read black).
#include <array>
#include <chrono>
#include <cmath>

#include "assets/envgen.h"
#include "render/renderer.h"
#include "steps/contract.h"
#include "util/cache_file.h"
#include "util/digest.h"
#include "util/error.h"
#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// What a scene's environment maps are kept by: their source and every setting they depend on.
std::string environmentKey(const std::string& environment, const IblSettings& settings) {
    return environment + "|" + settings.key();
}
std::string environmentKey(const Scene& scene, const IblSettings& settings) {
    return environmentKey(scene.environment, settings);
}

}  // namespace

Image loadEnvironmentImage(const std::string& source, const fs::path& cache) {
    if (const size_t hash = source.rfind(kBrightSuffix);
        hash != std::string::npos && hash + kBrightSuffix.size() == source.size())
        return brightTexels(loadEnvironmentImage(source.substr(0, hash), cache));
    if (!isGeneratedEnvironment(source)) {
        Image image = readImage(source);
        if (image.width != 2 * image.height || image.channels < 3)
            throw Error(source +
                        ": expected an equirectangular RGB image (width = 2 x height), got " +
                        std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                        std::to_string(image.channels));
        return image;
    }
    auto generate = [&] { return generateEnvironment(source); };
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
        if (in.floats(image.pixels, size_t(size[0]) * size_t(size[1]) * 3) && in.atEnd())
            return image;
    }
    Image image = generate();
    CacheWriter out(kMagic);
    out.put(std::array<std::int32_t, 2>{image.width, image.height});
    out.bytes(image.pixels.data(), image.pixels.size() * sizeof(float));
    out.commit(file);  // no cache: fine
    return image;
}

// What names an environment's pixels without reading them (EquirectSource): a generated
// one's name with the generators' version (kEnvironmentVersion, which also covers brightTexels
// for "NAME#bright"), a file's absolute path, size and modification time.
static std::string environmentSourceKey(const std::string& source) {
    if (const size_t hash = source.rfind(kBrightSuffix);
        hash != std::string::npos && hash + kBrightSuffix.size() == source.size()) {
        const std::string base = environmentSourceKey(source.substr(0, hash));
        return base.empty() ? base : base + kBrightSuffix;
    }
    if (isGeneratedEnvironment(source))
        return "generated " + source + " v" + std::to_string(kEnvironmentVersion);
    std::error_code pathError, sizeError, timeError;
    const fs::path path = fs::absolute(source, pathError);
    const auto size = fs::file_size(path, sizeError);
    // In nanoseconds, a 64-bit count (libc++'s file clock counts in a 128-bit type).
    const long long time = std::chrono::duration_cast<std::chrono::nanoseconds>(
                               fs::last_write_time(path, timeError).time_since_epoch())
                               .count();
    // Not readable: keyed by its pixels, whose read names the problem.
    if (pathError || sizeError || timeError) return "";
    return "file " + path.string() + " " + std::to_string(size) + " " + std::to_string(time);
}

LabRenderer::Environment& LabRenderer::environment(const Scene& scene, const IblSettings& settings,
                                                   bool derived) {
    Environment& env = environments_[environmentKey(scene, settings)];
    // Also for maps adopted from another context (adoptEnvironmentMaps), whose derived maps
    // may still have to be built.
    if (!env.source)
        env.source = std::make_unique<EquirectSource>(
            environmentSourceKey(scene.environment),
            [source = scene.environment, cache = options_.cacheRoot] {
                return loadEnvironmentImage(source, cache);
            });
    auto precompute = [&]() -> IblPrecompute& {
        if (!precompute_)
            precompute_ = std::make_unique<IblPrecompute>(programs_, paths_.shaders());
        precompute_->onPass = options_.onPrecomputePass;
        return *precompute_;
    };
    IblDiskCache cache(options_.cacheRoot);
    const IblDiskCache* disk = options_.cacheRoot.empty() ? nullptr : &cache;
    if (!env.maps) {
        logLine("environment", scene.environment + " (" + settings.key() + ")");
        // The pixels, if read, are kept until the derived maps are built.
        env.maps = precompute().buildEnvironment(*env.source, settings, disk);
    }
    if (derived && !env.maps->derived) {
        precompute().buildDerived(*env.maps, *env.source, disk);
        env.source->release();
    }
    return env;
}

int LabRenderer::environmentMapsBuilt(const std::string& environment,
                                      const IblSettings& settings) const {
    auto it = environments_.find(environmentKey(environment, settings));
    if (it == environments_.end() || !it->second.maps) return 0;
    return it->second.maps->derived ? 2 : 1;
}

std::shared_ptr<const IblMapImages> LabRenderer::environmentMapImages(
    const std::string& environment, const IblSettings& settings) const {
    auto it = environments_.find(environmentKey(environment, settings));
    if (it == environments_.end() || !it->second.maps) return nullptr;
    return std::make_shared<const IblMapImages>(IblPrecompute::readImages(*it->second.maps));
}

void LabRenderer::adoptEnvironmentMaps(const std::string& environment, const IblMapImages& images) {
    Environment& env = environments_[environmentKey(environment, images.settings)];
    if (env.maps && (env.maps->derived || !images.derived)) return;  // as much held already
    env = Environment{};
    logLine("environment", environment + " (" + images.settings.key() + ") from another context");
    env.maps = IblPrecompute::fromImages(images);
}

float LabRenderer::prefilterMaxLod(const Scene& scene, const IblSettings& settings) const {
    const auto it = environments_.find(environmentKey(scene, settings));
    const bool derived = it != environments_.end() && it->second.maps && it->second.maps->derived;
    return derived ? it->second.maps->prefilterMaxLod : 0.f;
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
    auto cube = [&](GLuint texture, int size, int levels, Digest& digest,
                    std::vector<std::vector<Image>>* kept = nullptr) {
        // The texels uploaded (an RGBA32F texture reads back the same floats), else read back.
        std::vector<std::vector<Image>> mips = kept && !kept->empty()
                                                   ? std::move(*kept)
                                                   : IblPrecompute::readCube(texture, size, levels);
        if (kept) kept->clear();
        for (const auto& faces : mips)
            for (const Image& face : faces) add(digest, face);
        // The references read the maps as this renderer's views do: across face edges when
        // it cannot turn that off (WebGL 2), which then enters the maps' digest.
        if (options_.seamlessCubesAlways) digest.add(std::string("seamless"));
        return CubeSampler(std::move(mips), options_.seamlessCubesAlways);
    };
    if (!env.cpu) {
        env.cpu = std::make_unique<IblInputs>();
        Digest digest;
        env.cpu->environment = cube(maps.environment.id(), s.environmentSize,
                                    int(std::floor(std::log2(s.environmentSize))) + 1, digest,
                                    &env.maps->environmentTexels);
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

bool LabRenderer::mayRead(const ModuleDesc& d, const std::string& sampler) {
    if (!(d.needs & NeedsEnvironment)) return false;
    if (sampler == "uEnvironment") return true;
    // A view that is no step of the contract is the host's own (the error-against-run-time
    // study's methods): it compares every map, so it may read them all.
    const ContractStep* self = findContractStep(d.id);
    for (const DerivedMap& map : kDerivedMaps)
        if (sampler == map.sampler) {
            // A map no step declares is the host's alone: any step that needs the environment
            // may read it.
            const ContractStep* producer = findProvider(sampler);
            return !self || !producer || producer->step < self->step;
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

}  // namespace pbrlab
