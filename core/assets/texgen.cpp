#include "assets/texgen.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <system_error>
#include <vector>

#include "assets/image_io.h"
#include "assets/procedural.h"
#include "util/color.h"
#include "util/error.h"

namespace pbrlab {

namespace {

using u32 = std::uint32_t;

// ---- integer hash noise (pure functions of their arguments: same bytes on every run) ----

using namespace procedural;

u32 hash(u32 a, u32 b = 0, u32 c = 0) {
    return mix(a ^ mix(b ^ mix(c + 0x9e3779b9U)));
}

double clamp01(double x) {
    return std::clamp(x, 0.0, 1.0);
}

// Value noise with fu x fv lattice cells over the unit square, periodic (the texture tiles).
double valueNoise(double u, double v, int fu, int fv, u32 seed) {
    const double x = u * fu, y = v * fv;
    const double fx = std::floor(x), fy = std::floor(y);
    const double tx = fade(x - fx), ty = fade(y - fy);
    auto wrap = [](double i, int f) { return u32(((long long)i % f + f) % f); };
    const u32 x0 = wrap(fx, fu), x1 = wrap(fx + 1, fu), y0 = wrap(fy, fv), y1 = wrap(fy + 1, fv);
    const double a = unit(hash(seed, x0, y0)), b = unit(hash(seed, x1, y0));
    const double c = unit(hash(seed, x0, y1)), d = unit(hash(seed, x1, y1));
    return lerp(lerp(a, b, tx), lerp(c, d, tx), ty);
}

// Fractal sum of value noise, in [0, 1], mean about 0.5.
double fbm(double u, double v, int freq, int octaves, u32 seed) {
    double sum = 0.0, amplitude = 1.0, total = 0.0;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * valueNoise(u, v, freq << o, freq << o, seed + u32(o) * 101u);
        total += amplitude;
        amplitude *= 0.5;
    }
    return sum / total;
}

// ---- layout: rows of plates, each row cut into 2 or 3 plates at a per-row offset ----

constexpr std::array<double, 5> kRowEdges = {0.0, 0.3125, 0.5625, 0.8125, 1.0};
constexpr int kRows = int(kRowEdges.size()) - 1;

// Seeds of the independent noise fields.
enum : u32 {
    kSeedRows = 11,
    kSeedPlate = 23,
    kSeedWear = 37,
    kSeedDent = 41,
    kSeedGrain = 53,
    kSeedMetal = 67,
    kSeedPaint = 71,
    kSeedRoughMetal = 83,
    kSeedRoughPaint = 97,
    kSeedScratch = 109,
    kSeedStreaks = 127,
};

// Feature sizes in uv units (the texture is the unit square).
constexpr double kGrooveDepth = 0.01;
constexpr double kGrooveFlat = 0.0015;  // half-width of the groove floor
constexpr double kBevel = 0.008;        // rounded plate edge
constexpr double kRivetInset = 0.018;   // rivet centre to plate edge
constexpr double kRivetSpacing = 0.05;
constexpr double kRivetRadius = 0.0085;
constexpr double kRivetHeight = 0.0055;
constexpr double kPaintThickness = 0.0005;
constexpr int kScratchesPerPlate = 7;

struct Plate {
    u32 id;
    double x, y;  // position inside the plate from its left / top edge
    double w, h;  // plate size
};

Plate plateAt(double u, double v) {
    int r = 0;
    while (r + 1 < kRows && v >= kRowEdges[r + 1]) ++r;
    const u32 rowHash = hash(kSeedRows, u32(r));
    const int count = 2 + int(rowHash % 2);
    double s = u - unit(hash(rowHash, 1));  // per-row offset, wrapped: plates cross u = 1
    s -= std::floor(s);
    const int j = std::min(int(s * count), count - 1);
    const double w = 1.0 / count;
    return {hash(kSeedPlate, u32(r), u32(j)), s - j * w, v - kRowEdges[r], w,
            kRowEdges[r + 1] - kRowEdges[r]};
}

// Distance to the nearest rivet centre of a plate: rows of rivets parallel to each edge.
double rivetDistance(const Plate& p) {
    auto alongEdge = [](double t, double length) {
        const int n = std::max(2, int(std::lround((length - 2 * kRivetInset) / kRivetSpacing)) + 1);
        const double step = (length - 2 * kRivetInset) / (n - 1);
        const double i = std::clamp(std::round((t - kRivetInset) / step), 0.0, double(n - 1));
        return kRivetInset + i * step;
    };
    const double cx = alongEdge(p.x, p.w), cy = alongEdge(p.y, p.h);
    double best = 1e9;
    for (double ey : {kRivetInset, p.h - kRivetInset})  // top and bottom rows
        best = std::min(best, std::hypot(p.x - cx, p.y - ey));
    for (double ex : {kRivetInset, p.w - kRivetInset})  // left and right columns
        best = std::min(best, std::hypot(p.x - ex, p.y - cy));
    return best;
}

// Scratch mask in [0, 1]: a few thin tapered segments per plate, roughly along one direction.
double scratchMask(const Plate& p) {
    const double dx0 = unit(hash(p.id, kSeedScratch)) - 0.5;
    const double dy0 = unit(hash(p.id, kSeedScratch + 1)) - 0.5;
    double best = 0.0;
    for (int s = 0; s < kScratchesPerPlate; ++s) {
        const u32 h = hash(p.id, kSeedScratch + 2, u32(s));
        const double cx = unit(hash(h, 1)) * p.w, cy = unit(hash(h, 2)) * p.h;
        double dx = dx0 + 0.3 * (unit(hash(h, 3)) - 0.5);
        double dy = dy0 + 0.3 * (unit(hash(h, 4)) - 0.5);
        const double len = std::hypot(dx, dy);
        if (len < 1e-6) continue;
        dx /= len;
        dy /= len;
        const double halfLength = 0.01 + 0.05 * unit(hash(h, 5));
        const double halfWidth = 0.0018 + 0.0015 * unit(hash(h, 6));
        const double strength = 0.5 + 0.5 * unit(hash(h, 7));
        const double rx = p.x - cx, ry = p.y - cy;
        const double t = rx * dx + ry * dy;  // along the scratch
        const double n = std::abs(-rx * dy + ry * dx);
        if (std::abs(t) > halfLength || n > halfWidth) continue;
        const double taper = 1.0 - smoothstep(0.5, 1.0, std::abs(t) / halfLength);
        best = std::max(best, strength * taper * (1.0 - smoothstep(0.3, 1.0, n / halfWidth)));
    }
    return best;
}

struct Rgb {
    double r, g, b;
};

// Industrial paints, as sRGB 8-bit colours.
constexpr std::array<std::array<int, 3>, 6> kPaints = {{
    {74, 98, 116},    // steel blue
    {92, 102, 70},    // olive drab
    {126, 54, 40},    // oxide red
    {190, 156, 52},   // safety yellow
    {196, 190, 170},  // cream
    {78, 80, 82},     // dark grey
}};

// Per-pixel material before ambient occlusion is known.
struct Texel {
    double height;
    double paint;  // 1 = paint on top, 0 = bare metal
    double scratch;
    double seam;     // 1 in the groove, 0 on the plate
    double streaks;  // run-off stains on bare metal
    Rgb metal, paintColour;
    double roughMetal, roughPaint;
};

Texel evaluate(double u, double v) {
    const Plate p = plateAt(u, v);
    const double edge = std::min(std::min(p.x, p.w - p.x), std::min(p.y, p.h - p.y));
    const double rivet = rivetDistance(p);
    const double scratch = scratchMask(p);

    Texel t{};
    t.scratch = scratch;
    t.seam = 1.0 - smoothstep(kGrooveFlat, kGrooveFlat + kBevel, edge);

    // Paint: some plates are painted; paint chips off near seams and rivets and where scratched.
    const bool painted = unit(hash(p.id, 2)) < 0.6;
    if (painted) {
        const double wear = 0.6 * fbm(u, v, 4, 2, kSeedWear) +
                            0.4 * fbm(u, v, 16, 4, kSeedWear + 7) +
                            0.2 * (1.0 - smoothstep(0.0, 0.025, edge)) +
                            0.15 * (1.0 - smoothstep(kRivetRadius, 2.0 * kRivetRadius, rivet));
        const double threshold = 0.68 + 0.1 * unit(hash(p.id, 3));
        t.paint = 1.0 - smoothstep(threshold - 0.025, threshold + 0.025, wear);
        t.paint *= 1.0 - smoothstep(0.35, 0.7, scratch);
    }

    // Height: plate surface at 0, bevelled down into the grooves, rivet domes on top.
    const double r = rivet / kRivetRadius;
    double h = -kGrooveDepth * t.seam;
    h += kRivetHeight * std::sqrt(std::max(0.0, 1.0 - r * r));
    h += 0.0012 * (fbm(u, v, 4, 3, kSeedDent) - 0.5);
    h += 0.0002 * (fbm(u, v, 64, 2, kSeedGrain) - 0.5);
    h += kPaintThickness * t.paint;
    h -= 0.0003 * scratch;
    t.height = h;

    // Bare steel: per-plate tone, mottled, vertical run-off streaks, scratches a little brighter.
    const double tone = unit(hash(p.id, 4));
    t.streaks = smoothstep(0.45, 0.9,
                           0.7 * valueNoise(u, v, 48, 3, kSeedStreaks) +
                               0.3 * valueNoise(u, v, 96, 6, kSeedStreaks + 1));
    const double mottle =
        (0.75 + 0.5 * fbm(u, v, 8, 5, kSeedMetal)) * (1.0 - 0.3 * t.streaks) + 0.15 * scratch;
    t.metal = {lerp(0.36, 0.52, tone) * mottle, lerp(0.37, 0.52, tone) * mottle,
               lerp(0.39, 0.53, tone) * mottle};

    const auto& c = kPaints[hash(p.id, 5) % kPaints.size()];
    const double shade = 0.88 + 0.24 * fbm(u, v, 8, 3, kSeedPaint);
    t.paintColour = {srgbDecode(c[0] / 255.0) * shade, srgbDecode(c[1] / 255.0) * shade,
                     srgbDecode(c[2] / 255.0) * shade};

    t.roughMetal = 0.24 + 0.12 * unit(hash(p.id, 6)) +
                   0.22 * (fbm(u, v, 16, 4, kSeedRoughMetal) - 0.5) + 0.2 * scratch +
                   0.15 * t.streaks;
    t.roughPaint =
        0.5 + 0.12 * unit(hash(p.id, 7)) + 0.12 * (fbm(u, v, 32, 3, kSeedRoughPaint) - 0.5);
    return t;
}

// Ambient occlusion from the height field: in 8 directions, the highest horizon within a
// short radius; ao = 1 - mean sine of the horizon elevations. Wraps (the texture tiles).
std::vector<double> ambientOcclusion(const std::vector<double>& height, int size) {
    constexpr std::array<double, 5> radii = {0.003, 0.006, 0.012, 0.02, 0.03};
    constexpr double d = 0.70710678118654752;
    constexpr std::array<std::array<double, 2>, 8> dirs = {
        {{1, 0}, {d, d}, {0, 1}, {-d, d}, {-1, 0}, {-d, -d}, {0, -1}, {d, -d}}};
    auto wrap = [size](long long i) { return int(((i % size) + size) % size); };
    std::vector<double> ao(height.size());
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const double h0 = height[size_t(y) * size + x];
            double occlusion = 0.0;
            for (const auto& dir : dirs) {
                double maxTan = 0.0;
                for (double r : radii) {
                    const int sx = wrap(x + std::lround(dir[0] * r * size));
                    const int sy = wrap(y + std::lround(dir[1] * r * size));
                    maxTan = std::max(maxTan, (height[size_t(sy) * size + sx] - h0) / r);
                }
                occlusion += maxTan / std::sqrt(1.0 + maxTan * maxTan);
            }
            ao[size_t(y) * size + x] = clamp01(1.0 - 1.6 * occlusion / double(dirs.size()));
        }
    }
    return ao;
}

}  // namespace

