#include "ibl.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

#include "cache_file.h"
#include "digest.h"
#include "parallel.h"
#include "pbrlab/contract.h"
#include "pbrlab/cube_sampler.h"
#include "pbrlab/error.h"
#include "pbrlab/ibl_reference.h"
#include "pbrlab/log.h"

namespace fs = std::filesystem;

namespace pbrlab {

const char* const kCubeFaceNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};

const DerivedMap kDerivedMaps[3] = {{"uIrradianceMap"}, {"uPrefilterMap"}, {"uBrdfLut"}};

// The id of the step whose reference solution a pass for this map links (step.json "provides"),
// "" when no step declares the map.
static std::string providerOf(const char* sampler) {
    const ContractStep* step = findProvider(sampler);
    return step ? step->id : std::string();
}

namespace {

// Names what the CPU code of this file computes (cube resampling, irradiance bins) in the
// cache keys: bump it when that code changes what it writes.
constexpr const char* kCpuMapsVersion = "cpu-maps-1";

std::string number(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

}  // namespace

namespace {

std::string irradianceText(const IblSettings& s) {
    switch (s.irradiance) {
        case IrradianceMethod::Bins:
            return "bins " + std::to_string(s.bins);
        case IrradianceMethod::Step18:
            return "step 18";
        case IrradianceMethod::Riemann:
            return "Riemann " + number(s.riemannStep);
    }
    return "";
}

std::string prefilterText(const IblSettings& s) {
    switch (s.prefilter) {
        case PrefilterMethod::Bins:
            return "bins " + std::to_string(s.bins);
        case PrefilterMethod::Filtered:
            return std::to_string(s.prefilterSamples) + " filtered samples (bias " +
                   number(s.filteredLodBias) + ")";
        case PrefilterMethod::Plain:
            return std::to_string(s.prefilterSamples) + " samples";
    }
    return "";
}

}  // namespace

std::string IblSettings::key() const {
    return "src" + std::to_string(source()) + "_irr" + std::to_string(irradianceSize) + " " +
           irradianceText(*this) + "_pre" + std::to_string(prefilterSize) + "x" +
           std::to_string(prefilterMips) + (prefilterMirrorExact ? "m" : "") +
           std::to_string(mirrorSupersample) + " " + prefilterText(*this);
}

std::string IblSettings::lutKey() const {
    return std::string(lut == LutMethod::Quadrature ? "quad" : "mc" + std::to_string(lutSamples)) +
           "_" + std::to_string(lutWidth) + "x" + std::to_string(lutHeight);
}

std::string IblSettings::describe() const {
    return "irradiance " + std::to_string(irradianceSize) + "^2 by " + irradianceText(*this) +
           "; prefilter " + std::to_string(prefilterSize) + "^2 x " +
           std::to_string(prefilterMips) + " by " + prefilterText(*this) +
           (prefilterMirrorExact ? ", mip 0 resampled" : "") + " (source " +
           std::to_string(source()) + "^2); LUT " + std::to_string(lutWidth) + " x " +
           std::to_string(lutHeight) + " by " +
           (lut == LutMethod::Quadrature ? std::string("quadrature")
                                         : std::to_string(lutSamples) + " samples");
}

IblSettings IblSettings::learnOpenGl() {
    IblSettings s;
    s.environmentSize = 512;
    s.sourceSize = 512;
    s.irradiance = IrradianceMethod::Riemann;
    s.irradianceSize = 32;
    s.riemannStep = 0.025;
    s.prefilterSize = 128;
    s.prefilterMips = 5;
    s.prefilterMirrorExact = false;
    s.prefilter = PrefilterMethod::Plain;
    s.prefilterSamples = 1024;
    s.lut = LutMethod::Step20;
    s.lutWidth = s.lutHeight = 512;
    s.lutSamples = 1024;
    return s;
}

double IblMaps::milliseconds(const std::string& map) const {
    double ms = 0;
    for (const IblPass& p : passes)
        if (p.map == map) ms += p.milliseconds;
    return ms;
}

glm::dvec3 cubeTexelDirection(int face, double x, double y, int size) {
    // As pbrlab_cubeDirection in shaders/ibl/cube_face.glsl.
    const double s = (x + 0.5) / size * 2.0 - 1.0, t = (y + 0.5) / size * 2.0 - 1.0;
    return glm::normalize(cubeFaceDirection(face, s, t));
}

std::vector<std::vector<Image>> equirectToCube(const Image& equirect, int size, int levels) {
    auto square = [](int n) {
        Image im;
        im.width = im.height = n;
        im.channels = 4;
        im.pixels.assign(size_t(n) * size_t(n) * 4, 1.0f);
        return im;
    };
    std::vector<std::vector<Image>> out(static_cast<size_t>(levels));
    for (int f = 0; f < 6; ++f) out[0].push_back(square(size));
    parallelFor(size_t(6 * size), [&](size_t row) {
        const int face = int(row) / size, y = int(row) % size;
        Image& im = out[0][size_t(face)];
        for (int x = 0; x < size; ++x) {
            const glm::dvec3 L =
                ref::equirectRadiance(equirect, cubeTexelDirection(face, x, y, size));
            for (int c = 0; c < 3; ++c) im.at(x, y, c) = float(L[c]);
        }
    });
    // Mips: each texel the mean of the 2 x 2 below it (sizes are powers of two here; an odd
    // size keeps its last row and column out, as a box filter that GL may also use).
    for (int level = 1; level < levels; ++level) {
        const int n = std::max(size >> level, 1);
        for (int f = 0; f < 6; ++f) {
            const Image& fine = out[size_t(level) - 1][size_t(f)];
            Image im = square(n);
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x)
                    for (int c = 0; c < 3; ++c) {
                        const int x0 = std::min(2 * x, fine.width - 1),
                                  x1 = std::min(2 * x + 1, fine.width - 1);
                        const int y0 = std::min(2 * y, fine.height - 1),
                                  y1 = std::min(2 * y + 1, fine.height - 1);
                        im.at(x, y, c) = 0.25f * (fine.at(x0, y0, c) + fine.at(x1, y0, c) +
                                                  fine.at(x0, y1, c) + fine.at(x1, y1, c));
                    }
            out[size_t(level)].push_back(std::move(im));
        }
    }
    return out;
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

// The cube bin (face, i, j) a direction falls in, for bins of n texels a side, as a cube map
// of n x n texels selects it. `d` is never zero here (texel directions of the sphere).
int binOf(const glm::dvec3& d, int n) {
    const CubeFacePoint p = cubeFacePoint(d);
    const int i = std::clamp(int(0.5 * (p.s + 1.0) * n), 0, n - 1);
    const int j = std::clamp(int(0.5 * (p.t + 1.0) * n), 0, n - 1);
    return (p.face * n + j) * n + i;
}

// Four floats processed as one (GCC and Clang vector extensions: SSE on any x86-64).
typedef float Float4 __attribute__((vector_size(16)));

// The environment binned per texel of a cube of n x n texels a face (IrradianceMethod::Bins,
// PrefilterMethod::Bins): every texel of the equirectangular image adds its power, L times its
// exact solid angle, to the bin its centre falls in; per bin, the grey power weighs the mean
// direction m and the mean of d d^T. Stored four bins to a pack, one component per Float4.
struct EnvironmentBins {
    struct Pack {
        Float4 power[3], mean[3], second[6];  // second: xx yy zz xy yz xz
    };
    std::vector<Pack> packs;
};

EnvironmentBins binEnvironment(const Image& equirect, int n) {
    const int W = equirect.width, H = equirect.height, count = 6 * n * n;
    std::vector<double> sinPhi(static_cast<size_t>(W)), cosPhi(static_cast<size_t>(W));
    for (int x = 0; x < W; ++x) {
        const double phi = ((x + 0.5) / W - 0.5) * 2.0 * ref::kPi;
        sinPhi[size_t(x)] = std::sin(phi);
        cosPhi[size_t(x)] = std::cos(phi);
    }
    struct Sums {
        glm::dvec3 power{0.0}, mean{0.0};
        double grey = 0, second[6] = {};
    };
    std::vector<Sums> bins(static_cast<size_t>(count));
    for (int y = 0; y < H; ++y) {
        const double t = ref::kPi * (y + 0.5) / H, st = std::sin(t), ct = std::cos(t);
        const double omega =
            2.0 * ref::kPi / W * (std::cos(ref::kPi * y / H) - std::cos(ref::kPi * (y + 1) / H));
        for (int x = 0; x < W; ++x) {
            const glm::dvec3 d(st * sinPhi[size_t(x)], ct, -st * cosPhi[size_t(x)]);
            Sums& b = bins[size_t(binOf(d, n))];
            const glm::dvec3 p = ref::equirectTexel(equirect, x, y) * omega;
            const double g = std::max((p.x + p.y + p.z) / 3.0, 0.0);
            b.power += p;
            b.grey += g;
            b.mean += g * d;
            const double dd[6] = {d.x * d.x, d.y * d.y, d.z * d.z, d.x * d.y, d.y * d.z, d.x * d.z};
            for (int k = 0; k < 6; ++k) b.second[k] += g * dd[k];
        }
    }
    EnvironmentBins out;
    out.packs.resize(size_t(count + 3) / 4, EnvironmentBins::Pack{});
    for (int i = 0; i < count; ++i) {
        const Sums& b = bins[size_t(i)];
        EnvironmentBins::Pack& p = out.packs[size_t(i) / 4];
        const int lane = i % 4;
        const double g = b.grey > 0.0 ? 1.0 / b.grey : 0.0;
        for (int k = 0; k < 3; ++k) {
            p.power[k][lane] = float(b.power[k]);
            p.mean[k][lane] = float(b.mean[k] * g);
        }
        for (int k = 0; k < 6; ++k) p.second[k][lane] = float(b.second[k] * g);
    }
    return out;
}

// The integral over the sphere of the prefilter weight c / u^2, u = 1 + b (1 + c),
// b = (alpha^2 - 1) / 2 (see convolveBins): 2 pi integral_0^1 c / (A + b c)^2 dc with
// A = 1 + b, in closed form (1 / b^2) (ln((A + b) / A) + A / (A + b) - 1), or its Taylor
// series near alpha^2 = 1 where that cancels. pi at alpha = 1 (the cosine).
double lobeIntegral(double alpha2) {
    const double b = 0.5 * (alpha2 - 1.0), A = 1.0 + b;
    const double integral = std::abs(b) < 1e-3
                                ? 0.5 - 5.0 / 3.0 * b + 17.0 / 4.0 * b * b
                                : (std::log((A + b) / A) + A / (A + b) - 1.0) / (b * b);
    return 2.0 * ref::kPi * integral;
}

// One cube map level of the environment convolved with the prefilter's lobe, from its bins.
// The prefiltered value at R is  sum over l of L(l) w(R.l) / integral of w  with the weight
// of Karis' estimator, w(c) = c D(h) (N = V = R, (N.h)^2 = (1 + c) / 2), up to a constant
// c / u^2, u = 1 + b (1 + c), b = (alpha^2 - 1) / 2. At roughness 1 (alpha^2 = 1) the weight
// is the cosine and the result is E / pi: the irradiance map is this convolution too.
// A bin stands for its texels through their moments: expanding w around c = R.m to second
// order, it adds  P (w(c) + w''(c) Var(R.d) / 2),  Var(R.d) = R^T S R - c^2.  That is exact
// for the cosine, and a small bright sun inside a bin stays exactly where it is (m is its
// direction); bins below R's horizon (c <= 0) add nothing. Accuracy in docs/ibl.md.
std::vector<Image> convolveBins(const EnvironmentBins& bins, int size, double roughness) {
    const double a = roughness * roughness, alpha2 = std::max(a * a, 1e-7);
    const float b = float(0.5 * (alpha2 - 1.0)), scale = float(1.0 / lobeIntegral(alpha2));
    std::vector<Image> faces(6);
    for (Image& im : faces) {
        im.width = im.height = size;
        im.channels = 4;
        im.pixels.assign(size_t(size) * size_t(size) * 4, 1.0f);
    }
    parallelFor(size_t(6 * size), [&](size_t row) {
        const int face = int(row) / size, y = int(row) % size;
        const Float4 zero = {0, 0, 0, 0};
        for (int x = 0; x < size; ++x) {
            const glm::vec3 R(cubeTexelDirection(face, x, y, size));
            const float xx = R.x * R.x, yy = R.y * R.y, zz = R.z * R.z;
            const float xy = 2 * R.x * R.y, yz = 2 * R.y * R.z, xz = 2 * R.x * R.z;
            Float4 sum[3] = {zero, zero, zero};
            for (const EnvironmentBins::Pack& p : bins.packs) {
                const Float4 c = R.x * p.mean[0] + R.y * p.mean[1] + R.z * p.mean[2];
                const Float4 RSR = xx * p.second[0] + yy * p.second[1] + zz * p.second[2] +
                                   xy * p.second[3] + yz * p.second[4] + xz * p.second[5];
                const Float4 variance = RSR - c * c;
                const Float4 inv = 1.0f / (1.0f + b * (1.0f + c));
                const Float4 w = c * inv * inv;
                const Float4 w2 = (6.0f * b * b * c * inv - 4.0f * b) * inv * inv * inv;
                Float4 k = w + 0.5f * w2 * (variance > 0.0f ? variance : zero);
                k = c > 0.0f && k > 0.0f ? k : zero;
                for (int ch = 0; ch < 3; ++ch) sum[ch] += p.power[ch] * k;
            }
            for (int ch = 0; ch < 3; ++ch)
                faces[size_t(face)].at(x, y, ch) =
                    (sum[ch][0] + sum[ch][1] + sum[ch][2] + sum[ch][3]) * scale;
        }
    });
    return faces;
}

}  // namespace

