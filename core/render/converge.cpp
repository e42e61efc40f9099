#include "render/converge.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <future>
#include <iostream>
#include <thread>

#include "assets/envgen.h"
#include "pbrlab/ibl_reference.h"
#include "steps/contract.h"
#include "util/error.h"
#include "util/log.h"
#include "util/parallel.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// A view of the host's own, not a step: shaders/converge/<name>/view.glsl with every step's
// reference solution linked in (as every view is). Its id names no contract step, so the
// renderer lets it read every precomputed map (LabRenderer::mayRead).
struct Method {
    ModuleDesc desc;
    LoadedModule module;
    Method(const DataPaths& paths, const std::string& name, std::vector<ParamDecl> params = {}) {
        desc.id = name;
        desc.components = 3;
        desc.needs = NeedsMaterial | NeedsEnvironment;
        desc.params = std::move(params);
        module = {&desc, {}, paths.shaders() / "converge" / name};
    }
};

// llvmpipe compiles a shader's machine code at its first draw: render once untimed, then keep
// the fastest of three (the least disturbed by the rest of the machine).
RenderResult timedRender(LabRenderer& renderer, const RenderRequest& request) {
    RenderResult best = renderer.render(request);
    best.milliseconds = 1e300;
    for (int i = 0; i < 3; ++i) {
        RenderResult r = renderer.render(request);
        if (r.milliseconds < best.milliseconds) best = std::move(r);
    }
    return best;
}

// The specular integral of f_spec (N.L) L over the environment taken as piecewise constant
// per texel: exact for that image, and converged where Monte Carlo with BRDF sampling is
// not (rough lobes that contain a 20000-bright sun of a few texels). Same integrand as step 17:
// D G F / (4 N.V) with G for IBL (k = r^2 / 2) and Schlick's F on V.H.
glm::dvec3 specularByTexels(const Image& env, const glm::dvec3& N, const glm::dvec3& V,
                            const glm::dvec3& F0, double roughness) {
    const double NdotV = std::max(glm::dot(N, V), 1e-4);
    glm::dvec3 sum(0);
    for (int y = 0; y < env.height; ++y) {
        double t0 = ref::kPi * y / env.height, t1 = ref::kPi * (y + 1) / env.height;
        double solidAngle = 2 * ref::kPi / env.width * (std::cos(t0) - std::cos(t1));
        for (int x = 0; x < env.width; ++x) {
            glm::dvec3 L = ref::equirectDirection({(x + 0.5) / env.width, (y + 0.5) / env.height});
            double NdotL = glm::dot(N, L);
            if (NdotL <= 0) continue;
            glm::dvec3 H = glm::normalize(L + V);
            double D = ref::distributionGGX(N, H, roughness);
            double G = ref::geometrySmithIBL(NdotV, NdotL, roughness);
            glm::dvec3 F = ref::fresnelSchlick(std::max(glm::dot(V, H), 0.0), F0);
            glm::dvec3 radiance(env.at(x, y, 0), env.at(x, y, 1), env.at(x, y, 2));
            sum += radiance * F * (D * G / (4 * NdotV) * solidAngle);
        }
    }
    return sum;
}

// A 2x box-filtered copy (energy kept): the texel sum at a quarter of the cost, for lobes
// much wider than a texel.
Image halve(const Image& im) {
    Image h;
    h.width = im.width / 2;
    h.height = im.height / 2;
    h.channels = 3;
    h.pixels.resize(size_t(h.width) * h.height * 3);
    for (int y = 0; y < h.height; ++y)
        for (int x = 0; x < h.width; ++x)
            for (int c = 0; c < 3; ++c)
                h.at(x, y, c) =
                    0.25f * (im.at(2 * x, 2 * y, c) + im.at(2 * x + 1, 2 * y, c) +
                             im.at(2 * x, 2 * y + 1, c) + im.at(2 * x + 1, 2 * y + 1, c));
    return h;
}

struct Truth {
    std::vector<Surface> surfaces;
    std::vector<glm::dvec3> specular, diffuse;
};

