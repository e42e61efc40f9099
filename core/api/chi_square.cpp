// The chi-square tests of sampled directions (ibl_reference.h): the distribution a sampler
// draws against the density it claims.
#include <algorithm>
#include <cmath>
#include <functional>
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

namespace {

constexpr int kThetaBins = 16;

// Theta is binned by s = ln tan(theta): the lobe is a smooth bump around ln(alpha) at every
// roughness, and float directions keep their relative precision there. The edges are the
// quantiles of D (N.h) at this roughness, in closed form.
std::vector<double> thetaEdges(double roughness) {
    const double lnAlpha = std::log(std::max(roughness * roughness, kIblMinAlpha));
    std::vector<double> edges;
    for (int j = 0; j <= kThetaBins; ++j) {
        const double u = double(j) / kThetaBins;
        edges.push_back(j == 0            ? lnAlpha - 40
                        : j == kThetaBins ? lnAlpha + 40
                                          : lnAlpha + 0.5 * std::log(u / (1 - u)));
    }
    return edges;
}

int thetaBin(const std::vector<double>& edges, const dvec3& N, const dvec3& H) {
    const double s = std::log(glm::length(glm::cross(N, H)) / glm::dot(N, H));
    return std::clamp(int(std::upper_bound(edges.begin(), edges.end(), s) - edges.begin()) - 1, 0,
                      kThetaBins - 1);
}

// A unit vector of the sample's, or not one the density can have drawn.
bool validSample(const dvec3& N, const dvec3& H) {
    return std::isfinite(H.x + H.y + H.z) && std::abs(glm::length(H) - 1) <= 1e-3 &&
           glm::dot(N, H) > 0;
}

}  // namespace

ChiSquareTest ggxHalfVectorChiSquare(const std::vector<dvec3>& samples, const dvec3& Nin,
                                     double roughness) {
    constexpr int kPhiBins = 8;
    const dvec3 N = glm::normalize(Nin);
    const std::vector<double> edges = thetaEdges(roughness);
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
        if (!validSample(N, H)) {
            ++t.invalid;
            continue;
        }
        ++t.valid;
        const int tb = thetaBin(edges, N, H);
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

ChiSquareTest directionChiSquare(const std::vector<dvec3>& samples, const dvec3& Nin,
                                 const dvec3& Tin, double roughness,
                                 const std::function<double(const dvec3&)>& p) {
    constexpr int kPhiBins = 16, kGrid = 24;
    const dvec3 N = glm::normalize(Nin);
    const dvec3 T = glm::normalize(Tin - N * glm::dot(N, Tin)), B = glm::cross(N, T);
    const std::vector<double> edges = thetaEdges(roughness);
    const auto direction = [&](double theta, double phi) {
        return T * (std::sin(theta) * std::cos(phi)) + B * (std::sin(theta) * std::sin(phi)) +
               N * std::cos(theta);
    };
    // Each bin's probability: p sin(theta) dtheta dphi with dtheta = sin cos ds, midpoints on a
    // grid of the bin (16 times finer in s for the two unbounded outer bins).
    const double dphi = 2 * kPi / kPhiBins;
    std::vector<double> expected(size_t(kThetaBins) * kPhiBins, 0);
    double total = 0;
    for (int j = 0; j < kThetaBins; ++j) {
        const int ns = j == 0 || j == kThetaBins - 1 ? kGrid * 16 : kGrid;
        const double ds = (edges[size_t(j) + 1] - edges[size_t(j)]) / ns;
        for (int k = 0; k < kPhiBins; ++k) {
            double sum = 0;
            for (int a = 0; a < ns; ++a) {
                const double theta = std::atan(std::exp(edges[size_t(j)] + (a + 0.5) * ds));
                const double jacobian = std::sin(theta) * std::sin(theta) * std::cos(theta);
                for (int b = 0; b < kGrid; ++b)
                    sum += p(direction(theta, (k + (b + 0.5) / kGrid) * dphi)) * jacobian;
            }
            expected[size_t(j * kPhiBins + k)] = sum * ds * dphi / kGrid;
            total += expected[size_t(j * kPhiBins + k)];
        }
    }
    ChiSquareTest t;
    std::vector<double> observed(expected.size(), 0);
    for (const dvec3& H : samples) {
        if (!validSample(N, H) || !(p(H) > 0)) {
            ++t.invalid;
            continue;
        }
        ++t.valid;
        double phi = std::atan2(glm::dot(H, B), glm::dot(H, T));
        if (phi < 0) phi += 2 * kPi;
        const int pb = std::min(int(phi / dphi), kPhiBins - 1);
        observed[size_t(thetaBin(edges, N, H) * kPhiBins + pb)] += 1;
    }
    // The bins expecting fewer than 5 samples are pooled into one (the test's approximation
    // needs about 5 per cell); the probabilities are normalised by their sum.
    double pooledExpected = 0, pooledObserved = 0;
    int cells = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        const double e = expected[i] / total * t.valid;
        if (e < 5) {
            pooledExpected += e;
            pooledObserved += observed[i];
            continue;
        }
        t.chi2 += (observed[i] - e) * (observed[i] - e) / e;
        ++cells;
    }
    if (pooledExpected > 0) {
        t.chi2 +=
            (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
        ++cells;
    }
    t.dof = std::max(cells - 1, 1);
    t.pValue = t.valid > 0 ? chiSquareTail(t.chi2, t.dof) : 0;
    return t;
}

}  // namespace pbrlab::ref