IblPrecompute::IblPrecompute(ProgramCache& programs, fs::path shaders)
    : programs_(programs), shaders_(std::move(shaders)) {}

std::shared_ptr<Program> IblPrecompute::program(const std::string& pass,
                                                const std::string& contractId,
                                                const Defines& extra) {
    ProgramRecipe r;
    r.label = "precompute " + pass;
    r.vertex = {shaders_ / "fullscreen.vert"};
    r.fragment.push_back(shaders_ / "common.glsl");
    if (!contractId.empty())
        for (const ContractStep* step : contractClosure(contractId, {}))
            r.fragment.push_back(step->folder / "solution.glsl");
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
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkError(pass.c_str());
}

fs::path IblDiskCache::defaultRoot() {
    if (const char* c = std::getenv("PBRLAB_CACHE"); c && *c) return c;
    if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "pbrlab";
    const char* home = std::getenv("HOME");
    return fs::path(home ? home : ".") / ".cache" / "pbrlab";
}

namespace {

constexpr char kCacheMagic[8] = {'P', 'B', 'R', 'L', 'C', 'U', 'B', '3'};

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
            im.pixels.resize(size_t(size[0]) * size_t(size[1]) * 4);
            if (!in.bytes(im.pixels.data(), im.pixels.size() * sizeof(float))) return false;
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

}  // namespace