void score(ConvergeRow& row, const Image& value, const Truth& truth,
           const std::vector<glm::dvec3>& reference) {
    double sum = 0, sumDisplay = 0;
    int n = 0;
    row.maxError = 0;
    for (size_t i = 0; i < truth.surfaces.size(); ++i) {
        if (!truth.surfaces[i].covered) continue;
        for (int c = 0; c < 3; ++c) {
            double g = value.pixels[i * 4 + size_t(c)], r = reference[i][c];
            double e = g - r;
            sum += e * e;
            auto reinhard = [](double x) { return std::max(x, 0.0) / (1 + std::max(x, 0.0)); };
            double d = reinhard(g) - reinhard(r);
            sumDisplay += d * d;
            row.maxError = std::max(row.maxError, std::abs(e));
            ++n;
        }
    }
    row.rmse = n ? std::sqrt(sum / n) : 0;
    row.displayRmse = n ? std::sqrt(sumDisplay / n) : 0;
}

// What every measured method shares: the scene, the renderer that times it, the truth it is
// scored against and the rows measured so far.
struct Measurements {
    const ConvergeOptions& o;
    const Scene& scene;
    LabRenderer& renderer;
    const ParamValues none;  // what the parameterless methods are given
    Truth truth;
    std::vector<ConvergeRow> rows;

    Measurements(const ConvergeOptions& options, const Scene& s, LabRenderer& r)
        : o(options), scene(s), renderer(r) {}

    // A picture of the scene with these parameters and maps (the default view).
    RenderRequest request(const Method& method, const ParamValues& params,
                          const IblSettings& ibl) const {
        RenderRequest r{&method.module, &params, &scene, {}, nullptr, o.size, o.size};
        r.ibl = ibl;
        return r;
    }

    // A row scored against `reference` (the truth's specular or diffuse term), then kept.
    void keep(ConvergeRow& row, const Image& value, const std::vector<glm::dvec3>& reference) {
        score(row, value, truth, reference);
        rows.push_back(row);
    }
};

// The truth, per pixel of the scene, in double precision on the CPU.
Truth cpuTruth(const Measurements& m, const Method& splitSum, const Image& equirect,
               const ref::EquirectEnvironment& environment) {
    Truth truth;
    {
        RenderRequest r = m.request(splitSum, m.none, m.o.ibl);
        r.readSurfaces = true;
        truth.surfaces = m.renderer.render(r).surfaces;
    }
    truth.specular.assign(truth.surfaces.size(), glm::dvec3(0));
    truth.diffuse = truth.specular;
    auto start = std::chrono::steady_clock::now();
    const Image coarse = halve(equirect);
    parallelFor(truth.surfaces.size(), [&](size_t i) {
        const Surface& s = truth.surfaces[size_t(i)];
        if (!s.covered) return;
        glm::dvec3 F0 = ref::baseReflectivity(s.albedo, s.metallic);
        // Narrow lobes: BRDF-sampled Monte Carlo converges (the sun, when in the lobe, is hit
        // often). Wide lobes (alpha = r^2 >= 0.25, > 14 degrees): the texel sum.
        truth.specular[size_t(i)] =
            s.roughness < 0.5 ? ref::specularIBLReference(environment, s.normal, s.view, F0,
                                                          s.roughness, unsigned(m.o.truthSamples))
                              : specularByTexels(coarse, s.normal, s.view, F0, s.roughness);
        truth.diffuse[size_t(i)] = s.albedo * ref::irradianceAt(equirect, s.normal);
    });
    logLine(
        "converge",
        "CPU truth: " +
            std::to_string(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()) +
            " s");
    return truth;
}

// Brute force: every frame pays for every sample. `method` names the rows: brute_force
// (half vectors from D (N.H)) or brute_force_vndf (from the normals visible from V), at the
// same counts.
void measureBruteForce(Measurements& m, const Method& bruteForce, const std::string& method) {
    for (int n = 1; n <= m.o.maxBruteForce; n *= (m.o.quick ? 16 : 2)) {
        ParamValues params(bruteForce.desc.params);
        params.set("samples", glm::dvec3(n, 0, 0));
        RenderResult r = timedRender(m.renderer, m.request(bruteForce, params, m.o.ibl));
        ConvergeRow row{"specular", method, "N=" + std::to_string(n), n, r.milliseconds};
        m.keep(row, r.value, m.truth.specular);
    }
}

