// Image-based lighting on the GPU: an equirectangular environment becomes a cube map with
// mips, then the split-sum precompute passes (irradiance, prefiltered mip chain, BRDF LUT)
// run with the reference solutions of steps 18-20. Runs under OSMesa too. Every pass is
// counted (Counter::PrecomputePasses) and timed, so "no environment, no precompute" is
// observable.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>

#include "gl/objects.h"
#include "pbrlab/image.h"
#include "shader/program.h"

namespace pbrlab {

struct IblSettings {
    int environmentSize = 256;  // cube face size of the radiance map (mips to 1x1)
    int irradianceSize = 32;
    int prefilterSize = 128;  // mip 0 of the prefiltered map
    int prefilterMips = 5;    // roughness 0, 0.25, ... 1
    int prefilterSamples = 256;
    int lutSize = 128;
    int lutSamples = 512;
    // Prefilter with filtered importance sampling (source mip from the pdf) instead of the
    // step 19 function: the default for pictures, off to study the plain estimator.
    bool filteredSampling = true;
    std::string key() const;  // all of the above, for caches
};

struct IblMaps {
    IblSettings settings;
    gl::Handle environment, irradiance, prefilter, lut;
    bool derived = false;  // irradiance, prefilter and lut are built (buildDerived)
    float prefilterMaxLod = 0;
    std::map<std::string, double> milliseconds;  // per pass: glFinish + steady clock
};

// The precomputed maps on disk (irradiance cube, prefiltered mips, LUT), keyed by the
// environment's pixels, the settings and every GLSL file that computes them, so that an edit
// to a solution or a shader never reads stale maps.
class IblDiskCache {
public:
    explicit IblDiskCache(std::filesystem::path root) : root_(std::move(root)) {}
    // $PBRLAB_CACHE, else $XDG_CACHE_HOME/pbrlab, else ~/.cache/pbrlab.
    static std::filesystem::path defaultRoot();
    const std::filesystem::path& root() const { return root_; }

private:
    friend class IblPrecompute;
    std::filesystem::path root_;
};

class IblPrecompute {
public:
    IblPrecompute(ProgramCache& programs, std::filesystem::path shaders,
                  std::filesystem::path labs);
    // With a cache: the maps come from disk when present (only the environment cube is built),
    // else they are computed and stored.
    std::unique_ptr<IblMaps> build(const Image& equirect, const IblSettings& settings,
                                   const IblDiskCache* cache = nullptr);
    // The two halves of build(): the environment cube with its mips (what steps 17-19 read),
    // then the maps that steps 18-20's reference solutions compute from it (what step 21
    // reads), only when something samples them.
    std::unique_ptr<IblMaps> buildEnvironment(const Image& equirect, const IblSettings& settings);
    void buildDerived(IblMaps& maps, const Image& equirect, const IblDiskCache* cache = nullptr);
    // Called as each pass starts ("[2/4] irradiance 32"): progress for people waiting.
    std::function<void(const std::string&)> onPass;

    // Read-back for files and tests: one face (0..5 = +x -x +y -y +z -z) of a cube mip.
    static Image readCubeFace(GLuint cube, int face, int mip, int size);
    // Mips 0..levels-1, six faces each.
    static std::vector<std::vector<Image>> readCube(GLuint cube, int size, int levels);
    // A 2D texture's level 0, row 0 = t = 0 (as stored, not flipped).
    static Image readTexture(GLuint texture, int width, int height);

private:
    std::shared_ptr<Program> program(const std::string& pass, const std::string& contractId,
                                     const Defines& extra = {});
    void renderCube(GLuint cube, int size, int mip, const Program& program,
                    const std::string& pass);
    std::string cacheKey(const Image& equirect, const IblSettings& settings) const;
    bool loadCached(const std::filesystem::path& dir, IblMaps& maps) const;
    void storeCached(const std::filesystem::path& dir, const IblMaps& maps) const;
    ProgramCache& programs_;
    std::filesystem::path shaders_, labs_;
    gl::FullscreenTriangle fullscreen_;
};

// The maps the precompute derives from the environment, each computed with the reference
// solution of one contract step: a view may read a map only when that step comes before its
// own (no step sees what its own or a later step's reference computed).
struct DerivedMap {
    const char* sampler;   // the contract's uniform name
    const char* producer;  // the contract step whose reference solution computes it
};
extern const DerivedMap kDerivedMaps[3];

// Six faces named +x -x +y -y +z -z, as cmgen-like tools expect.
extern const char* const kCubeFaceNames[6];

}  // namespace pbrlab
