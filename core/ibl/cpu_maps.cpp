// The maps computed on the CPU: the environment resampled into cube faces (and mips), and the
// bins convolution that gives the irradiance and the rough prefiltered mips (docs/ibl.md for
// why: more accurate than the GPU passes at a fraction of their time on llvmpipe).
#include "ibl/cpu_maps.h"

#include <algorithm>
#include <cmath>

#include "ibl/precompute.h"
#include "pbrlab/cube_sampler.h"
#include "pbrlab/ibl_reference.h"
#include "util/parallel.h"

namespace pbrlab {

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

// The cube bin (face, i, j) a direction falls in, for bins of n texels a side, as a cube map
// of n x n texels selects it. `d` is never zero here (texel directions of the sphere).
int binOf(const glm::dvec3& d, int n) {
    const CubeFacePoint p = cubeFacePoint(d);
    const int i = std::clamp(int(0.5 * (p.s + 1.0) * n), 0, n - 1);
    const int j = std::clamp(int(0.5 * (p.t + 1.0) * n), 0, n - 1);
    return (p.face * n + j) * n + i;
}

}  // namespace

EnvironmentBins binEnvironment(const Image& equirect, int n) {
    const int W = equirect.width, H = equirect.height, count = 6 * n * n;
    std::vector<double> sinPhi(static_cast<size_t>(W)), cosPhi(static_cast<size_t>(W));
    for (int x = 0; x < W; ++x) {
        const double phi = ((x + 0.5) / W - 0.5) * 2.0 * ref::kPi;
        sinPhi[size_t(x)] = std::sin(phi);
        cosPhi[size_t(x)] = std::cos(phi);
    }
    // A bin's power and its directions' moments under a weight: the grey power for the
    // environment's bins, the solid angle for the sphere's.
    struct Sums {
        glm::dvec3 power{0.0}, mean{0.0};
        double weight = 0, second[6] = {};
        void add(const glm::dvec3& d, double w) {
            weight += w;
            mean += w * d;
            const double dd[6] = {d.x * d.x, d.y * d.y, d.z * d.z, d.x * d.y, d.y * d.z, d.x * d.z};
            for (int k = 0; k < 6; ++k) second[k] += w * dd[k];
        }
    };
    std::vector<Sums> bins(static_cast<size_t>(count)), sphere(static_cast<size_t>(count));
    for (int y = 0; y < H; ++y) {
        const double t = ref::kPi * (y + 0.5) / H, st = std::sin(t), ct = std::cos(t);
        const double omega =
            2.0 * ref::kPi / W * (std::cos(ref::kPi * y / H) - std::cos(ref::kPi * (y + 1) / H));
        for (int x = 0; x < W; ++x) {
            const glm::dvec3 d(st * sinPhi[size_t(x)], ct, -st * cosPhi[size_t(x)]);
            const int bin = binOf(d, n);
            const glm::dvec3 p = ref::equirectTexel(equirect, x, y) * omega;
            bins[size_t(bin)].power += p;
            bins[size_t(bin)].add(d, std::max((p.x + p.y + p.z) / 3.0, 0.0));
            sphere[size_t(bin)].add(d, omega);
        }
    }
    EnvironmentBins out;
    out.packs.resize(size_t(count + 3) / 4, EnvironmentBins::Pack{});
    out.sphere.resize(out.packs.size(), EnvironmentBins::SpherePack{});
    // The moments of a bin's directions, normalised by their weight, into lane `lane`.
    auto moments = [](const Sums& b, Float4(&mean)[3], Float4(&second)[6], int lane) {
        const double g = b.weight > 0.0 ? 1.0 / b.weight : 0.0;
        for (int k = 0; k < 3; ++k) mean[k][lane] = float(b.mean[k] * g);
        for (int k = 0; k < 6; ++k) second[k][lane] = float(b.second[k] * g);
    };
    for (int i = 0; i < count; ++i) {
        EnvironmentBins::Pack& p = out.packs[size_t(i) / 4];
        EnvironmentBins::SpherePack& q = out.sphere[size_t(i) / 4];
        const int lane = i % 4;
        for (int k = 0; k < 3; ++k) p.power[k][lane] = float(bins[size_t(i)].power[k]);
        moments(bins[size_t(i)], p.mean, p.second, lane);
        q.solidAngle[lane] = float(sphere[size_t(i)].weight);
        moments(sphere[size_t(i)], q.mean, q.second, lane);
    }
    return out;
}

