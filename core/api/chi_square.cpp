// The chi-square test of GGX half vectors (ibl_reference.h): the distribution a sampler
// draws against the density it claims, by bins of equal expected count.
#include <algorithm>
#include <cmath>
#include <vector>

#include "pbrlab/ibl_reference.h"

namespace pbrlab::ref {

double chiSquareTail(double chi2, int dof) {
    const double a = 0.5 * dof, x = 0.5 * chi2;
    if (x <= 0) return 1;
    const double logPrefix = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1) {  // series
        double term = 1 / a, sum = term;
        for (int n = 1; n < 10000 && std::abs(term) > std::abs(sum) * 1e-15; ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return std::max(0.0, 1 - sum * std::exp(logPrefix));
    }
    double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;  // Lentz's continued fraction
    for (int i = 1; i < 10000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (std::abs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1) < 1e-15) break;
    }
    return std::exp(logPrefix) * h;
}

ChiSquareTest ggxHalfVectorChiSquare(const std::vector<dvec3>& samples, const dvec3& Nin,
                                     double roughness) {
    constexpr int kThetaBins = 16, kPhiBins = 8;
    const dvec3 N = glm::normalize(Nin);
    // Theta is binned by s = ln tan(theta): the lobe is a smooth bump around ln(alpha) at every
    // roughness, and float directions keep their relative precision there.
    const double lnAlpha = std::log(std::max(roughness * roughness, kIblMinAlpha));
    std::vector<double> edges;
    for (int j = 0; j <= kThetaBins; ++j) {
        const double u = double(j) / kThetaBins;
        edges.push_back(j == 0            ? lnAlpha - 40
                        : j == kThetaBins ? lnAlpha + 40
                                          : lnAlpha + 0.5 * std::log(u / (1 - u)));
    }
    // Probability per bin: the integral of 2 pi D cos sin dtheta = 2 pi D cos^2 sin^2 ds,
    // 4-point Gauss-Legendre on equal panels.
    auto density = [&](double s) {
        const double theta = std::atan(std::exp(s)), c = std::cos(theta), sn = std::sin(theta);
        return 2 * kPi * pdfGGXHalfVector(c, roughness) * sn * c * sn;
    };
    static const double gx[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                                 0.9602898564975363};
    static const double gw[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                                 0.1012285362903763};
    std::vector<double> probability;
    for (int j = 0; j < kThetaBins; ++j) {
        const int panels = j == 0 || j == kThetaBins - 1 ? 512 : 64;
        const double a = edges[size_t(j)], h = (edges[size_t(j) + 1] - a) / panels;
        double sum = 0;
        for (int p = 0; p < panels; ++p) {
            const double mid = a + (p + 0.5) * h, half = 0.5 * h;
            for (int k = 0; k < 4; ++k)
                sum += gw[k] * half * (density(mid - half * gx[k]) + density(mid + half * gx[k]));
        }
        probability.push_back(sum);
    }
    const dvec3 axis = std::abs(N.x) < 0.6 ? dvec3(1, 0, 0) : dvec3(0, 1, 0);
    const dvec3 T = glm::normalize(axis - N * glm::dot(N, axis)), B = glm::cross(N, T);
    ChiSquareTest t;
    std::vector<double> observed(size_t(kThetaBins) * kPhiBins, 0);
    for (const dvec3& H : samples) {
        const double cosTheta = glm::dot(N, H);
        if (!std::isfinite(H.x + H.y + H.z) || std::abs(glm::length(H) - 1) > 1e-3 ||
            cosTheta <= 0) {
            ++t.invalid;
            continue;
        }
        ++t.valid;
        const double s = std::log(glm::length(glm::cross(N, H)) / cosTheta);
        const int tb =
            std::clamp(int(std::upper_bound(edges.begin(), edges.end(), s) - edges.begin()) - 1, 0,
                       kThetaBins - 1);
        double phi = std::atan2(glm::dot(H, B), glm::dot(H, T));
        if (phi < 0) phi += 2 * kPi;
        const int pb = std::min(int(phi / (2 * kPi) * kPhiBins), kPhiBins - 1);
        observed[size_t(tb * kPhiBins + pb)] += 1;
    }
    for (int j = 0; j < kThetaBins; ++j)
        for (int k = 0; k < kPhiBins; ++k) {
            const double e = probability[size_t(j)] / kPhiBins * t.valid;
            const double o = observed[size_t(j * kPhiBins + k)];
            t.chi2 += e > 0 ? (o - e) * (o - e) / e : 0;
        }
    t.dof = kThetaBins * kPhiBins - 1;
    t.pValue = t.valid > 0 ? chiSquareTail(t.chi2, t.dof) : 0;
    return t;
}

}  // namespace pbrlab::ref
