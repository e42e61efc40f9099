// TexelSums (ibl_reference.h): the irradiance and prefilter integrals as exact sums over an
// equirectangular image's texels, evaluated hierarchically.
#include <algorithm>
#include <cmath>
#include <vector>

#include "pbrlab/ibl_reference.h"
#include "util/error.h"

namespace pbrlab::ref {

namespace {

// The angle between two unit vectors, accurate for small angles too (acos is not).
double angleBetween(const dvec3& a, const dvec3& b) {
    return 2.0 * std::asin(std::min(1.0, 0.5 * glm::length(a - b)));
}

// The prefilter's weight per solid angle of l as a function of c = N.l: c D(h) with
// (N.h)^2 = (1 + c) / 2 (N = V), D as distributionGGX with its alpha floor; 0 below the
// horizon. With u = 1 + b (1 + c), b = (alpha^2 - 1) / 2: w = (alpha^2 / pi) c / u^2.
struct PrefilterKernel {
    double a2, b;
    explicit PrefilterKernel(double alpha2) : a2(alpha2), b(0.5 * (alpha2 - 1.0)) {}
    double operator()(double c) const {
        if (c <= 0.0) return 0.0;
        const double u = 1.0 + b * (1.0 + c);
        return a2 / kPi * c / (u * u);
    }
    double second(double c) const {  // d^2 w / dc^2
        const double u = 1.0 + b * (1.0 + c);
        return a2 / kPi * (6.0 * b * b * c / u - 4.0 * b) / (u * u * u);
    }
};

struct CosineKernel {
    double operator()(double c) const { return std::max(c, 0.0); }
    double second(double) const { return 0.0; }
};

// Finest blocks of blockSize x blockSize texels: at most ~8k of them (3 MB of blocks in all),
// since fresh memory is slow to touch on some machines (page faults).
int finestBlockSize(int width, int height) {
    int size = 4;
    while (double(width) * height / (double(size) * size) > 8192.0) size *= 2;
    return size;
}

}  // namespace

void TexelSums::Moments::add(const dvec3& d, double w) {
    weight += w;
    mean += w * d;
    const double m[6] = {d.x * d.x, d.y * d.y, d.z * d.z, d.x * d.y, d.y * d.z, d.x * d.z};
    for (int k = 0; k < 6; ++k) second[k] += w * m[k];
}

void TexelSums::Moments::add(const Moments& m) {
    weight += m.weight;
    mean += m.weight * m.mean;
    for (int k = 0; k < 6; ++k) second[k] += m.weight * m.second[k];
}

void TexelSums::Moments::normalise() {
    if (weight <= 0.0) return;
    mean /= weight;
    for (double& v : second) v /= weight;
}

TexelSums::TexelSums(const Image& equirect, double opening)
    : image_(equirect),
      blockSize_(finestBlockSize(equirect.width, equirect.height)),
      opening_(opening) {
    const int W = image_.width, H = image_.height;
    if (W <= 0 || H <= 0 || image_.channels <= 0 ||
        image_.pixels.size() != size_t(W) * size_t(H) * size_t(image_.channels))
        throw Error("texel sums: empty or inconsistent image (" + std::to_string(W) + " x " +
                    std::to_string(H) + ", " + std::to_string(image_.channels) + " channels)");
    for (int y = 0; y < H; ++y) {
        const double t = kPi * (y + 0.5) / H;
        rowSolidAngle_.push_back(((2.0 * kPi) / W) *
                                 (std::cos(kPi * y / H) - std::cos(kPi * (y + 1) / H)));
        rowSin_.push_back(std::sin(t));
        rowCos_.push_back(std::cos(t));
    }
    for (int x = 0; x < W; ++x) {
        const double phi = ((x + 0.5) / W - 0.5) * (2.0 * kPi);
        colSin_.push_back(std::sin(phi));
        colCos_.push_back(std::cos(phi));
    }
    int bw = (W + blockSize_ - 1) / blockSize_, bh = (H + blockSize_ - 1) / blockSize_;
    std::vector<Block> level = finestLevel(bw, bh);
    // Coarser levels, 2 x 2 blocks of the one below, up to a level of at most 4 x 2 blocks.
    for (int size = blockSize_;; size *= 2) {
        levels_.push_back(std::move(level));
        widths_.push_back(bw);
        heights_.push_back(bh);
        if (bw <= 4 && bh <= 2) break;
        const int fw = bw, fh = bh;
        bw = (fw + 1) / 2;
        bh = (fh + 1) / 2;
        level = coarserLevel(levels_.back(), fw, fh, bw, bh, size);
    }
}

// The finest level, bw x bh blocks of blockSize_ texels a side summed from the texels (their
// bounds a new level of bounds_).
std::vector<TexelSums::Block> TexelSums::finestLevel(int bw, int bh) {
    const int W = image_.width, H = image_.height;
    std::vector<Block> level(size_t(bw) * size_t(bh));
    bounds_.emplace_back();
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            Block& b = level[size_t(by) * size_t(bw) + size_t(bx)];
            const int x0 = bx * blockSize_, y0 = by * blockSize_;
            const int x1 = std::min(W, x0 + blockSize_), y1 = std::min(H, y0 + blockSize_);
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const dvec3 d(rowSin_[size_t(y)] * colSin_[size_t(x)], rowCos_[size_t(y)],
                                  -rowSin_[size_t(y)] * colCos_[size_t(x)]);
                    const double omega = rowSolidAngle_[size_t(y)];
                    const dvec3 L = texel(x, y);
                    for (int c = 0; c < 3; ++c) b.power[c].add(d, L[c] * omega);
                    b.solidAngle.add(d, omega);
                }
            bounds_.back().push_back(finish(b, x0, y0, x1, y1));
        }
    return level;
}

