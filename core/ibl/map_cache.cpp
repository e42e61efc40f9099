// The precomputed maps on disk: where the cache lives, its file format, and the keys that say
// when a cached map is still what the settings, the environment and the shaders would compute.
#include "ibl/map_cache.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "ibl/precompute.h"
#include "steps/contract.h"
#include "util/cache_file.h"
#include "util/digest.h"
#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

fs::path IblDiskCache::defaultRoot() {
    if (const char* c = std::getenv("PBRLAB_CACHE"); c && *c) return c;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "pbrlab";
    const char* home = std::getenv("HOME");
    return fs::path(home ? home : ".") / ".cache" / "pbrlab";
}

namespace {

constexpr char kCacheMagic[8] = {'P', 'B', 'R', 'L', 'C', 'U', 'B', '3'};

}  // namespace

// levels x faces RGBA32F images (faces: 6, or 1 for the LUT), as read back (cache_file.h).
bool writeMaps(const fs::path& file, const std::vector<std::vector<Image>>& levels) {
    CacheWriter out(kCacheMagic);
    out.put(
        std::array<std::int32_t, 2>{std::int32_t(levels.size()), std::int32_t(levels[0].size())});
    for (const auto& faces : levels)
        for (const Image& im : faces) {
            out.put(std::array<std::int32_t, 2>{im.width, im.height});
            out.bytes(im.pixels.data(), im.pixels.size() * sizeof(float));
        }
    return out.commit(file);
}

bool readMaps(const fs::path& file, std::vector<std::vector<Image>>& levels) {
    CacheReader in(file, kCacheMagic);
    std::int32_t header[2];
    if (!in.get(header) || header[0] < 1 || header[0] > 16 || (header[1] != 1 && header[1] != 6))
        return false;
    levels.assign(size_t(header[0]), {});
    for (auto& faces : levels)
        for (int f = 0; f < header[1]; ++f) {
            std::int32_t size[2] = {0, 0};
            if (!in.get(size) || size[0] < 1 || size[0] > 8192 || size[1] < 1 || size[1] > 8192)
                return false;
            Image im;
            im.width = size[0];
            im.height = size[1];
            im.channels = 4;
            if (!in.floats(im.pixels, size_t(size[0]) * size_t(size[1]) * 4)) return false;
            faces.push_back(std::move(im));
        }
    return in.atEnd();
}

bool sizesAre(const std::vector<std::vector<Image>>& levels, int size, int count) {
    if (int(levels.size()) != count) return false;
    for (size_t l = 0; l < levels.size(); ++l)
        for (const Image& im : levels[l])
            if (im.width != std::max(size >> l, 1) || im.height != im.width) return false;
    return levels[0].size() == 6;
}

void storeQuietly(const fs::path& file, const std::vector<std::vector<Image>>& levels) {
    if (!writeMaps(file, levels)) logLine("precompute", "cache not written: " + file.string());
}

std::vector<fs::path> IblPrecompute::sources(const std::vector<std::string>& hostShaders,
                                             const std::vector<const char*>& samplers) const {
    std::vector<fs::path> files = {shaders_ / "common.glsl", shaders_ / "fullscreen.vert",
                                   shaders_ / "ibl" / "cube_face.glsl"};
    for (const std::string& s : hostShaders) files.push_back(shaders_ / "ibl" / (s + ".frag"));
    for (const char* sampler : samplers)
        if (const ContractStep* provider = findProvider(sampler)) {
            if (provider->precompute) files.push_back(provider->precompute->shader);
            for (const ContractStep* step : contractClosure(provider->id, {}))
                files.push_back(referenceImplementation(*step));
        }
    return files;
}

namespace {

void addFiles(Digest& f, std::vector<fs::path> files) {
    std::sort(files.begin(), files.end());
    files.erase(std::unique(files.begin(), files.end()), files.end());
    for (const auto& p : files) {
        std::ifstream in(p, std::ios::binary);
        std::stringstream text;
        text << in.rdbuf();
        f.add(p.filename().string() + text.str());
    }
}

}  // namespace

std::string IblPrecompute::mapsKey(const EquirectSource& equirect, const IblSettings& s) const {
    Digest f;
    f.add(equirect.key() + s.key() + kCpuMapsVersion);
    // Every file that can compute the irradiance or the prefiltered map: the host's methods,
    // and the passes of the steps that provide the maps with what they link.
    addFiles(f, sources({kFilteredPrefilterShader, kRiemannIrradianceShader},
                        {"uPrefilterMap", "uIrradianceMap"}));
    return f.hex();
}

// The environment cube is resampled on the CPU (equirectToCube): its texels depend on the
// equirectangular pixels, the cube's size and mip count and that code, no shader.
std::string IblPrecompute::environmentKey(const EquirectSource& equirect, int size, int levels) {
    Digest f;
    f.add(equirect.key() + " cube " + std::to_string(size) + " x" + std::to_string(levels) +
          kCpuMapsVersion);
    return f.hex();
}

EquirectSource::EquirectSource(const Image& image) : image_(&image) {}

EquirectSource::EquirectSource(std::string key, std::function<Image()> load)
    : load_(std::move(load)), key_(std::move(key)) {}

const std::string& EquirectSource::key() const {
    if (key_.empty()) {
        const Image& i = image();
        Digest f;
        f.add(i.pixels.data(), i.pixels.size() * sizeof(float));
        f.add(std::to_string(i.width) + "x" + std::to_string(i.height) + "x" +
              std::to_string(i.channels));
        key_ = "pixels " + f.hex();
    }
    return key_;
}

const Image& EquirectSource::image() const {
    if (image_) return *image_;
    if (!loaded_) loaded_ = std::make_unique<Image>(load_());
    return *loaded_;
}

void EquirectSource::release() {
    loaded_.reset();
}

std::string IblPrecompute::lutKey(const IblSettings& s) const {
    Digest f;
    f.add(s.lutKey());
    addFiles(f, sources({kQuadratureLutShader}, {"uBrdfLut"}));
    return f.hex();
}

}  // namespace pbrlab
