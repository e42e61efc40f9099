// Runs a module on the GPU: the G-buffer pass for a scene (or uploaded probe inputs), the
// module's view over them into a float target, read back for comparison and display.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "assets/scene.h"
#include "gl/objects.h"
#include "ibl/precompute.h"
#include "pbrlab/cube_sampler.h"
#include "shader/program.h"
#include "steps/paths.h"
#include "steps/plugin_host.h"

namespace pbrlab {

// Where shaders/, labs/ and assets/ are: $PBRLAB_DATA, else the source tree it was built from.

// Whose code fills the contract functions: the reference solutions, or a student's folder.
struct StudentSource {
    std::filesystem::path dir;  // empty: reference solutions only
    bool cumulative = false;    // use the student's earlier steps too (default: stepwise)
    // The diagnosis build (kTraceNonFinite, shader/preprocess.h): the view writes which of the
    // graded step's calls made the first NaN or Inf, and its line, instead of its value.
    bool traceNonFinite = false;
};

// GLSL declarations of the step's parameter uniforms (u_<name>: float, int for int, bool and
// enum, vec3 for colour and direction), which every view program of the step gets.
std::string parameterUniforms(const ModuleDesc& d);

// The scene after the module's parameters that move things (e.g. the light direction).
Scene applyParamBindings(Scene scene, const ModuleDesc& module, const ParamValues& values);

struct RenderResult {
    Image value;                    // the view's output, RGBA float, alpha 1 where evaluated
    std::vector<Surface> surfaces;  // the inputs per pixel (when asked for)
    // The value on the GPU (RGBA32F, GL rows bottom-up), valid until the next render: what a
    // live view draws from without reading `value` back.
    GLuint valueTexture = 0;
    double milliseconds = 0;  // view pass, glFinish + steady clock (GPU timer queries
                              // are unreliable on llvmpipe)
    // The view pass and the value's read-back (when asked for): the read-back waits for the
    // GPU where glFinish may not (WebGL's finish returns before the work is done, so
    // `milliseconds` is near 0 in a browser, and this is the view's cost there).
    double pictureMilliseconds = 0;
    // The loops of the students' files in the program drawn (Program::loops) and the budget of
    // iterations they shared per invocation (loopBudget; 0: no student's loop): what the
    // diagnosis build's cut loop (shaders/view_main.frag) is read with.
    std::vector<LoopSite> loops;
    int loopBudget = 0;
};

// The probe's inputs, row 0 = top (y = 1 there, so larger values are up in pictures).
std::vector<Surface> probeSurfaces(const Probe& probe);

// One render of a module's view: what, on which inputs, how. Everything a render depends on
// is here (no renderer modes to set and restore).
struct RenderRequest {
    RenderRequest() = default;
    RenderRequest(const LoadedModule* m, const ParamValues* p, const Scene* s, StudentSource src,
                  const std::vector<Surface>* inputs, int w, int h)
        : module(m),
          params(p),
          scene(s),
          source(std::move(src)),
          surfaces(inputs),
          width(w),
          height(h) {}
    const LoadedModule* module = nullptr;
    const ParamValues* params = nullptr;
    const Scene* scene = nullptr;  // camera, lights, environment (objects when no surfaces)
    StudentSource source;
    // Null: the scene's G-buffer at width x height. Else these inputs (width * height of them,
    // row 0 = top), uploaded as textures.
    const std::vector<Surface>* surfaces = nullptr;
    int width = 0, height = 0;
    // The inputs the view saw into RenderResult::surfaces: the scene's G-buffer read back, or
    // the given surfaces as the packed floats have them.
    bool readSurfaces = false;
    // Scene: keep the G-buffer on disk when its draws read no image, and read it from there
    // (grading draws the same few scenes, small, in every process; see drawGBuffer).
    bool cacheGBuffer = false;
    // Scene: when the G-buffer target still holds this scene's G-buffer (the same key as the
    // disk cache's: camera, objects, materials, size), use it as it is; in memory only. The
    // GUI's evaluation thread: an edit of a parameter or a light draws no G-buffer (the sphere
    // grid's: 0.15 s of vertex work, and 15-30 ms of llvmpipe's rasterizer, which the
    // window's frames wait for).
    bool reuseGBuffer = false;
    // Scene: read the value back into RenderResult::value (off: only valueTexture, for a view
    // drawn straight from the GPU while the input moves).
    bool readValue = true;
    // Scene: the built-in sphere drawn with as few segments as keep its outline within half a
    // pixel of the full mesh's at this size (sphereSegments), for the GUI's live frames: the
    // G-buffer's vertices are transformed on one thread on llvmpipe, and the lesson's grid of
    // 49 full spheres takes longer than a frame at 30 a second at any picture size. Off for
    // every image that is saved, compared or graded. Drawn into the live pictures' G-buffer
    // (liveGbuffer_), so it never replaces the one a settled picture left for the next edit.
    bool coarseSpheres = false;
    // GL_TEXTURE_CUBE_MAP_SEAMLESS in the view pass: on for pictures; off for checks, so the
    // GPU reads the texels CubeSampler reads on the CPU.
    bool seamlessCubes = true;
    std::string view;  // "" the module's view.glsl, else one of its extra views
    // Surfaces only: each point drawn as a 2 x 2 quad of its own, so screen-space derivatives
    // are zero and texture() with implicit LOD reads as at a single point, whatever the
    // neighbouring points are (grading lays out unrelated points side by side).
    bool isolatePoints = false;
    // The environment maps the view reads are the scene's environment precomputed with these
    // settings (the renderer keeps them per environment and settings, for the next request).
    IblSettings ibl;
    // Sets uniforms a host-made view declares beyond the module's parameters (converge).
    std::function<void(const Program&)> extraUniforms;
};

// What a renderer is for its whole life. Neither changes what a render returns (maps read
// from the disk cache are the computed ones, bit for bit), so they are not in the request:
// they say where its caches live and whom it tells about long work.
struct RendererOptions {
    // Where precomputed maps are kept between runs (empty: no disk cache). Grading keeps its
    // converged integrals there too.
    std::filesystem::path cacheRoot = IblDiskCache::defaultRoot();
    // Told as each precompute pass starts, for progress output.
    std::function<void(const std::string&)> onPrecomputePass;
    // The GLSL every program is written in (Es300: WebGL 2's, ShaderPreprocessor).
    GlslDialect dialect = gl::kWebGl2 ? GlslDialect::Es300 : GlslDialect::Desktop450;
    // Cube maps always filtered across face edges, whatever RenderRequest::seamlessCubes asks:
    // WebGL 2 cannot turn seamless filtering off (its cube maps are always seamless), so this
    // is the browser's renderer, on the desktop (tests/test_glsl_es.cpp grades with it).
    bool seamlessCubesAlways = gl::kWebGl2;
};

class LabRenderer {
public:
    explicit LabRenderer(const DataPaths& paths, RendererOptions options = {});

