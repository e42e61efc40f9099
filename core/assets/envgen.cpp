// The project's own HDR environment (see envgen.h). Everything is a pure function of the
// direction: sky, clouds, sun, two area lights and a tiled ground plane, averaged over 4 x 4
// sub-samples per texel.
#include "assets/envgen.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "assets/procedural.h"
#include "util/error.h"
#include "util/parallel.h"

namespace pbrlab {

namespace {

using glm::dvec2;
using glm::dvec3;
using u32 = std::uint32_t;

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// ---- integer hash noise (pure functions of their arguments) ----
using namespace procedural;

u32 hash(u32 seed, int a, int b, int c = 0) {
    return mix(seed ^ mix(u32(a) ^ mix(u32(b) ^ mix(u32(c) + 0x9e3779b9U))));
}

// Value noise on the integer lattice of 3D space, trilinear with a quintic fade, in [0, 1).
double valueNoise3(const dvec3& p, u32 seed) {
    const dvec3 f = glm::floor(p);
    const int x = int(f.x), y = int(f.y), z = int(f.z);
    const double tx = fade(p.x - f.x), ty = fade(p.y - f.y), tz = fade(p.z - f.z);
    auto corner = [&](int dx, int dy, int dz) { return unit(hash(seed, x + dx, y + dy, z + dz)); };
    const double c00 = lerp(corner(0, 0, 0), corner(1, 0, 0), tx);
    const double c10 = lerp(corner(0, 1, 0), corner(1, 1, 0), tx);
    const double c01 = lerp(corner(0, 0, 1), corner(1, 0, 1), tx);
    const double c11 = lerp(corner(0, 1, 1), corner(1, 1, 1), tx);
    return lerp(lerp(c00, c10, ty), lerp(c01, c11, ty), tz);
}

// Fractal sum of value noise, in [0, 1), mean about 0.5.
double fbm3(dvec3 p, int octaves, u32 seed) {
    double sum = 0.0, amplitude = 1.0, total = 0.0;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * valueNoise3(p, seed + u32(o) * 101u);
        total += amplitude;
        amplitude *= 0.5;
        p = p * 2.03 + dvec3(17.1, 5.3, 11.7);  // shifted so octaves do not share lattice points
    }
    return sum / total;
}

// ---- the scene ------------------------------------------------------------------------------

enum : u32 { kSeedClouds = 7, kSeedTiles = 19, kSeedStone = 29 };

// A direction from azimuth (0 = looking down -z, positive towards +x, as u grows in the
// equirectangular image) and elevation above the horizon.
dvec3 dirFromAzEl(double az, double el) {
    return {std::cos(el) * std::sin(az), std::sin(el), -std::cos(el) * std::cos(az)};
}

const dvec3 kSunDir = dirFromAzEl(130.0 * kDeg, 35.0 * kDeg);  // behind and right of a -z view
constexpr double kSunRadius = 1.2 * kDeg;
constexpr double kSunRadiance = 20000.0;
const dvec3 kSunColour(1.0, 0.96, 0.88);
// sky-sun's disc: the real sun's angular radius, and a radiance 1e5 times sky-soft's median
// (a clear day's sun is 1e4 to 1e5 times the sky: the dynamic range estimators meet in real
// HDRs).
constexpr double kSunDiscRadius = 0.27 * kDeg;
constexpr double kSunDiscRadiance = 5e4;

// Irradiance of the sun on a horizontal plane plus an estimate for the sky's, for the ground.
double groundIrradiance() {
    const double sunSolidAngle = kPi * kSunRadius * kSunRadius;
    return kSunRadiance * 0.8 * sunSolidAngle * kSunDir.y + kPi * 0.6;  // 0.8: limb darkening
}

struct AreaLight {
    double az, el;        // centre
    double halfW, halfH;  // angular half sizes (along the horizon, vertical)
    double softness;      // width of the smooth edge
    dvec3 radiance;
};

const AreaLight kLights[2] = {
    {-40.0 * kDeg, 12.0 * kDeg, 9.0 * kDeg, 5.0 * kDeg, 0.8 * kDeg, 80.0 * dvec3(1.0, 0.85, 0.65)},
    {75.0 * kDeg, 50.0 * kDeg, 6.0 * kDeg, 6.0 * kDeg, 0.8 * kDeg, 50.0 * dvec3(0.7, 0.85, 1.0)},
};

// 0..1 coverage of an area light at direction (az, el).
double lightCoverage(const AreaLight& l, double az, double el, bool soft) {
    double dAz = std::remainder(az - l.az, 2.0 * kPi) * std::cos(l.el);
    const double dEl = el - l.el;
    const double ex = std::abs(dAz) - l.halfW, ey = std::abs(dEl) - l.halfH;
    const double edge = soft ? 5.0 * l.softness : l.softness;
    return (1.0 - smoothstep(-edge, edge, ex)) * (1.0 - smoothstep(-edge, edge, ey));
}

dvec3 skyRadiance(const dvec3& d, bool soft) {
    const double y = std::max(d.y, 0.0);
    const dvec3 zenith(0.08, 0.18, 0.50), horizon(0.65, 0.75, 0.90);
    dvec3 sky = glm::mix(horizon, zenith, std::pow(y, 0.45));
    // Brighter towards the sun: a broad glow, and a tighter aureole around the disc.
    const double gamma = std::acos(std::clamp(glm::dot(d, kSunDir), -1.0, 1.0));
    // (The soft sky spreads the aureole's energy over ten times the angle.)
    sky += dvec3(1.0, 0.85, 0.6) *
           (0.35 * std::exp(-gamma / 0.5) +
            (soft ? 0.6 * std::exp(-gamma / 0.4) : 6.0 * std::exp(-gamma / 0.04)));
    // Clouds: fractal noise on the direction (seamless on the sphere), thinning to nothing at
    // the horizon, brighter and warmer near the sun.
    const double n = fbm3(d * 3.2, 5, kSeedClouds);
    const double density = smoothstep(0.52, 0.75, n) * smoothstep(0.03, 0.25, y);
    const dvec3 cloud = dvec3(0.95, 0.95, 0.97) * (1.1 + 0.6 * n) +
                        dvec3(1.0, 0.8, 0.55) * (2.0 * std::exp(-gamma / 0.3));
    return glm::mix(sky, cloud, 0.85 * density);
}

dvec3 groundRadiance(const dvec3& d) {
    const dvec3 horizon(0.65, 0.75, 0.90);
    constexpr double kEyeHeight = 1.6;
    const double t = kEyeHeight / std::max(-d.y, 1e-6);  // distance to the ground plane
    const dvec2 p(d.x * t, d.z * t);
    // 1 m stone tiles with 2 cm joints, each tile its own shade, with mottling noise.
    const dvec2 cell = glm::floor(p);
    const dvec2 f = p - cell;
    const double tileShade = unit(hash(kSeedTiles, int(cell.x), int(cell.y)));
    const double joint = std::min(std::min(f.x, 1.0 - f.x), std::min(f.y, 1.0 - f.y));
    const double mottle = fbm3(dvec3(p * 3.0, 0.5), 4, kSeedStone);
    dvec3 albedo = glm::mix(dvec3(0.05, 0.045, 0.04), dvec3(0.16, 0.14, 0.12), tileShade) *
                   (0.75 + 0.5 * mottle);
    albedo = glm::mix(dvec3(0.02), albedo, smoothstep(0.005, 0.02, joint));
    // Far away the tiles are smaller than a texel: fade to their mean, then into haze.
    albedo = glm::mix(albedo, dvec3(0.1, 0.09, 0.08), smoothstep(15.0, 60.0, t));
    const dvec3 lit = albedo * (groundIrradiance() / kPi);
    return glm::mix(horizon, lit, std::exp(-t / 120.0));
}

dvec3 environmentRadiance(const dvec3& d, bool soft) {
    dvec3 L = d.y >= 0.0 ? skyRadiance(d, soft) : groundRadiance(d);
    if (d.y >= -0.02) {  // the lights stand on the horizon at the lowest
        const double az = std::atan2(d.x, -d.z), el = std::asin(std::clamp(d.y, -1.0, 1.0));
        for (const AreaLight& l : kLights)
            L = glm::mix(L, (soft ? 0.1 : 1.0) * l.radiance, lightCoverage(l, az, el, soft));
    }
    if (soft) return L;
    const double gamma = std::acos(std::clamp(glm::dot(d, kSunDir), -1.0, 1.0));
    if (gamma < kSunRadius) {
        const double r = gamma / kSunRadius;
        const double limb = 1.0 - 0.6 * (1.0 - std::sqrt(1.0 - r * r));  // darker at the rim
        L = kSunColour * (kSunRadiance * limb);
    }
    return L;
}

}  // namespace

