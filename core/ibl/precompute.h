// Image-based lighting maps: an equirectangular environment becomes a cube map with mips
// (uEnvironment), then the split-sum precompute builds the irradiance cube, the prefiltered
// mip chain and the BRDF LUT. The default passes are the host's own, chosen by their measured
// error against run time (docs/ibl.md): cube maps resampled on the CPU, the irradiance and the
// rough mips convolved on the CPU from the environment's power binned per cube texel, the LUT
// by quadrature on the GPU, computed once whatever the environment. Steps 18-20's reference
// solutions, filtered importance sampling and LearnOpenGL's Riemann sum remain selectable (the
// baseline of `pbrlab precompute --bench`). Runs under OSMesa too. Every pass is counted
// (Counter::PrecomputePasses) and timed, so "no environment, no precompute" is observable.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "assets/image_io.h"
#include "gl/objects.h"
#include "shader/program.h"
#include "steps/contract.h"

namespace pbrlab {

// How the irradiance map and the rough prefiltered mips are computed (docs/ibl.md).
enum class IrradianceMethod {
    Bins,      // the environment binned per texel of a small cube (power, mean direction and
               // spread of each bin), convolved with the cosine (ibl/precompute.cpp, convolveBins)
    StepPass,  // the pass the step providing uIrradianceMap declares (step 18's texel sum)
    Riemann,   // LearnOpenGL's Riemann sum over the hemisphere
};

enum class PrefilterMethod {
    Bins,      // the same bins convolved with the prefilter's lobe
    Filtered,  // filtered importance sampling (each sample reads the mip of its solid angle)
    StepPass,  // the pass the step providing uPrefilterMap declares (GGX importance sampling)
};

enum class LutMethod {
    Quadrature,  // Gauss-Legendre over the half vector, the exact range where N.L > 0 (GPU)
    StepPass,    // the pass the step providing uBrdfLut declares (Hammersley Monte Carlo)
};

struct IblSettings {
    int environmentSize = 256;  // uEnvironment: the sky behind, what steps 17-19 read
    // The cube the GPU passes read (mips to 1x1): the prefilter's source, and uEnvironment for
    // the step 18 and Riemann irradiance. 0: prefilterSize.
    int sourceSize = 0;
    int bins = 16;  // Bins: a cube of bins x bins per face
    IrradianceMethod irradiance = IrradianceMethod::Bins;
    int irradianceSize = 32;
    double riemannStep = 0.025;  // Riemann: radians in theta and phi (LearnOpenGL's sampleDelta)
    int prefilterSize = 128;     // mip 0 of the prefiltered map
    int prefilterMips = 5;       // roughness 0, 0.25, ... 1
    // Mip 0 (roughness 0, a mirror) is the environment itself, resampled; false: sampled like
    // the other mips.
    bool prefilterMirrorExact = true;
    int mirrorSupersample = 1;  // mip 0 resampled at this many times its size, then averaged
    PrefilterMethod prefilter = PrefilterMethod::Bins;  // the mips of roughness > 0
    int prefilterSamples = 64;                          // Filtered, Plain: per texel of each mip
    double filteredLodBias = 1.0;  // Filtered: mips added to the one of the sample's solid angle
    LutMethod lut = LutMethod::Quadrature;
    int lutWidth = 1024;  // N.V: the LUT changes fastest at grazing angles
    int lutHeight = 32;   // roughness
    int lutSamples = 64;  // StepPass: Monte Carlo samples (Quadrature: fixed, 64 nodes)