    // The program recipe for a module's view: the contract functions of its own and every
    // earlier step (the student's for the graded steps, the reference solutions for the
    // others), the surface loader, the view, one permutation per (probe, light count).
    ProgramRecipe viewRecipe(const LoadedModule& module, const StudentSource& source, bool probe,
                             int lightCount, const std::string& view = "") const;

    // A function of the request (and of the files it names): the renderer holds only caches
    // between calls (programs, the G-buffer, textures, environment maps by their settings).
    RenderResult render(const RenderRequest& request);
    // Shorthands for requests with the defaults above (default IBL settings among them).
    // Pictures (seamless cube filtering), for the gallery, the CLI and the GUI.
    RenderResult renderScene(const LoadedModule& module, const ParamValues& params,
                             const Scene& scene, const StudentSource& source, int width, int height,
                             bool readSurfaces);
    RenderResult renderProbe(const LoadedModule& module, const ParamValues& params,
                             const Scene& scene, const StudentSource& source);
    // The view evaluated on arbitrary surfaces (width * height of them, row 0 = top).
    RenderResult renderSurfaces(const LoadedModule& module, const ParamValues& params,
                                const Scene& scene, const StudentSource& source,
                                const std::vector<Surface>& surfaces, int width, int height);

    ProgramCache& programs() { return programs_; }