// An equirectangular image of `width` x width/2 texels, each the radiance `at` gives for the
// direction through its centre (y up, -z at the centre column).
template <class Radiance>
Image equirectangular(const std::string& what, int width, Radiance at) {
    if (width < 16 || width > 8192 || width % 2 != 0)
        throw Error(what + " environment: width " + std::to_string(width) +
                    " must be even and in [16, 8192]");
    Image image;
    image.width = width;
    image.height = width / 2;
    image.channels = 3;
    image.pixels.resize(size_t(image.width) * image.height * 3);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double phi = ((x + 0.5) / image.width - 0.5) * 2.0 * kPi;
            const double theta = (y + 0.5) / image.height * kPi;
            const dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                          -std::sin(theta) * std::cos(phi));
            const dvec3 L = at(d);
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(L[c]);
        }
    return image;
}

Image generateSmoothEnvironment(int width) {
    return equirectangular("smooth", width, [](const dvec3& d) {
        return dvec3(0.7, 0.8, 1.0) * (1.0 + 0.4 * d.y) +
               dvec3(0.3, 0.2, 0.1) * (0.5 + 0.5 * d.x + 0.2 * d.z * d.y);
    });
}

// The soft sky with a sun of the real sun's size and a real sky's dynamic range: the sky is
// sky-soft at 512 upsampled bilinearly (it has no feature under a degree to lose), the disc is
// antialiased with 8 x 8 sub-samples per texel, so that the cube of grading's size (256, 0.35
// degrees a texel) still holds it in a few texels at nearly its full radiance.
Image generateSunSky(int width) {
    if (width < 512 || width > 8192 || width % 2 != 0)
        throw Error("sky-sun environment: width " + std::to_string(width) +
                    " must be even and in [512, 8192]");
    const Image soft = generateSkyEnvironment(512, true);
    Image image;
    image.width = width;
    image.height = width / 2;
    image.channels = 3;
    image.pixels.resize(size_t(image.width) * image.height * 3);
    const double scale = 512.0 / image.width;
    const double cosReach = std::cos(2.0 * kSunDiscRadius);  // texels that may hold the disc
    parallelFor(size_t(image.height), [&](size_t row) {
        const int y = int(row);
        const double sy = std::clamp((y + 0.5) * scale - 0.5, 0.0, 255.0);
        const int y0 = int(sy), y1 = std::min(y0 + 1, 255);
        const double ty = sy - y0;
        for (int x = 0; x < image.width; ++x) {
            // Bilinear, wrapping around in azimuth.
            const double sx = (x + 0.5) * scale - 0.5;
            const int fx = int(std::floor(sx));
            const double tx = sx - fx;
            const int x0 = (fx + 512) % 512, x1 = (fx + 1) % 512;
            dvec3 L(0.0);
            for (int c = 0; c < 3; ++c)
                L[c] = lerp(lerp(soft.at(x0, y0, c), soft.at(x1, y0, c), tx),
                            lerp(soft.at(x0, y1, c), soft.at(x1, y1, c), tx), ty);
            const double phi = ((x + 0.5) / image.width - 0.5) * 2.0 * kPi,
                         theta = (y + 0.5) / image.height * kPi;
            const dvec3 centre(std::sin(theta) * std::sin(phi), std::cos(theta),
                               -std::sin(theta) * std::cos(phi));
            if (glm::dot(centre, kSunDir) > cosReach) {
                constexpr int kSub = 8;
                double disc = 0.0;
                for (int j = 0; j < kSub; ++j)
                    for (int i = 0; i < kSub; ++i) {
                        const double p = ((x + (i + 0.5) / kSub) / image.width - 0.5) * 2.0 * kPi;
                        const double t = (y + (j + 0.5) / kSub) / image.height * kPi;
                        const dvec3 d(std::sin(t) * std::sin(p), std::cos(t),
                                      -std::sin(t) * std::cos(p));
                        const double gamma = std::acos(std::clamp(glm::dot(d, kSunDir), -1.0, 1.0));
                        if (gamma >= kSunDiscRadius) continue;
                        const double r = gamma / kSunDiscRadius;
                        disc += 1.0 - 0.6 * (1.0 - std::sqrt(1.0 - r * r));  // limb darkening
                    }
                L += kSunColour * (kSunDiscRadiance * disc / (kSub * kSub));
            }
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(L[c]);
        }
    });
    return image;
}