    int source() const { return sourceSize > 0 ? sourceSize : prefilterSize; }
    // How each map is computed, for labels: "bins 16", "64 filtered samples (bias 1)".
    std::string irradianceBy() const;
    std::string prefilterBy() const;
    std::string key() const;     // what the environment's maps depend on, for caches
    std::string lutKey() const;  // what the LUT depends on
    // One line for people: "irradiance bins 16 -> 32, prefilter 128 x5 64 samples FIS ...".
    std::string describe() const;
    // LearnOpenGL's sizes and sample counts through pbrlab's passes: 512 environment,
    // irradiance by a Riemann sum with step 0.025, 128 x 5 mips prefiltered with 1024 plain
    // GGX importance samples each, a 512 x 512 LUT with 1024 samples.
    static IblSettings learnOpenGl();
};

// One precompute pass as it ran: which map, what it did, how long (glFinish + steady clock).
struct IblPass {
    std::string map;    // "environment", "irradiance", "prefilter", "lut"
    std::string label;  // "irradiance bins 16 -> 32"
    double milliseconds = 0;
    bool cached = false;  // read from the disk cache, not computed
};

struct IblMaps {
    IblSettings settings;
    gl::Handle environment, irradiance, prefilter, lut;
    bool derived = false;  // irradiance, prefilter and lut are built (buildDerived)
    float prefilterMaxLod = 0;
    std::vector<IblPass> passes;
    double milliseconds(const std::string& map) const;  // the passes of that map, summed
    // The texels uploaded to `environment` (mips[level][face], as readCube returns them), kept
    // from buildEnvironment for a caller that wants them on the CPU (none: read them back).
    std::vector<std::vector<Image>> environmentTexels;
};

// The maps as images, read back on one context to be uploaded on another (the GUI's evaluation
// thread builds them, the window's renderer takes them): mips[level][face], RGBA, row 0 = t = 0.
struct IblMapImages {
    IblSettings settings;
    std::vector<std::vector<Image>> environment;  // every mip
    bool derived = false;                         // the maps below are held (IblMaps::derived)
    std::vector<std::vector<Image>> irradiance, prefilter;
    Image lut;  // RGBA as read back; the texture holds its red and green
    float prefilterMaxLod = 0;
};

// The precomputed maps on disk: the irradiance cube and prefiltered mips keyed by the
// environment's pixels, the settings and every GLSL file and CPU algorithm that computes them;
// the LUT keyed by its own settings and files only (it does not depend on the environment).
// An edit to a solution or a shader never reads stale maps.
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

// An equirectangular environment for the precompute, read only when a map must be computed.
// Its key names its pixels without them (a generated sky's name and generator version, a
// file's path, size and modification time), so maps kept on disk are found without reading or
// decoding it: a sun sky is 25 MB of floats. An image in memory is its own source, keyed by
// its pixels.
class EquirectSource {
public:
    EquirectSource(const Image& image);  // NOLINT(google-explicit-constructor): any image is one
    EquirectSource(std::string key, std::function<Image()> load);
    const std::string& key() const;
    const Image& image() const;  // read on first use
    void release();              // forget the pixels read (they are read again when needed)

private:
    const Image* image_ = nullptr;
    std::function<Image()> load_;
    mutable std::unique_ptr<Image> loaded_;
    mutable std::string key_;
};

class IblPrecompute {
public:
    IblPrecompute(ProgramCache& programs, std::filesystem::path shaders);
    // With a cache: the maps come from disk when present, else they are computed and stored.
    std::unique_ptr<IblMaps> build(const Image& equirect, const IblSettings& settings,
                                   const IblDiskCache* cache = nullptr);
    // The two halves of build(): the environment cube with its mips (what steps 17-19 read),
    // then the maps derived from the environment (what step 21 reads), only when something
    // samples them. `maps` may come from makeMaps() instead, without an environment cube.
    std::unique_ptr<IblMaps> buildEnvironment(const EquirectSource& equirect,
                                              const IblSettings& settings,
                                              const IblDiskCache* cache = nullptr);
    void buildDerived(IblMaps& maps, const EquirectSource& equirect,
                      const IblDiskCache* cache = nullptr);
    static std::unique_ptr<IblMaps> makeMaps(const IblSettings& settings);
    // Every map `maps` holds (the derived ones when built) read back, and maps made from such
    // images on another context: the same texels, no pass run.
    static IblMapImages readImages(const IblMaps& maps);
    static std::unique_ptr<IblMaps> fromImages(const IblMapImages& images);
    // Called as each pass starts ("[2/4] irradiance bins 16 -> 32"): progress for people.
    std::function<void(const std::string&)> onPass;