    // The split-sum maps of the scene's environment with these settings, precomputed on first
    // use (and only for modules that need an environment), then reused for every frame.
    const IblMaps& environmentMaps(const Scene& scene, const IblSettings& settings);
    // CPU copies of the same maps, for references (read back on first use). `derived`: also
    // the irradiance, prefiltered and LUT maps (otherwise only the environment cube).
    const IblInputs& environmentInputs(const Scene& scene, const IblSettings& settings,
                                       bool derived = true);
    // A hash of every texel environmentInputs(scene, settings, derived) holds (the data, not
    // its name): what a cached value computed from those maps is keyed by.
    std::uint64_t environmentDigest(const Scene& scene, const IblSettings& settings,
                                    bool derived = true);
    // Which of an environment's maps with these settings are built (a render that reads them
    // precomputes nothing): 0 none, 1 the environment cube, 2 the derived maps too.
    int environmentMapsBuilt(const std::string& environment, const IblSettings& settings) const;
    // The maps of (environment, settings) read back from this renderer's context (null when
    // none is built), and another renderer's maps taken instead of building them: the GUI's
    // evaluation thread builds the maps, the window's renderer uploads its images
    // (milliseconds, against a precompute of tenths of a second to seconds in a frame).
    std::shared_ptr<const IblMapImages> environmentMapImages(const std::string& environment,
                                                             const IblSettings& settings) const;
    void adoptEnvironmentMaps(const std::string& environment, const IblMapImages& images);
    const std::filesystem::path& cacheRoot() const { return options_.cacheRoot; }

    // Whether the module's view may read this IBL sampler: the environment cube when it needs
    // the environment, a derived map (kDerivedMaps) only when the step that computes it comes
    // before the module's own. Anything else reads black.
    static bool mayRead(const ModuleDesc& module, const std::string& sampler);
    // The samplers a program reads that its module may not.
    static std::vector<std::string> forbiddenSamplers(const ModuleDesc& module,
                                                      const Program& program);

    // The G-buffer program for a material: one HAS_*_MAP define per map the material has and
    // the module reads.
    ProgramRecipe gbufferRecipe(const MaterialDesc& material, unsigned needs) const;

private:
    struct MaterialMap {
        unsigned need;  // SurfaceNeeds bits that read the map
        const TextureSource* source;
        const char* define;
        const char* sampler;
    };
    static std::vector<MaterialMap> materialMaps(const MaterialDesc& m);
    const gl::GpuMesh& mesh(const MeshData* data);  // nullptr: the unit sphere
    // Draws (or reads from the disk cache) the scene's G-buffer; returns the view-projection
    // it drew with.
    glm::mat4 drawGBuffer(const Scene& scene, unsigned needs, int width, int height,
                          const RenderRequest& request);
    // drawGBuffer's pieces: a material's maps bound to its program, and one draw's mesh.
    void bindMaterialMaps(const Program& program, const MaterialDesc& material);
    void drawItemMesh(const DrawItem& item, const Camera& camera, int height, bool coarseSpheres);
    // drawGBuffer's disk cache, for the lesson's sphere grid above all (49 spheres of 9216
    // triangles: half a second of llvmpipe in every grading process). The key of these draws
    // (empty: not cacheable), and the attachments read from a file or written to it.
    std::string gbufferKey(const Scene& scene, const std::vector<DrawItem>& items, unsigned needs,
                           const glm::mat4& viewProjection);
    bool readGBuffer(const std::filesystem::path& file);
    void writeGBuffer(const std::filesystem::path& file) const;
    // `viewProjection`: the G-buffer's, for the sky behind a scene (unused on probes).
    // Sets `result`'s milliseconds and loops.
    void runView(const RenderRequest& request, const Scene& scene, bool probe,
                 const std::vector<GLuint>& inputs, int width, int height,
                 const glm::mat4& viewProjection, RenderResult& result);
    // A sampler of a view's program and the texture runView binds to it.
    struct SamplerBinding {
        const char* name;
        GLenum target;
        GLuint texture;
    };
    // runView's IBL samplers: what the program uses, each with its map where the module may
    // read it, else black.
    std::vector<SamplerBinding> iblBindings(const Program& program, const ModuleDesc& module,
                                            const Scene& scene, const IblSettings& ibl);
    GLuint texture(const TextureSource& source);  // read and uploaded on first use
    // The scene's environment with these settings: the cube only, or with the derived maps
    // too.
    struct Environment;
    Environment& environment(const Scene& scene, const IblSettings& settings, bool derived);
    // The prefiltered map's largest LOD once the derived maps are built, else 0 (none bound).
    float prefilterMaxLod(const Scene& scene, const IblSettings& settings) const;
    GLuint blackTexture(GLenum target);  // 1 x 1 black, for samplers a view may not read