// The level above `fine` (fw x fh blocks of `size` texels a side): bw x bh blocks, each the
// sum of its 2 x 2 children (their bounds a new level of bounds_).
std::vector<TexelSums::Block> TexelSums::coarserLevel(const std::vector<Block>& fine, int fw,
                                                      int fh, int bw, int bh, int size) {
    const int W = image_.width, H = image_.height;
    std::vector<Block> level(size_t(bw) * size_t(bh), Block());
    bounds_.emplace_back();
    for (int by = 0; by < bh; ++by)
        for (int bx = 0; bx < bw; ++bx) {
            Block& b = level[size_t(by) * size_t(bw) + size_t(bx)];
            for (int cy = 2 * by; cy < std::min(fh, 2 * by + 2); ++cy)
                for (int cx = 2 * bx; cx < std::min(fw, 2 * bx + 2); ++cx) {
                    const Block& child = fine[size_t(cy) * size_t(fw) + size_t(cx)];
                    for (int c = 0; c < 3; ++c) b.power[c].add(child.power[c]);
                    b.solidAngle.add(child.solidAngle);
                }
            bounds_.back().push_back(finish(b, bx * 2 * size, by * 2 * size,
                                            std::min(W, (bx + 1) * 2 * size),
                                            std::min(H, (by + 1) * 2 * size)));
        }
    return level;
}

// A block whose sums are complete, its moments normalised; returns its bound, for the texels
// of columns x0..x1 and rows y0..y1. A block covers a rectangle of rows and columns: in angles,
// a patch between two latitudes and two longitudes. Seen from a direction on its middle
// meridian (its axis), the patch's farthest points are corners: along a meridian (a great
// circle) the distance to a point is largest at an end, along a latitude it grows with the
// longitude difference.
TexelSums::Bound TexelSums::finish(Block& b, int x0, int y0, int x1, int y1) const {
    const int W = image_.width, H = image_.height;
    for (Moments& m : b.power) m.normalise();
    b.solidAngle.normalise();
    Bound bound;
    bound.axis = glm::normalize(b.solidAngle.mean);
    for (double v : {double(y0), double(y1)})
        for (double u : {double(x0), double(x1)})
            bound.radius =
                std::max(bound.radius, angleBetween(bound.axis, equirectDirection({u / W, v / H})));
    bound.sinRadius = std::sin(std::min(bound.radius, kPi / 2.0));
    bound.cosFar =
        opening_ > 0.0 && bound.radius / opening_ < kPi ? std::cos(bound.radius / opening_) : -2.0;
    return bound;
}