std::vector<fs::path> IblPrecompute::sources(const std::vector<std::string>& shaders,
                                             const std::string& contractId) const {
    std::vector<fs::path> files = {shaders_ / "common.glsl", shaders_ / "fullscreen.vert",
                                   shaders_ / "ibl" / "cube_face.glsl"};
    for (const std::string& s : shaders) files.push_back(shaders_ / "ibl" / (s + ".frag"));
    if (!contractId.empty())
        for (const ContractStep* step : contractClosure(contractId, {}))
            files.push_back(step->folder / "solution.glsl");
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

std::string IblPrecompute::mapsKey(const Image& equirect, const IblSettings& s) const {
    Digest f;
    f.add(equirect.pixels.data(), equirect.pixels.size() * sizeof(float));
    f.add(std::to_string(equirect.width) + "x" + std::to_string(equirect.height) + "x" +
          std::to_string(equirect.channels) + s.key() + kCpuMapsVersion);
    // Every file that can compute the irradiance or the prefiltered map.
    std::vector<fs::path> files =
        sources({"prefilter", "irradiance", "irradiance_riemann"}, providerOf("uPrefilterMap"));
    for (const auto& p : sources({}, providerOf("uIrradianceMap"))) files.push_back(p);
    addFiles(f, files);
    return f.hex();
}

std::string IblPrecompute::lutKey(const IblSettings& s) const {
    Digest f;
    f.add(s.lutKey());
    addFiles(f, sources({"brdf_lut", "brdf_lut_quadrature"}, providerOf("uBrdfLut")));
    return f.hex();
}

std::unique_ptr<IblMaps> IblPrecompute::makeMaps(const IblSettings& settings) {
    auto maps = std::make_unique<IblMaps>();
    maps->settings = settings;
    return maps;
}

std::unique_ptr<IblMaps> IblPrecompute::build(const Image& equirect, const IblSettings& s,
                                              const IblDiskCache* cache) {
    auto maps = buildEnvironment(equirect, s);
    buildDerived(*maps, equirect, cache);
    return maps;
}

std::unique_ptr<IblMaps> IblPrecompute::buildEnvironment(const Image& equirect,
                                                         const IblSettings& s) {
    auto maps = makeMaps(s);
    PassTimer timer(*maps, "environment", "environment cube " + std::to_string(s.environmentSize),
                    onPass);
    const int levels = fullMipCount(s.environmentSize);
    maps->environment = makeCube(s.environmentSize, levels);
    uploadCube(maps->environment.id(), equirectToCube(equirect, s.environmentSize, levels));
    return maps;
}

// What the passes of one buildDerived share, made on first use: the source cube the GPU
// passes read, and the environment's bins in uniform buffers.
struct IblPrecompute::Inputs {
    const Image& equirect;
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
        sourceLevels = equirectToCube(equirect, n, fullMipCount(n));
        ownSource = makeCube(n, fullMipCount(n));
        uploadCube(ownSource.id(), sourceLevels);
        return source = ownSource.id();
    }
    const EnvironmentBins& bins() {
        if (!binned)
            binned = std::make_unique<EnvironmentBins>(
                binEnvironment(equirect, std::clamp(maps.settings.bins, 1, 64)));
        return *binned;
    }
};