    // Read-back for files and tests: one face (0..5 = +x -x +y -y +z -z) of a cube mip.
    static Image readCubeFace(GLuint cube, int face, int mip, int size);
    // Mips 0..levels-1, six faces each.
    static std::vector<std::vector<Image>> readCube(GLuint cube, int size, int levels);
    // A 2D texture's level 0, row 0 = t = 0 (as stored, not flipped).
    static Image readTexture(GLuint texture, int width, int height);
    static Image readLut(const IblMaps& maps);
    // A cube map read at these directions, mip `lod`, as a view's textureLod reads it
    // (bilinear, seamless): for measuring the maps at points independent of their size.
    std::vector<glm::dvec3> sampleCube(GLuint cube, float lod,
                                       const std::vector<glm::dvec3>& directions);

private:
    // The host's own method shaders (shaders/ibl/<stem>.frag).
    static constexpr const char* kFilteredPrefilterShader = "prefilter_filtered";
    static constexpr const char* kRiemannIrradianceShader = "irradiance_riemann";
    static constexpr const char* kQuadratureLutShader = "lut_quadrature";
    std::shared_ptr<Program> hostProgram(const std::string& shader, const char* linkedSampler,
                                         const Defines& extra = {});
    std::shared_ptr<Program> stepProgram(const char* sampler);
    std::shared_ptr<Program> program(const std::string& label,
                                     const std::filesystem::path& fragment,
                                     const ContractStep* linked, const Defines& extra);
    // The generic passes: every face of one cube mip, or one 2D texture, drawn full screen.
    void renderCube(GLuint cube, int size, int mip, const Program& program,
                    const std::string& pass);
    void renderSquare(GLuint texture, int width, int height, const Program& program,
                      const std::string& pass);
    struct Inputs;
    void buildIrradiance(IblMaps& maps, Inputs& inputs);
    void buildPrefilter(IblMaps& maps, Inputs& inputs);
    void buildLut(IblMaps& maps);
    // The files a map's programs read: the host's shaders and, for each sampler, the pass of
    // the step that provides it and every solution that pass links.
    std::vector<std::filesystem::path> sources(const std::vector<std::string>& hostShaders,
                                               const std::vector<const char*>& samplers) const;
    std::string mapsKey(const EquirectSource& equirect, const IblSettings& settings) const;
    static std::string environmentKey(const EquirectSource& equirect, int size, int levels);
    std::string lutKey(const IblSettings& settings) const;
    ProgramCache& programs_;
    std::filesystem::path shaders_;
    gl::FullscreenTriangle fullscreen_;
};

// The maps the precompute derives from the environment, by their contract sampler names, and
// the kind of pass that fills each. The step each stands in for declares it (step.json
// "precompute" or "provides", findProvider): a view may read a map only when that step comes
// before its own (no step sees what its own or a later step computes).
struct DerivedMap {
    const char* sampler;  // the contract's uniform name
    ContractStep::PrecomputePass::Kind kind;
};
extern const DerivedMap kDerivedMaps[3];

// Six faces named +x -x +y -y +z -z, as cmgen-like tools expect.
extern const char* const kCubeFaceNames[6];

// The unit direction through the centre of texel (x, y) of a cube face (OpenGL's convention,
// as shaders/ibl/cube_face.glsl; row y = 0 has t = 0).
glm::dvec3 cubeTexelDirection(int face, double x, double y, int size);

// An equirectangular image resampled into a cube map's level 0 (bilinear, as a GPU sampler
// with GL_REPEAT in u and GL_CLAMP_TO_EDGE in v), and the box-filtered mips below it (as
// glGenerateMipmap): levels[mip][face], RGBA.
std::vector<std::vector<Image>> equirectToCube(const Image& equirect, int size, int levels);

}  // namespace pbrlab
