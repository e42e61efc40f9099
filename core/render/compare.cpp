#include "render/compare.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

#include "util/parallel.h"

namespace pbrlab {

namespace {

glm::dvec3 absolute(const glm::dvec3& v) {
    return glm::abs(v);
}

bool finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

glm::dvec3 referenceSpread(const ModuleDesc& module, const Surface& s,
                           const ReferenceContext& context, double ulps, std::uint64_t seed) {
    if (ulps <= 0) return glm::dvec3(0);
    const glm::dvec3 base = module.reference(s, context);
    DomainRandom random(seed);
    // One float ulp of a value in [1, 2) is 2^-23. Vectors move by ulps of their length (what
    // rounding in a dot product or a normalisation does to each component), scalars by ulps
    // of themselves.
    const double u = ulps * std::ldexp(1.0, -23);
    auto sign = [&] { return random.uniform() < 0.5 ? -1.0 : 1.0; };
    auto scalar = [&](double v) { return v * (1 + u * sign()); };
    auto vector = [&](auto v) {
        const double scale = u * std::sqrt(glm::dot(v, v));
        for (int c = 0; c < v.length(); ++c) v[c] += scale * sign();
        return v;
    };
    glm::dvec3 spread(0);
    // The extreme change of a function that is smooth at this scale is at a corner of the
    // box of perturbations: eight random corners.
    for (int trial = 0; trial < 8; ++trial) {
        Surface p = s;
        p.position = vector(p.position);
        p.normal = vector(p.normal);
        p.tangent = vector(p.tangent);
        p.uv = vector(p.uv);
        p.view = vector(p.view);
        p.light = vector(p.light);
        p.lightPosition = vector(p.lightPosition);
        p.lightColor = vector(p.lightColor);
        p.albedoTexel = vector(p.albedoTexel);
        p.albedo = vector(p.albedo);
        p.metallic = scalar(p.metallic);
        p.roughness = scalar(p.roughness);
        p.ao = scalar(p.ao);
        p.normalTexel = vector(p.normalTexel);
        p.emissive = vector(p.emissive);
        p.extra = vector(p.extra);
        ReferenceContext moved{context.params, context.lights, context.cameraPosition, context.ibl};
        for (ref::PointLight& l : moved.lights) {
            l.position = vector(l.position);
            l.color = vector(l.color);
        }
        const glm::dvec3 v = module.reference(p, moved);
        if (finite(v)) spread = glm::max(spread, absolute(v - base));
    }
    return spread;
}

double Band::excess(size_t i, const glm::dvec3& v, int components) const {
    auto distance = [&](const glm::dvec3& a, const glm::dvec3& b) {
        double e = 0;
        for (int c = 0; c < components; ++c) {
            const double lo = a[c], hi = b[c], s = slack[i][c];
            if (!std::isfinite(v[c]) || !std::isfinite(lo) || !std::isfinite(hi)) {
                if (std::isfinite(v[c]) != (std::isfinite(lo) && std::isfinite(hi))) return 1e30;
                continue;
            }
            e = std::max(e, std::max({lo - v[c], v[c] - hi, 0.0}) / std::max(s, 1e-300));
        }
        return e;
    };
    double e = distance(lo[i], hi[i]);
    for (const auto& alternative : separate)
        e = std::min(e, distance(alternative[i], alternative[i]));
    return e;
}

// The band at one point (its reference, alternatives and slack).
static void bandAt(const ModuleDesc& module, const Surface& s, const ReferenceContext& context,
                   double ulps, size_t i, Band& band) {
    if (!s.covered) return;
    const glm::dvec3 r = module.reference(s, context);
    glm::dvec3 lo = r, hi = r, magnitude = glm::abs(r);
    size_t separate = 0;
    for (const AcceptedAlternative& a : module.alternatives) {
        const glm::dvec3 v = a.value(s, context);
        if (a.range) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        } else {
            band.separate[separate++][i] = v;
        }
        magnitude = glm::max(magnitude, glm::abs(v));
    }
    const glm::dvec3 spread = referenceSpread(module, s, context, ulps, i + 1);
    glm::dvec3 slack(0);
    for (int c = 0; c < module.components; ++c) {
        const Tolerance& t = module.toleranceFor(c);
        slack[c] = std::max(
            {t.absolute, t.relative * magnitude[c], ulps > 0 ? spread[c] * (t.ulps / ulps) : 0.0});
    }
    band.expected[i] = r;
    band.lo[i] = lo;
    band.hi[i] = hi;
    band.slack[i] = slack;
}

Band referenceBand(const ModuleDesc& module, const std::vector<Surface>& surfaces,
                   const ReferenceContext& context, const StopRequested& stop) {
    Band band;
    band.resize(surfaces.size());
    for (const AcceptedAlternative& a : module.alternatives)
        if (!a.range) band.separate.emplace_back(surfaces.size(), glm::dvec3(0));
    double ulps = 0;
    for (int c = 0; c < module.components; ++c) ulps = std::max(ulps, module.toleranceFor(c).ulps);
    // Nine or more reference evaluations per point (the spread's eight corners): on every
    // core. The references are pure functions of their inputs.
    std::atomic<bool> stopped{false};
    parallelFor(surfaces.size(), [&](size_t i) {
        if (stopped.load(std::memory_order_relaxed)) return;
        if (stop && stop()) {
            stopped = true;
            return;
        }
        bandAt(module, surfaces[i], context, ulps, i, band);
    });
    if (stopped) throw Cancelled();
    return band;
}

Comparison compareWithBand(const Image& value, const std::vector<Surface>& surfaces,
                           const Band& band, int components, bool nonNegative,
                           double outlierFraction) {
    Comparison s;
    std::vector<double> excesses;
    for (int y = 0; y < value.height; ++y)
        for (int x = 0; x < value.width; ++x) {
            const size_t i = size_t(y) * size_t(value.width) + size_t(x);
            if (i >= surfaces.size() || !surfaces[i].covered) continue;
            ++s.compared;
            bool nan = false, inf = false, negative = false;
            const glm::dvec3 v(value.at(x, y, 0), value.at(x, y, 1), value.at(x, y, 2));
            for (int c = 0; c < components; ++c) {
                nan = nan || std::isnan(v[c]);
                inf = inf || std::isinf(v[c]);
                negative = negative || v[c] < 0;
            }
            const double excess = band.excess(i, v, components);
            excesses.push_back(excess);
            s.outside += excess > 1;
            s.nanCount += nan;
            s.infCount += inf;
            s.negativeCount += negative && nonNegative;
            if (s.worstIndex < 0 || excess > s.worstExcess) {
                s.worstExcess = excess;
                s.worstIndex = int(i);
                s.worstX = x;
                s.worstY = y;
                s.worstValue = {value.at(x, y, 0), value.at(x, y, 1), value.at(x, y, 2)};
                s.worstExpected = band.expected[i];
                s.worstLo = band.lo[i] - band.slack[i];
                s.worstHi = band.hi[i] + band.slack[i];
            }
        }
    if (!excesses.empty()) {
        const size_t k = size_t(double(excesses.size() - 1) * (1 - outlierFraction));
        std::nth_element(excesses.begin(), excesses.begin() + long(k), excesses.end());
        s.quantileExcess = excesses[k];
    }
    return s;
}

std::string describe(const Comparison& s) {
    std::ostringstream o;
    o.precision(4);
    o << s.compared << " points, " << s.outside << " outside the band, worst " << s.worstExcess
      << " x the tolerance";
    if (s.nonFinite() + s.negativeCount > 0)
        o << ", NaN " << s.nanCount << ", Inf " << s.infCount << ", negative " << s.negativeCount;
    return o.str();
}

}  // namespace pbrlab