Image generateHdrLobe(int width) {
    return equirectangular("hdr-lobe", width, [](const dvec3& d) {
        return kSunColour * (1e4 * std::pow(10.0, 0.5 * (1.0 + glm::dot(d, kSunDir))));
    });
}

namespace {

// "NAME*K" -> (NAME, K); K = 1 when there is no factor.
std::pair<std::string, double> splitFactor(const std::string& name) {
    const size_t star = name.rfind('*');
    if (star == std::string::npos) return {name, 1.0};
    try {
        size_t used = 0;
        const double k = std::stod(name.substr(star + 1), &used);
        if (used == name.size() - star - 1 && std::isfinite(k)) return {name.substr(0, star), k};
    } catch (const std::exception&) {
    }
    return {name, 1.0};
}

}  // namespace

bool isGeneratedEnvironment(const std::string& name) {
    const std::string base = splitFactor(name).first;
    return base == "sky" || base == "sky-soft" || base == "smooth" || base == "hdr-lobe" ||
           base == "sky-hdr" || base == "sky-sun" || base == "white";
}

Image generateEnvironment(const std::string& name) {
    const auto [base, factor] = splitFactor(name);
    Image image;
    if (base == "sky")
        image = generateSkyEnvironment(512);
    else if (base == "sky-soft")
        image = generateSkyEnvironment(512, true);
    else if (base == "smooth")
        image = generateSmoothEnvironment(256);
    else if (base == "hdr-lobe")
        image = generateHdrLobe(512);
    else if (base == "sky-hdr") {
        image = generateSkyEnvironment(512, true);
        const Image lobes = generateHdrLobe(512);
        // The sum in double, rounded once: the texel of sky-hdr is the float nearest to the
        // sum of the two environments' texels.
        for (size_t i = 0; i < image.pixels.size(); ++i)
            image.pixels[i] = float(double(image.pixels[i]) + double(lobes.pixels[i]));
    } else if (base == "sky-sun")
        image = generateSunSky(2048);
    else if (base == "white")
        image = generateWhiteEnvironment();
    else
        throw Error("no generated environment is called '" + name + "'");
    if (factor != 1.0)
        for (float& v : image.pixels) v = float(double(v) * factor);
    return image;
}

