#include "render/display.h"

#include <algorithm>
#include <cmath>

#include "util/color.h"

namespace pbrlab {

namespace {

double normalised(double v, const Display& d) {
    if (d.logScale)
        return (std::log(std::max(v, 1e-30)) - std::log(d.lo)) / (std::log(d.hi) - std::log(d.lo));
    return (v - d.lo) / (d.hi - d.lo);
}

}  // namespace

glm::dvec3 falseColor(double t) {
    static const glm::dvec3 stops[5] = {{0.02, 0.02, 0.12},
                                        {0.30, 0.05, 0.55},
                                        {0.80, 0.20, 0.35},
                                        {0.98, 0.60, 0.10},
                                        {1.00, 1.00, 0.75}};
    if (!(t > 0)) t = 0;  // also NaN
    t = std::min(t, 1.0) * 4;
    int i = std::min(int(t), 3);
    return glm::mix(stops[i], stops[i + 1], t - i);
}

glm::dvec3 displayColor(const glm::dvec4& value, const Display& d, int components) {
    if (value.a == 0) return kBackgroundColor;
    glm::dvec3 v(value);
    if (components == 1) v = glm::dvec3(v.x);
    if (components == 2) v.z = 0;
    for (int c = 0; c < 3; ++c) {
        if (std::isnan(v[c])) return kNanColor;
        if (std::isinf(v[c])) return kInfColor;
    }
    glm::dvec3 out;
    switch (d.mode) {
        case DisplayMode::Grey:
            for (int c = 0; c < 3; ++c) out[c] = std::clamp(normalised(v[c], d), 0.0, 1.0);
            break;
        case DisplayMode::LinearColor:
            for (int c = 0; c < 3; ++c) out[c] = srgbEncode(v[c]);
            break;
        case DisplayMode::HdrColor:
            for (int c = 0; c < 3; ++c) {
                double h = std::max(v[c], 0.0);
                out[c] = std::pow(h / (h + 1), 1 / 2.2);
            }
            break;
        case DisplayMode::SignedVector:
            out = glm::clamp(0.5 + 0.5 * v, 0.0, 1.0);
            break;
        case DisplayMode::FalseColor:
            out = falseColor(normalised(v.x, d));
            break;
        case DisplayMode::Encoded:
            out = glm::clamp(v, 0.0, 1.0);
            break;
    }
    return out;
}

Image displayImage(const Image& value, const Display& display, int components) {
    Image out;
    out.width = value.width;
    out.height = value.height;
    out.channels = 4;
    out.pixels.resize(size_t(value.width) * value.height * 4);
    for (int y = 0; y < value.height; ++y)
        for (int x = 0; x < value.width; ++x) {
            glm::dvec4 v(value.at(x, y, 0), value.at(x, y, 1), value.at(x, y, 2),
                         value.at(x, y, 3));
            glm::dvec3 c = displayColor(v, display, components);
            for (int k = 0; k < 3; ++k) out.at(x, y, k) = float(c[k]);
            out.at(x, y, 3) = 1;
        }
    return out;
}

Image differenceImage(const Image& a, const Image& b, int components, double range) {
    Image diff = a;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            double d = 0;
            bool background = a.at(x, y, 3) == 0 || b.at(x, y, 3) == 0;
            for (int c = 0; c < components; ++c) {
                double e = std::abs(double(a.at(x, y, c)) - b.at(x, y, c));
                d = std::isnan(e) ? e : std::max(d, e);
            }
            glm::dvec3 color = background      ? kBackgroundColor
                               : std::isnan(d) ? kNanColor
                               : std::isinf(d) ? kInfColor
                                               : falseColor(d / range);
            for (int c = 0; c < 3; ++c) diff.at(x, y, c) = float(color[c]);
            diff.at(x, y, 3) = 1;
        }
    return diff;
}

}  // namespace pbrlab