// One split-sum row: the frame with maps of these settings, and the precompute they cost.
void measureSplitSumRow(Measurements& m, const Method& splitSum, const IblSettings& s,
                        const std::string& setting, int samples) {
    RenderResult r = timedRender(m.renderer, m.request(splitSum, m.none, s));
    const IblMaps& maps = m.renderer.environmentMaps(m.scene, s);
    ConvergeRow row{"specular",     "split_sum",
                    setting,        samples,
                    r.milliseconds, maps.milliseconds("prefilter") + maps.milliseconds("lut")};
    m.keep(row, r.value, m.truth.specular);
}

// Split sum: a cheap frame, after a precompute whose quality varies.
void measureSplitSum(Measurements& m, const Method& splitSum) {
    const IblSettings& defaults = m.o.ibl;
    std::vector<int> prefilterSamples =
        m.o.quick ? std::vector<int>{16, 256} : std::vector<int>{16, 32, 64, 128, 256, 512, 1024};
    for (bool fis : {false, true})
        for (int samples : prefilterSamples) {
            IblSettings s = defaults;
            s.prefilterSamples = samples;
            s.prefilter = fis ? PrefilterMethod::Filtered : PrefilterMethod::StepPass;
            measureSplitSumRow(m, splitSum, s,
                               std::string("prefilter=") + std::to_string(samples) +
                                   (fis ? " fis=on" : " fis=off"),
                               samples);
        }
    std::vector<int> lutSizes =
        m.o.quick ? std::vector<int>{16, 128} : std::vector<int>{16, 32, 64, 128, 256, 512};
    for (int size : lutSizes) {
        IblSettings s = defaults;
        s.lutWidth = s.lutHeight = size;
        measureSplitSumRow(m, splitSum, s, "lut=" + std::to_string(size), s.lutSamples);
    }
}

// The diffuse term from the irradiance cube, with the precompute it costs.
void measureConvolution(Measurements& m, const Method& convolution) {
    const IblSettings& defaults = m.o.ibl;
    RenderResult r = timedRender(m.renderer, m.request(convolution, m.none, defaults));
    ConvergeRow row{"diffuse",
                    "convolution",
                    "irradiance " + std::to_string(defaults.irradianceSize) + "^2 x 6",
                    32 * 128,
                    r.milliseconds,
                    m.renderer.environmentMaps(m.scene, defaults).milliseconds("irradiance")};
    m.keep(row, r.value, m.truth.diffuse);
}

// The diffuse term from 9 spherical-harmonic coefficients, projected on the CPU (timed).
void measureHarmonics(Measurements& m, const Method& harmonics, const Image& equirect) {
    auto t0 = std::chrono::steady_clock::now();
    ref::SH9 sh = ref::projectSH9(equirect);
    double shMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    RenderRequest shRequest = m.request(harmonics, m.none, m.o.ibl);
    shRequest.extraUniforms = [&](const Program& p) {
        std::vector<glm::vec3> c;
        for (const auto& v : sh.c) c.emplace_back(v);
        p.set("uSH[0]", c);
    };
    RenderResult r = timedRender(m.renderer, shRequest);
    ConvergeRow row{"diffuse", "spherical_harmonics", "9 coefficients (CPU projection)",
                    9,         r.milliseconds,        shMs};
    m.keep(row, r.value, m.truth.diffuse);
}

}  // namespace