Image generateWhiteEnvironment(int width) {
    return equirectangular("white", width, [](const dvec3&) { return dvec3(1.0); });
}

Image brightTexels(const Image& environment, double overMedian) {
    const size_t texels = size_t(environment.width) * size_t(environment.height);
    const int channels = environment.channels;
    auto luminance = [&](size_t i) {
        const float* p = &environment.pixels[i * size_t(channels)];
        return channels >= 3 ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : double(p[0]);
    };
    std::vector<double> values(texels);
    for (size_t i = 0; i < texels; ++i) values[i] = luminance(i);
    std::nth_element(values.begin(), values.begin() + long(texels / 2), values.end());
    const double threshold = overMedian * values[texels / 2];
    Image bright = environment;
    for (size_t i = 0; i < texels; ++i)
        if (!(luminance(i) > threshold))
            for (int c = 0; c < channels; ++c) bright.pixels[i * size_t(channels) + size_t(c)] = 0;
    return bright;
}

glm::dvec3 skySunDirection() {
    return kSunDir;
}

double skySunAngularRadius() {
    return kSunRadius;
}

Image generateSkyEnvironment(int width, bool soft) {
    if (width < 16 || width > 8192 || width % 2 != 0)
        throw Error("sky environment: width " + std::to_string(width) +
                    " must be even and in [16, 8192]");
    Image image;
    image.width = width;
    image.height = width / 2;
    image.channels = 3;
    image.pixels.resize(size_t(image.width) * image.height * 3);
    constexpr int kSub = 4;
    // Rows in parallel: the GUI's and every grading process's first IBL frame waits for it.
    parallelFor(size_t(image.height), [&](size_t row) {
        const int y = int(row);
        for (int x = 0; x < image.width; ++x) {
            dvec3 sum(0.0);
            for (int sy = 0; sy < kSub; ++sy)
                for (int sx = 0; sx < kSub; ++sx) {
                    const dvec2 uv((x + (sx + 0.5) / kSub) / image.width,
                                   (y + (sy + 0.5) / kSub) / image.height);
                    const double phi = (uv.x - 0.5) * 2.0 * kPi, theta = uv.y * kPi;
                    const dvec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                                  -std::sin(theta) * std::cos(phi));
                    sum += environmentRadiance(d, soft);
                }
            sum /= double(kSub * kSub);
            for (int c = 0; c < 3; ++c) image.at(x, y, c) = float(sum[c]);
        }
    });
    return image;
}

}  // namespace pbrlab