template <class Kernel>
void TexelSums::accumulate(const dvec3& N, double lobeWidth, const Kernel& kernel, dvec3& weighted,
                           double& weight) const {
    const double fineEnough = opening_ * lobeWidth;
    // N.l for texel (x, y) is N.y cos(theta_y) + sin(theta_y) (N.x sin(phi_x) - N.z cos(phi_x)).
    std::vector<double> across(colSin_.size());
    for (size_t x = 0; x < across.size(); ++x) across[x] = N.x * colSin_[x] - N.z * colCos_[x];
    // The kernel's sum over directions with these moments, to second order.
    auto moments = [&](const Moments& m) {
        const double c = glm::dot(N, m.mean);
        const double nSn =
            N.x * N.x * m.second[0] + N.y * N.y * m.second[1] + N.z * N.z * m.second[2] +
            2.0 * (N.x * N.y * m.second[3] + N.y * N.z * m.second[4] + N.x * N.z * m.second[5]);
        return m.weight * (kernel(c) + 0.5 * kernel.second(c) * std::max(nSn - c * c, 0.0));
    };
    std::vector<std::pair<int, int>> stack;  // (level, block)
    const int top = int(levels_.size()) - 1;
    for (int i = 0; i < int(levels_[size_t(top)].size()); ++i) stack.emplace_back(top, i);
    while (!stack.empty()) {
        const auto [level, index] = stack.back();
        stack.pop_back();
        const Bound& bound = bounds_[size_t(level)][size_t(index)];
        const double c = glm::dot(N, bound.axis);
        if (c < -bound.sinRadius) continue;  // every direction of the block is below the horizon
        if (c > bound.sinRadius && (bound.radius <= fineEnough || c <= bound.cosFar)) {
            const Block& b = levels_[size_t(level)][size_t(index)];
            for (int k = 0; k < 3; ++k) weighted[k] += moments(b.power[k]);
            weight += moments(b.solidAngle);
            continue;
        }
        const int bx = index % widths_[size_t(level)], by = index / widths_[size_t(level)];
        if (level == 0) {
            const int x0 = bx * blockSize_, y0 = by * blockSize_;
            const int x1 = std::min(image_.width, x0 + blockSize_);
            const int y1 = std::min(image_.height, y0 + blockSize_);
            for (int y = y0; y < y1; ++y) {
                const double a = N.y * rowCos_[size_t(y)], s = rowSin_[size_t(y)];
                const double omega = rowSolidAngle_[size_t(y)];
                for (int x = x0; x < x1; ++x) {
                    const double k = kernel(a + s * across[size_t(x)]) * omega;
                    if (k <= 0.0) continue;
                    weighted += k * texel(x, y);
                    weight += k;
                }
            }
            continue;
        }
        const int fw = widths_[size_t(level) - 1], fh = heights_[size_t(level) - 1];
        for (int cy = 2 * by; cy < std::min(fh, 2 * by + 2); ++cy)
            for (int cx = 2 * bx; cx < std::min(fw, 2 * bx + 2); ++cx)
                stack.emplace_back(level - 1, cy * fw + cx);
    }
}

dvec3 TexelSums::irradiance(const dvec3& N) const {
    // The cosine is linear in l: a block's moments give its sum exactly at any size, so only
    // the horizon opens blocks.
    dvec3 weighted(0.0);
    double weight = 0.0;
    accumulate(N, 1e300, CosineKernel(), weighted, weight);
    return weighted / kPi;
}

dvec3 TexelSums::prefilter(const dvec3& R, double roughness) const {
    // The lobe's width in l: twice alpha (l turns twice as far as h).
    const double alpha2 = ggxAlpha2(roughness);
    dvec3 weighted(0.0);
    double weight = 0.0;
    accumulate(R, 2.0 * std::sqrt(alpha2), PrefilterKernel(alpha2), weighted, weight);
    return weight > 0.0 ? weighted / weight : dvec3(0.0);
}

dvec3 TexelSums::meanRadiance() const {
    dvec3 power(0.0);
    for (const Block& b : levels_.back())
        for (int c = 0; c < 3; ++c) power[c] += b.power[c].weight;
    return power / (4.0 * kPi);
}

}  // namespace pbrlab::ref