namespace {

// Karis' prefilter weight, expanded to second order over a bin (see convolveBins), for four
// bins: their mean direction's cosine to R and their R^T S R.
struct BinWeight {
    float b;
    Float4 operator()(Float4 c, Float4 RSR) const {
        const Float4 zero = {0, 0, 0, 0};
        const Float4 variance = RSR - c * c;
        const Float4 inv = 1.0f / (1.0f + b * (1.0f + c));
        const Float4 w = c * inv * inv;
        const Float4 w2 = (6.0f * b * b * c * inv - 4.0f * b) * inv * inv * inv;
        const Float4 k = w + 0.5f * w2 * (variance > 0.0f ? variance : zero);
        return c > 0.0f && k > 0.0f ? k : zero;
    }
};

// R's products for R^T S R with S = (xx yy zz xy yz xz): the off-diagonal ones doubled.
struct Quadratic {
    float r[6];
    explicit Quadratic(const glm::vec3& R)
        : r{R.x * R.x, R.y * R.y, R.z * R.z, 2 * R.x * R.y, 2 * R.y * R.z, 2 * R.x * R.z} {}
    Float4 operator()(const Float4 (&s)[6]) const {
        return r[0] * s[0] + r[1] * s[1] + r[2] * s[2] + r[3] * s[3] + r[4] * s[4] + r[5] * s[5];
    }
};

float laneSum(Float4 v) {
    return v[0] + v[1] + v[2] + v[3];
}

}  // namespace

// One cube map level of the environment convolved with the prefilter's lobe, from its bins.
// The prefiltered value at R is  sum over l of L(l) w(R.l) / sum over l of w(R.l)  with the
// weight of Karis' estimator, w(c) = c D(h) (N = V = R, (N.h)^2 = (1 + c) / 2), up to a
// constant: c / u^2, u = 1 + b (1 + c), b = (alpha^2 - 1) / 2. At roughness 1 (alpha^2 = 1)
// the weight is the cosine and the result is E / pi: the irradiance map is this convolution
// too. A bin stands for its texels through their moments: expanding w around c = R.m to
// second order, it adds  P (w(c) + w''(c) Var(R.d) / 2),  Var(R.d) = R^T S R - c^2. That is
// exact for the cosine, and a small bright sun inside a bin stays exactly where it is (m is
// its direction); bins below R's horizon (c <= 0) add nothing. The divisor is the same sum
// over the bins of a constant environment (EnvironmentBins::sphere), not the lobe's exact
// integral: where the expansion is off (a lobe narrower than a bin), numerator and divisor
// are off alike, and a constant environment stays constant. Accuracy in docs/ibl.md.
std::vector<Image> convolveBins(const EnvironmentBins& bins, int size, double roughness) {
    const double a = roughness * roughness, alpha2 = std::max(a * a, 1e-7);
    const BinWeight weight{float(0.5 * (alpha2 - 1.0))};
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
            const Quadratic quadratic(R);
            Float4 sum[3] = {zero, zero, zero}, divisor = zero;
            for (size_t i = 0; i < bins.packs.size(); ++i) {
                const EnvironmentBins::Pack& p = bins.packs[i];
                const Float4 c = R.x * p.mean[0] + R.y * p.mean[1] + R.z * p.mean[2];
                const Float4 k = weight(c, quadratic(p.second));
                for (int ch = 0; ch < 3; ++ch) sum[ch] += p.power[ch] * k;
                const EnvironmentBins::SpherePack& q = bins.sphere[i];
                const Float4 cq = R.x * q.mean[0] + R.y * q.mean[1] + R.z * q.mean[2];
                divisor += q.solidAngle * weight(cq, quadratic(q.second));
            }
            // The bins around R weigh more than 0: the divisor is never 0.
            const float scale = 1.0f / laneSum(divisor);
            for (int ch = 0; ch < 3; ++ch)
                faces[size_t(face)].at(x, y, ch) = laneSum(sum[ch]) * scale;
        }
    });
    return faces;
}

}  // namespace pbrlab