void IblPrecompute::buildDerived(IblMaps& maps, const Image& equirect, const IblDiskCache* cache) {
    if (maps.derived) return;
    maps.derived = true;
    const IblSettings& s = maps.settings;
    gl::Disable(GL_DEPTH_TEST);
    gl::Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);  // precomputed maps never depend on the caller
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
                                std::to_string(s.prefilterMips) + " by " + prefilterText(s) +
                                (s.prefilterMirrorExact ? ", mip 0 resampled" : ""),
                            onPass);
            buildPrefilter(maps, inputs);
        }
        {
            PassTimer timer(
                maps, "irradiance",
                "irradiance " + std::to_string(s.irradianceSize) + " by " + irradianceText(s),
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
        const Image& rg = lut[0][0];
        maps.lut = makeLutTexture(s.lutWidth, s.lutHeight);
        gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        gl::TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, rg.width, rg.height, GL_RGBA, GL_FLOAT,
                          rg.pixels.data());
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
            uploadCube(maps.prefilter.id(), {equirectToCube(inputs.equirect, s.prefilterSize * k,
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
    Defines defines;
    if (s.prefilter == PrefilterMethod::Filtered) defines["PBRLAB_FILTERED_IS"] = "1";
    auto p = program("prefilter", providerOf("uPrefilterMap"), defines);
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
                 ? program("irradiance_riemann", "")
                 : program("irradiance", providerOf("uIrradianceMap"));
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
    gl::Handle fbo = gl::makeFramebuffer();
    gl::BindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    gl::FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, maps.lut.id(), 0);
    if (gl::CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("brdf lut: target incomplete");
    GLenum buffer = GL_COLOR_ATTACHMENT0;
    gl::DrawBuffers(1, &buffer);
    gl::Viewport(0, 0, s.lutWidth, s.lutHeight);
    auto p = s.lut == LutMethod::Quadrature ? program("brdf_lut_quadrature", providerOf("uBrdfLut"))
                                            : program("brdf_lut", providerOf("uBrdfLut"));
    p->use();
    p->set("uSize", glm::vec2(float(s.lutWidth), float(s.lutHeight)));
    p->setUnsigned("uSampleCount", unsigned(s.lutSamples));
    fullscreen_.draw();
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkError("brdf lut");
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
    gl::Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    auto p = program("probe_cube", "");
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