std::vector<ConvergeRow> runConverge(const DataPaths& paths, const ConvergeOptions& o) {
    Scene scene = loadScene(paths.scene(o.scene));
    Image equirect = loadEnvironmentImage(scene.environment);
    ref::EquirectEnvironment environment(equirect);
    // Measure every precompute: a renderer of its own, without the disk cache.
    RendererOptions noDiskCache;
    noDiskCache.cacheRoot.clear();
    noDiskCache.onPrecomputePass = o.onPrecomputePass;
    LabRenderer renderer(paths, noDiskCache);

    Method bruteForce(paths, "specular_brute_force",
                      {intParam("samples", 64, 1, 1 << 20, "Monte Carlo samples")});
    Method visibleNormals(paths, "specular_visible_normals",
                          {intParam("samples", 64, 1, 1 << 20, "Monte Carlo samples")});
    Method splitSum(paths, "specular_split_sum");
    Method convolution(paths, "diffuse_convolution");
    Method harmonics(paths, "diffuse_sh");

    Measurements m(o, scene, renderer);
    m.truth = cpuTruth(m, splitSum, equirect, environment);
    measureBruteForce(m, bruteForce, "brute_force");
    measureBruteForce(m, visibleNormals, "brute_force_vndf");
    measureSplitSum(m, splitSum);
    // Diffuse: the irradiance cube against 9 spherical-harmonic coefficients.
    measureConvolution(m, convolution);
    measureHarmonics(m, harmonics, equirect);
    return std::move(m.rows);
}

void writeConvergeReport(const std::vector<ConvergeRow>& rows, const fs::path& out) {
    fs::create_directories(out);
    {
        std::ofstream csv(out / "converge.csv");
        csv << "term,method,setting,samples,ms,precompute_ms,rmse,max_error,display_rmse\n";
        for (const auto& r : rows)
            csv << r.term << "," << r.method << ",\"" << r.setting << "\"," << r.samples << ","
                << r.ms << "," << r.precomputeMs << "," << r.rmse << "," << r.maxError << ","
                << r.displayRmse << "\n";
    }
    // One data file per series, so gnuplot needs no CSV parsing.
    auto series = [&](const std::string& name, auto keep) {
        std::ofstream dat(out / (name + ".dat"));
        for (const auto& r : rows)
            if (keep(r)) dat << r.ms << " " << r.rmse << " \"" << r.setting << "\"\n";
    };
    series("brute_force", [](const ConvergeRow& r) { return r.method == "brute_force"; });
    series("brute_force_vndf", [](const ConvergeRow& r) { return r.method == "brute_force_vndf"; });
    series("split_sum_fis_off", [](const ConvergeRow& r) {
        return r.method == "split_sum" && r.setting.find("fis=off") != std::string::npos;
    });
    series("split_sum_fis_on", [](const ConvergeRow& r) {
        return r.method == "split_sum" && r.setting.find("fis=on") != std::string::npos;
    });
    series("split_sum_lut", [](const ConvergeRow& r) {
        return r.method == "split_sum" && r.setting.rfind("lut=", 0) == 0;
    });
    series("diffuse", [](const ConvergeRow& r) { return r.term == "diffuse"; });
    std::ofstream gp(out / "converge.gp");
    gp << "# gnuplot converge.gp -> converge.png (written by pbrlab converge)\n"
          "set terminal pngcairo size 1000,650 font 'DejaVu Sans,11'\n"
          "set output 'converge.png'\n"
          "set logscale xy\nset grid\n"
          "set xlabel 'GPU time per frame, ms (view pass; precomputes in the CSV)'\n"
          "set ylabel 'RMSE against the CPU reference (linear radiance)'\n"
          "set title 'Specular and diffuse ambient light: error against run time'\n"
          "set key outside right\n"
          "plot 'brute_force.dat' using 1:2 with linespoints lw 2 title 'brute force, N = "
          "1..1024', \\\n"
          "     'brute_force_vndf.dat' using 1:2 with linespoints lw 2 title 'brute force, "
          "visible normals', \\\n"
          "     'split_sum_fis_off.dat' using 1:2 with points pt 7 ps 1.5 title 'split sum, "
          "prefilter samples', \\\n"
          "     'split_sum_fis_on.dat' using 1:2 with points pt 5 ps 1.5 title 'split sum, "
          "filtered sampling', \\\n"
          "     'split_sum_lut.dat' using 1:2 with points pt 9 ps 1.5 title 'split sum, LUT "
          "sizes', \\\n"
          "     'diffuse.dat' using 1:2:3 with labels point pt 13 offset 1,1 notitle\n";
    gp.close();
    std::string cmd = "cd '" + out.string() + "' && gnuplot converge.gp 2>/dev/null";
    if (std::system("command -v gnuplot >/dev/null 2>&1") == 0 && std::system(cmd.c_str()) == 0)
        logLine("converge", "plot: " + (out / "converge.png").string());
    else
        logLine("converge", "gnuplot not available: run converge.gp by hand for the plot");
}

}  // namespace pbrlab