    DataPaths paths_;
    RendererOptions options_;
    ProgramCache programs_;
    gl::FullscreenTriangle fullscreen_;
    std::unique_ptr<gl::RenderTarget> gbuffer_, valueTarget_;
    // The live pictures' G-buffer (RenderRequest::coarseSpheres), kept at its own size: a drag
    // and the evaluation after it do not reallocate each other's (in a page both draw with
    // this renderer), and a live picture leaves the settled one's G-buffer held for the next
    // edit (gbufferHolds_).
    std::unique_ptr<gl::RenderTarget> liveGbuffer_;
    std::unique_ptr<gl::RenderTarget>& gbufferFor(bool coarseSpheres) {
        return coarseSpheres ? liveGbuffer_ : gbuffer_;
    }
    // GPU meshes by the CPU mesh they came from; the models stay alive while cached, so no
    // address is reused for another mesh.
    std::map<const MeshData*, std::unique_ptr<gl::GpuMesh>> meshes_;
    std::map<int, std::unique_ptr<gl::GpuMesh>> coarseSpheres_;  // by segments
    std::set<std::shared_ptr<const ModelData>> keepModels_;
    std::map<std::string, gl::Handle> textures_;            // by TextureSource::key
    std::map<const MeshData*, std::uint64_t> meshDigests_;  // for the G-buffer cache's key
    std::string gbufferHolds_;  // the key of the G-buffer gbuffer_ holds, if known
    std::vector<gl::Handle> probeInputs_;
    gl::Handle blackCube_, black2d_;

    struct Environment {
        std::unique_ptr<IblMaps> maps;
        std::unique_ptr<IblInputs> cpu;
        bool cpuDerived = false;
        std::uint64_t cubeDigest = 0, derivedDigest = 0;  // of the CPU copies' texels
        std::unique_ptr<EquirectSource> source;           // read only if a map is not on disk
    };
    std::map<std::string, Environment> environments_;  // by source and settings key
    std::unique_ptr<IblPrecompute> precompute_;
};

// What the host lets one invocation of a module's view loop over (loop_guard.h): the scene's
// light slots, uEnvironment where the view may read it (`environmentSize`, not below the
// default environment's), and the module's integer parameters, which are counts (samples,
// points): an estimator's sample count at its value (the view passes it to the step's
// function), any other at its largest (hammersley's view takes its point counts from its
// inputs, up to the parameter's largest).
LoopLimits viewLoopLimits(const ModuleDesc& module, const ParamValues& params, size_t lights,
                          int environmentSize);

// The segments (rings: half as many) of a sphere whose outline stays within half a pixel of a
// round one when its radius is `radiusPixels` on screen; 96 (the built-in sphere's) at most.
int sphereSegments(double radiusPixels);

// Loads an environment: a generated one's name ("sky", "sky-soft", "white", ...: envgen.h) or an
// equirectangular .hdr/.exr file; any of them followed by "#bright" is its bright texels alone
// (brightTexels: the sun of a sky, what grading's sun check needs to know it has resolved). The
// generated ones are kept in `cache` (when not empty) after the first time: the sky takes a
// second to generate, and grading reads it in every child process.
Image loadEnvironmentImage(const std::string& source, const std::filesystem::path& cache = {});

}  // namespace pbrlab