void generateMetalPlates(const std::filesystem::path& outDir, int size) {
    if (size < 16 || size > 4096) {
        throw Error("generateMetalPlates: size " + std::to_string(size) + " is outside [16, 4096]");
    }
    std::error_code ec;
    std::filesystem::create_directories(outDir, ec);
    if (ec) {
        throw Error("generateMetalPlates: cannot create the directory '" + outDir.string() + "' (" +
                    ec.message() + ")");
    }

    const size_t n = size_t(size) * size;
    std::vector<Texel> texels(n);
    std::vector<double> height(n);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            // Texel centres; v grows downwards with the rows (row 0 = top of the image).
            const Texel t = evaluate((x + 0.5) / size, (y + 0.5) / size);
            texels[size_t(y) * size + x] = t;
            height[size_t(y) * size + x] = t.height;
        }
    }
    const std::vector<double> ao = ambientOcclusion(height, size);

    auto makeImage = [size](int channels) {
        Image img;
        img.width = img.height = size;
        img.channels = channels;
        img.pixels.resize(size_t(size) * size * channels);
        return img;
    };
    Image albedo = makeImage(3), roughness = makeImage(1), metallic = makeImage(1),
          occlusion = makeImage(1), normal = makeImage(3);

    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const size_t i = size_t(y) * size + x;
            const Texel& t = texels[i];
            const double cavity = 1.0 - ao[i];  // grime collects where the surface is occluded

            const double grime = 1.0 - 0.6 * clamp01(2.0 * cavity);
            albedo.at(x, y, 0) =
                float(srgbEncode(lerp(t.metal.r, t.paintColour.r, t.paint) * grime));
            albedo.at(x, y, 1) =
                float(srgbEncode(lerp(t.metal.g, t.paintColour.g, t.paint) * grime));
            albedo.at(x, y, 2) =
                float(srgbEncode(lerp(t.metal.b, t.paintColour.b, t.paint) * grime));

            const double rough = lerp(t.roughMetal, t.roughPaint, t.paint) + 0.3 * cavity;
            roughness.at(x, y, 0) = float(std::clamp(rough, 0.05, 1.0));
            metallic.at(x, y, 0) = float(1.0 - t.paint);
            occlusion.at(x, y, 0) = float(clamp01(ao[i]));

            // Tangent-space normal from central differences of the height (uv units, so the
            // slopes do not depend on the resolution). +X = right, +Y = image top (OpenGL):
            // dh/dY = -dh/drow.
            auto h = [&](int sx, int sy) {
                sx = (sx + size) % size;
                sy = (sy + size) % size;
                return height[size_t(sy) * size + sx];
            };
            const double step = 2.0 / size;
            const double dhdx = (h(x + 1, y) - h(x - 1, y)) / step;
            const double dhdrow = (h(x, y + 1) - h(x, y - 1)) / step;
            const double nx = -dhdx, ny = dhdrow, nz = 1.0;
            const double len = std::sqrt(nx * nx + ny * ny + nz * nz);
            normal.at(x, y, 0) = float(nx / len * 0.5 + 0.5);
            normal.at(x, y, 1) = float(ny / len * 0.5 + 0.5);
            normal.at(x, y, 2) = float(nz / len * 0.5 + 0.5);
        }
    }

    writeImage(outDir / "albedo.png", albedo, FileDepth::Uint8, true);
    writeImage(outDir / "roughness.png", roughness, FileDepth::Uint16);
    writeImage(outDir / "metallic.png", metallic, FileDepth::Uint16);
    writeImage(outDir / "ao.png", occlusion, FileDepth::Uint8);
    writeImage(outDir / "normal.png", normal, FileDepth::Uint8);
}

}  // namespace pbrlab