namespace pbrlab {

IblRun measurePrecompute(IblPrecompute& precompute, const Image& equirect,
                         const IblSettings& settings, IblTruth& truth, const IblDiskCache* cache) {
    IblRun run;
    run.maps = IblPrecompute::makeMaps(settings);
    gl::Finish();
    const auto start = std::chrono::steady_clock::now();
    precompute.buildDerived(*run.maps, equirect, cache);
    gl::Finish();
    run.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    run.errors = measureIblErrors(precompute, *run.maps, truth);
    return run;
}

std::vector<IblSettings> iblLadder() {
    // Each rung costs more than the one below. What limits each map (docs/ibl.md): the bins
    // limit the irradiance and the rough mips (error ~ 1 / bins^2), the prefilter's size limits
    // mip 0 (the mirror: the environment resampled, error ~ 1 / size), the irradiance map's
    // size its interpolation. The LUT (computed once, whatever the environment) stays the
    // default's: its mean error, ~1e-3, is below every rung's other maps.
    struct Rung {
        int bins, prefilterSize, irradianceSize;
    };
    const Rung rungs[] = {{4, 32, 8},   {4, 64, 16},   {8, 64, 16},
                          {8, 128, 32}, {16, 128, 32}, {16, 256, 32}};
    std::vector<IblSettings> ladder;
    for (const Rung& r : rungs) {
        IblSettings s;
        s.bins = r.bins;
        s.prefilterSize = r.prefilterSize;
        s.prefilterMips = std::min(5, int(std::log2(r.prefilterSize)) + 1);
        s.irradianceSize = r.irradianceSize;
        ladder.push_back(s);
    }
    return ladder;
}

bool withinBudget(const IblErrors& e, double budget) {
    return e.irradiance.mean <= budget && e.prefilter.mean <= budget && e.lut.mean <= budget;
}

IblChoice chooseIblSettings(IblPrecompute& precompute, const Image& equirect, IblTruth& truth,
                            double budget, const IblDiskCache* cache) {
    IblChoice choice;
    for (const IblSettings& s : iblLadder()) {
        choice.settings = s;
        choice.run = measurePrecompute(precompute, equirect, s, truth, cache);
        ++choice.tried;
        if (withinBudget(choice.run.errors, budget)) {
            choice.met = true;
            break;
        }
    }
    return choice;
}

std::vector<IblRun> measureIblLadder(IblPrecompute& precompute, const Image& equirect,
                                     IblTruth& truth) {
    std::vector<IblRun> runs;
    for (const IblSettings& s : iblLadder())
        runs.push_back(measurePrecompute(precompute, equirect, s, truth));
    return runs;
}

IblRun precomputeWithErrors(IblPrecompute& precompute, const Image& equirect,
                            const IblSettings& settings, const IblDiskCache* cache) {
    // The CPU truth in a thread of its own while the maps are built (the GPU compiles and the
    // single-threaded steps leave a core free).
    auto truthReady = std::async(std::launch::async, [&] {
        auto truth = std::make_unique<IblTruth>(equirect);
        truth->prepare(settings);
        return truth;
    });
    IblRun run;
    run.maps = IblPrecompute::makeMaps(settings);
    const auto start = std::chrono::steady_clock::now();
    precompute.buildDerived(*run.maps, equirect, cache);
    gl::Finish();
    run.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const auto truth = truthReady.get();
    run.errors = measureIblErrors(precompute, *run.maps, *truth);
    return run;
}

void writePrecompute(const IblRun& run, const Image& equirect, const fs::path& out) {
    const IblMaps& maps = *run.maps;
    const IblSettings& settings = maps.settings;
    auto writeCube = [&](const fs::path& dir, GLuint cube, int size, int mip) {
        fs::create_directories(dir);
        for (int face = 0; face < 6; ++face)
            writeImage(dir / (std::string(kCubeFaceNames[face]) + ".exr"),
                       IblPrecompute::readCubeFace(cube, face, mip, size), FileDepth::Float32);
    };
    writeCube(out / "irradiance", maps.irradiance.id(), settings.irradianceSize, 0);
    for (int mip = 0; mip < settings.prefilterMips; ++mip)
        writeCube(out / "prefilter" / ("mip" + std::to_string(mip)), maps.prefilter.id(),
                  settings.prefilterSize, mip);
    writeImage(out / "brdf_lut.exr", IblPrecompute::readLut(maps), FileDepth::Float32);
    double shMs = 0;
    {
        // The 9 spherical-harmonic coefficients of the radiance (real SH, index l(l+1)+m),
        // the fast alternative to the irradiance cube: E(N)/pi = shIrradiance(sh, N).
        const auto start = std::chrono::steady_clock::now();
        const ref::SH9 sh = ref::projectSH9(equirect);
        shMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                   .count();
        std::ofstream json(out / "sh.json");
        json << "{\n  \"basis\": \"real SH, bands 0-2, index l(l+1)+m, radiance\",\n  "
                "\"coefficients\": [\n";
        for (int i = 0; i < 9; ++i)
            json << "    [" << sh.c[size_t(i)].x << ", " << sh.c[size_t(i)].y << ", "
                 << sh.c[size_t(i)].z << "]" << (i < 8 ? ",\n" : "\n");
        json << "  ]\n}\n";
    }
    // Each pass's time next to its map's error, on the screen and in errors.csv.
    const IblErrors& e = run.errors;
    std::printf("  %-52s %10s %11s %11s\n", "pass", "time", "mean error", "max error");
    std::ofstream csv(out / "errors.csv");
    csv << "map,pass,ms,cached,mean_error,max_error,samples\n";
    for (const IblPass& pass : maps.passes) {
        const MapError* m = pass.map == "irradiance"  ? &e.irradiance
                            : pass.map == "prefilter" ? &e.prefilter
                            : pass.map == "lut"       ? &e.lut
                                                      : nullptr;
        if (!m) continue;
        std::printf("  %-52s %7.1f ms %11.4f %11.4f\n", pass.label.c_str(), pass.milliseconds,
                    m->mean, m->max);
        csv << pass.map << ",\"" << pass.label << "\"," << pass.milliseconds << ","
            << (pass.cached ? 1 : 0) << "," << m->mean << "," << m->max << "," << m->samples
            << "\n";
        if (pass.map != "prefilter") continue;
        for (size_t mip = 0; mip < e.prefilterMips.size(); ++mip) {
            char what[64];
            std::snprintf(what, sizeof what, "  mip %zu (roughness %.2f)", mip,
                          double(mip) / std::max(settings.prefilterMips - 1, 1));
            std::printf("  %-52s %10s %11.4f %11.4f\n", what, "", e.prefilterMips[mip].mean,
                        e.prefilterMips[mip].max);
            csv << "prefilter mip " << mip << ",,,," << e.prefilterMips[mip].mean << ","
                << e.prefilterMips[mip].max << "," << e.prefilterMips[mip].samples << "\n";
        }
    }
    std::printf("  %-52s %7.1f ms\n", "spherical harmonics (CPU)", shMs);
    std::printf("  %-52s %7.1f ms\n", "all passes", run.milliseconds);
    const IblErrorSample& sample = IblErrorSample::standard();
    std::printf(
        "errors: against the CPU reference in double precision at %zu directions and %zu "
        "LUT points, relative to the local mean radiance (LUT: absolute); "
        "docs/ibl.md\n",
        sample.directions.size(), sample.lutPoints.size());
    std::cout << "wrote " << out.string()
              << "/{irradiance,prefilter/mip*}/{+x,-x,+y,-y,+z,-z}.exr, brdf_lut.exr, sh.json, "
                 "errors.csv\n";
}

bool benchPrecompute(const DataPaths& paths, const PrecomputeBenchOptions& options) {
    std::vector<std::pair<std::string, Image>> environments;
    environments.emplace_back("sky (pbrlab environment)", loadEnvironmentImage("sky"));
    std::vector<std::string> files = options.files;
    if (files.empty()) {
        const fs::path shared = paths.root / ".." / "shared" / "data" / "hdr";
        for (const char* name : {"venice_sunset_1k.hdr", "studio_small_03_1k.hdr"}) {
            if (fs::exists(shared / name))
                files.push_back((shared / name).string());
            else
                std::cout << "skipped " << name << ": not in " << shared.string()
                          << " (optional real-world HDRs)\n";
        }
    }
    for (const std::string& f : files) environments.emplace_back(f, loadEnvironmentImage(f));
    const IblSettings configs[2] = {IblSettings::learnOpenGl(), IblSettings()};
    const char* names[2] = {"LearnOpenGL sizes", "pbrlab default"};
    std::cout << "baseline: " << configs[0].describe() << "\ndefault:  " << configs[1].describe()
              << "\ntimes: median of " << options.runs
              << " cold precomputes (no disk cache, programs compiled in each), glFinish + "
                 "steady clock\n";
    std::ofstream csv;
    if (!options.out.empty()) {
        fs::create_directories(options.out);
        csv.open(options.out / "bench.csv");
        csv << "environment,config,ms,irradiance_mean,irradiance_max,prefilter_mean,"
               "prefilter_max,lut_mean,lut_max\n";
    }
    bool allBetter = true;
    double smallestRatio = 1e300;
    for (const auto& [name, equirect] : environments) {
        IblTruth truth(equirect);
        std::vector<double> times[2];
        IblErrors errors[2];
        for (int run = 0; run < std::max(options.runs, 1); ++run)
            for (int c = 0; c < 2; ++c) {
                // A fresh program cache: every run pays for its own compiles.
                ProgramCache programs(ShaderPreprocessor({paths.shaders(), paths.labs()}));
                IblPrecompute precompute(programs, paths.shaders());
                IblRun r = measurePrecompute(precompute, equirect, configs[c], truth);
                times[c].push_back(r.milliseconds);
                errors[c] = r.errors;
            }
        double ms[2];
        for (int c = 0; c < 2; ++c) {
            std::sort(times[c].begin(), times[c].end());
            ms[c] = times[c][times[c].size() / 2];
        }
        std::printf("\n%s\n  %-18s %10s %19s %19s %21s\n", name.c_str(), "", "time",
                    "irradiance mean/max", "prefilter mean/max", "LUT mean/max");
        for (int c = 0; c < 2; ++c) {
            const IblErrors& e = errors[c];
            std::printf("  %-18s %8.0f ms %9.4f / %-7.3f %9.4f / %-7.3f %10.5f / %-7.4f\n",
                        names[c], ms[c], e.irradiance.mean, e.irradiance.max, e.prefilter.mean,
                        e.prefilter.max, e.lut.mean, e.lut.max);
            if (csv)
                csv << "\"" << name << "\"," << names[c] << "," << ms[c] << "," << e.irradiance.mean
                    << "," << e.irradiance.max << "," << e.prefilter.mean << "," << e.prefilter.max
                    << "," << e.lut.mean << "," << e.lut.max << "\n";
        }
        const IblErrors &b = errors[0], &d = errors[1];
        const bool better =
            d.irradiance.mean <= b.irradiance.mean && d.irradiance.max <= b.irradiance.max &&
            d.prefilter.mean <= b.prefilter.mean && d.prefilter.max <= b.prefilter.max &&
            d.lut.mean <= b.lut.mean && d.lut.max <= b.lut.max;
        std::printf(
            "  default: %.1fx faster; every error (mean and max) at or below the "
            "baseline's: %s\n",
            ms[0] / ms[1], better ? "yes" : "NO");
        allBetter = allBetter && better;
        smallestRatio = std::min(smallestRatio, ms[0] / ms[1]);
    }
    std::printf(
        "\nsmallest speed-up %.1fx; every error at or below the baseline's everywhere: %s\n",
        smallestRatio, allBetter ? "yes" : "NO");
    return allBetter && smallestRatio >= 10;
}

}  // namespace pbrlab
