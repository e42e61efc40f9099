// The commands that write the project's generated and precomputed data: models,
// environment, converge, precompute, textures.
#include <cstdio>
#include <iostream>

#include "assets/envgen.h"
#include "assets/gltf.h"
#include "assets/texgen.h"
#include "ibl/precompute.h"
#include "render/converge.h"
#include "session.h"
#include "table.h"
#include "util/error.h"
#include "util/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

class ModelsCommand : public Command {
public:
    ModelsCommand()
        : Command("models",
                  "Write the project's own glTF test assets (deterministic): sphere-grid.glb, "
                  "textured-sphere.glb") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("--out", dir_, "Output folder")->required();
    }
    int run(const GlobalOptions&) override {
        const fs::path grid = fs::path(dir_) / "sphere-grid.glb",
                       textured = fs::path(dir_) / "textured-sphere.glb";
        writeSphereGridGlb(grid);
        writeTexturedSphereGlb(textured);
        for (const fs::path& file : {grid, textured}) {
            ModelData check = loadGltf(file);
            std::cout << "wrote " << file.string() << " (" << check.primitives.size()
                      << " primitives, " << check.vertexCount() << " vertices, "
                      << check.materials.size() << " materials, " << check.images.size()
                      << " images)\n";
        }
        return 0;
    }

private:
    std::string dir_;
};

class EnvironmentCommand : public Command {
public:
    EnvironmentCommand()
        : Command("environment",
                  "Write the project's own HDR sky (equirectangular, deterministic)") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("--out", out_, "Output .exr or .hdr")->required();
        // Not --size: an equirectangular map is always twice as wide as it is high.
        cmd.add_option("--width", width_, "Width in texels (height = width / 2)");
    }
    int run(const GlobalOptions&) override {
        Image sky = generateSkyEnvironment(width_);
        writeImage(out_, sky, FileDepth::Float32);
        std::cout << "wrote " << out_ << " (" << sky.width << "x" << sky.height << ")\n";
        return 0;
    }

private:
    std::string out_;
    int width_ = 512;
};

class ConvergeCommand : public Command {
public:
    ConvergeCommand()
        : Command("converge",
                  "Error against run time of the IBL approximations: CSV, table and plot") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("--out", options_.out, "Output folder (default: converge)");
        cmd.add_option("--size", size_, "Image side N or NxN (default 96)");
        cmd.add_option("--truth-samples", options_.truthSamples,
                       "Samples per pixel of the CPU Monte Carlo truth (default 16384)");
        cmd.add_option("--scene", options_.scene, "Scene (default sphere-grid)");
        cmd.add_flag("--quick", options_.quick, "Fewer settings (for tests)");
    }
    int run(const GlobalOptions& global) override {
        options_.size = parseSquareSize(size_);
        Session session(global);
        setVerbose(true);
        options_.onPrecomputePass = printPrecomputePass;
        auto rows = runConverge(session.paths, options_);
        writeConvergeReport(rows, options_.out);
        std::printf("%-9s %-20s %-26s %8s %10s %14s %11s %11s %13s\n", "term", "method", "setting",
                    "samples", "ms", "precompute ms", "rmse", "max error", "display rmse");
        for (const auto& r : rows)
            std::printf("%-9s %-20s %-26s %8d %10.2f %14.1f %11.3g %11.3g %13.3g\n", r.term.c_str(),
                        r.method.c_str(), r.setting.c_str(), r.samples, r.ms, r.precomputeMs,
                        r.rmse, r.maxError, r.displayRmse);
        std::cout << "wrote " << (options_.out / "converge.csv").string() << " and "
                  << (options_.out / "converge.png").string() << "\n";
        return 0;
    }

private:
    ConvergeOptions options_;
    std::string size_ = "96";
};

