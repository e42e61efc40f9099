#include "pbrlab/cube_sampler.h"

#include <algorithm>
#include <cmath>

namespace pbrlab {

namespace {

glm::dvec4 texel(const Image& im, int x, int y) {
    x = std::clamp(x, 0, im.width - 1);
    y = std::clamp(y, 0, im.height - 1);
    glm::dvec4 v(0);
    for (int c = 0; c < std::min(im.channels, 4); ++c) v[c] = im.at(x, y, c);
    return v;
}

}  // namespace

glm::dvec4 sampleTexture(const Image& im, const glm::dvec2& uv) {
    double x = std::clamp(uv.x, 0.0, 1.0) * im.width - 0.5;
    double y = std::clamp(uv.y, 0.0, 1.0) * im.height - 0.5;
    int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    double fx = x - x0, fy = y - y0;
    return glm::mix(glm::mix(texel(im, x0, y0), texel(im, x0 + 1, y0), fx),
                    glm::mix(texel(im, x0, y0 + 1), texel(im, x0 + 1, y0 + 1), fx), fy);
}

CubeFacePoint cubeFacePoint(const glm::dvec3& d) {
    // Table 8.19: the major axis picks the face and its sign, then sc, tc and ma.
    const glm::dvec3 a = glm::abs(d);
    int face;
    double sc, tc, ma;
    if (a.x >= a.y && a.x >= a.z) {
        face = d.x >= 0 ? 0 : 1;
        sc = d.x >= 0 ? -d.z : d.z;
        tc = -d.y;
        ma = a.x;
    } else if (a.y >= a.z) {
        face = d.y >= 0 ? 2 : 3;
        sc = d.x;
        tc = d.y >= 0 ? d.z : -d.z;
        ma = a.y;
    } else {
        face = d.z >= 0 ? 4 : 5;
        sc = d.z >= 0 ? d.x : -d.x;
        tc = -d.y;
        ma = a.z;
    }
    if (!(ma > 0)) return {};
    return {face, sc / ma, tc / ma};
}

glm::dvec3 cubeFaceDirection(int face, double s, double t) {
    // Table 8.19 solved for the direction, with ma = 1.
    switch (face) {
        case 0:
            return {1.0, -t, -s};
        case 1:
            return {-1.0, -t, s};
        case 2:
            return {s, 1.0, t};
        case 3:
            return {s, -1.0, -t};
        case 4:
            return {s, -t, 1.0};
        default:
            return {-s, -t, -1.0};
    }
}

glm::dvec4 CubeSampler::texelAcrossEdges(int level, int face, int x, int y) const {
    const Image& im = mips_[size_t(level)][size_t(face)];
    const int n = im.width;
    const bool xOut = x < 0 || x >= n, yOut = y < 0 || y >= n;
    if (!xOut && !yOut) return texel(im, x, y);
    if (xOut && yOut) {  // a corner: the three texels that meet there
        const int xc = std::clamp(x, 0, n - 1), yc = std::clamp(y, 0, n - 1);
        return (texel(im, xc, yc) + texelAcrossEdges(level, face, x, yc) +
                texelAcrossEdges(level, face, xc, y)) /
               3.0;
    }
    // The texel's centre lies just beyond the edge: the direction through it selects the
    // neighbouring face, and the texel of that face it falls in.
    const double s = 2.0 * (x + 0.5) / n - 1, t = 2.0 * (y + 0.5) / n - 1;
    const CubeFacePoint q = cubeFacePoint(cubeFaceDirection(face, s, t));
    const auto index = [n](double c) {
        return std::clamp(int(std::floor(0.5 * (c + 1) * n)), 0, n - 1);
    };
    return texel(mips_[size_t(level)][size_t(q.face)], index(q.s), index(q.t));
}

glm::dvec3 CubeSampler::sampleLevel(const glm::dvec3& d, int level) const {
    const CubeFacePoint p = cubeFacePoint(d);
    if (p.face < 0) return glm::dvec3(0);
    const glm::dvec2 st(0.5 * (p.s + 1), 0.5 * (p.t + 1));
    const Image& im = mips_[size_t(level)][size_t(p.face)];
    if (!seamless_) return glm::dvec3(sampleTexture(im, st));
    const double x = st.x * im.width - 0.5, y = st.y * im.height - 0.5;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const double fx = x - x0, fy = y - y0;
    const auto at = [&](int dx, int dy) {
        return texelAcrossEdges(level, p.face, x0 + dx, y0 + dy);
    };
    return glm::dvec3(
        glm::mix(glm::mix(at(0, 0), at(1, 0), fx), glm::mix(at(0, 1), at(1, 1), fx), fy));
}

glm::dvec3 CubeSampler::sample(const glm::dvec3& dir, double lod) const {
    if (mips_.empty()) return glm::dvec3(0);
    lod = std::clamp(lod, 0.0, double(mips_.size() - 1));
    int l0 = int(std::floor(lod));
    int l1 = std::min(l0 + 1, int(mips_.size()) - 1);
    double f = lod - l0;
    glm::dvec3 a = sampleLevel(dir, l0);
    return f > 0 ? glm::mix(a, sampleLevel(dir, l1), f) : a;
}

}  // namespace pbrlab