class PrecomputeCommand : public Command {
public:
    PrecomputeCommand()
        : Command("precompute",
                  "Split-sum maps of an environment (EXR), each pass's time and its map's error "
                  "against the CPU reference (errors.csv); --bench compares with LearnOpenGL's "
                  "sizes") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("--env", envFiles_,
                       "Equirectangular .hdr or .exr (--bench: one or more; default the "
                       "project's sky and ../shared/data/hdr when present)");
        cmd.add_option("--out", outDir_, "Output folder");
        cmd.add_option("--error-budget", errorBudget_,
                       "Choose the cheapest settings whose maps' mean errors stay within "
                       "this (e.g. 0.02)");
        cmd.add_flag("--bench", bench_,
                     "Time LearnOpenGL's sizes and sample counts against the default, both "
                     "through pbrlab's passes, and compare their maps' errors");
        cmd.add_option("--runs", runs_, "--bench: runs of each (default 3)");
        cmd.add_flag("--learnopengl", baseline_,
                     "LearnOpenGL's sizes and sample counts (the --bench baseline)");
        cmd.add_flag("--no-cache", noCache_, "Compute every map (no disk cache)");
        cmd.add_option("--env-size", ibl_.sourceSize,
                       "Size of the cube the GPU passes read (default: the prefilter's)");
        cmd.add_option("--bins", ibl_.bins,
                       "Bins per cube face side for irradiance and prefilter (default 16)");
        cmd.add_option("--irradiance-size", ibl_.irradianceSize, "Irradiance cube face size");
        cmd.add_option("--prefilter-size", ibl_.prefilterSize, "Prefiltered cube mip 0 size");
        cmd.add_option("--prefilter-mips", ibl_.prefilterMips, "Prefiltered mip count");
        cmd.add_option("--prefilter-samples", ibl_.prefilterSamples,
                       "Samples per texel (with --filtered-sampling)");
        cmd.add_option("--lut-size", ibl_.lutWidth, "BRDF LUT width (N.V)");
        cmd.add_option("--lut-height", ibl_.lutHeight, "BRDF LUT height (roughness)");
        cmd.add_option("--filtered-sampling", filteredSampling_,
                       "Prefilter by filtered importance sampling instead of bins");
    }
    int run(const GlobalOptions&) override {
        if (filteredSampling_) ibl_.prefilter = PrefilterMethod::Filtered;
        auto context = createHeadlessContext();
        logLine("gl", context->description());
        const DataPaths paths = DataPaths::locate();
        if (bench_) return benchPrecompute(paths, {envFiles_, runs_, outDir_}) ? 0 : 1;
        if (envFiles_.size() != 1 || outDir_.empty())
            throw Error("precompute: give one --env FILE and --out DIR (or --bench)");
        const Image equirect = loadEnvironmentImage(envFiles_[0]);
        IblSettings settings = baseline_ ? IblSettings::learnOpenGl() : ibl_;
        ProgramCache programs(ShaderPreprocessor({paths.shaders(), paths.labs()}));
        IblPrecompute precompute(programs, paths.shaders());
        precompute.onPass = [](const std::string& pass) { logLine("precompute", pass); };
        const IblDiskCache cache(IblDiskCache::defaultRoot());
        IblRun run;
        if (errorBudget_ > 0) {
            IblTruth truth(equirect);
            IblChoice choice = chooseIblSettings(precompute, equirect, truth, errorBudget_,
                                                 noCache_ ? nullptr : &cache);
            std::printf(
                "error budget %g (every map's mean error): %s after measuring %d of %zu "
                "settings\n",
                errorBudget_, choice.met ? "met" : "NOT met, the most accurate settings",
                choice.tried, iblLadder().size());
            run = std::move(choice.run);
        } else {
            run = precomputeWithErrors(precompute, equirect, settings, noCache_ ? nullptr : &cache);
        }
        std::cout << "precomputed " << envFiles_[0] << ": " << run.maps->settings.describe()
                  << "\n";
        writePrecompute(run, equirect, outDir_);
        return 0;
    }

private:
    std::vector<std::string> envFiles_;
    std::string outDir_;
    double errorBudget_ = 0;  // > 0: choose the settings
    bool bench_ = false;      // compare with LearnOpenGL's sizes
    int runs_ = 3;            // --bench: timed runs of each configuration
    bool noCache_ = false;
    bool baseline_ = false;  // LearnOpenGL's sizes and sample counts
    IblSettings ibl_;
    bool filteredSampling_ = false;
};

class TexturesCommand : public Command {
public:
    TexturesCommand()
        : Command("textures",
                  "Write the project's procedural metal-plates texture set (deterministic)") {}
    void declare(CLI::App& cmd) override {
        cmd.add_option("--out", dir_, "Output folder")->required();
        cmd.add_option("--size", size_, "Width and height in texels N or NxN (16..4096)");
    }
    int run(const GlobalOptions&) override {
        generateMetalPlates(dir_, parseSquareSize(size_));
        std::cout << "wrote albedo, roughness, metallic, ao and normal maps to " << dir_ << "\n";
        return 0;
    }

private:
    std::string dir_, size_ = "256";
};

}  // namespace

std::unique_ptr<Command> modelsCommand() {
    return std::make_unique<ModelsCommand>();
}
std::unique_ptr<Command> environmentCommand() {
    return std::make_unique<EnvironmentCommand>();
}
std::unique_ptr<Command> convergeCommand() {
    return std::make_unique<ConvergeCommand>();
}
std::unique_ptr<Command> precomputeCommand() {
    return std::make_unique<PrecomputeCommand>();
}
std::unique_ptr<Command> texturesCommand() {
    return std::make_unique<TexturesCommand>();
}

}  // namespace pbrlab
