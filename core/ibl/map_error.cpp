#include "ibl/map_error.h"

#include <chrono>
#include <cmath>
#include <mutex>

#include "pbrlab/cube_sampler.h"
#include "util/parallel.h"

namespace pbrlab {

double radianceError(const glm::dvec3& value, const glm::dvec3& reference, double floor) {
    const glm::dvec3 d = glm::abs(value - reference);
    const double grey = (reference.x + reference.y + reference.z) / 3.0;
    return std::max({d.x, d.y, d.z}) / std::max(grey, floor);
}

double lutError(const glm::dvec2& value, const glm::dvec2& reference) {
    const glm::dvec2 d = glm::abs(value - reference);
    return std::max(d.x, d.y);
}

const IblErrorSample& IblErrorSample::standard() {
    static const IblErrorSample sample = [] {
        constexpr int kDirections = 128, kLutPoints = 128;
        IblErrorSample s;
        // Spherical Fibonacci: equal-area rows in z, the golden angle between neighbours.
        const double goldenAngle = ref::kPi * (3.0 - std::sqrt(5.0));
        for (int i = 0; i < kDirections; ++i) {
            const double z = 1.0 - 2.0 * (i + 0.5) / kDirections;
            const double r = std::sqrt(1.0 - z * z), phi = goldenAngle * i;
            s.directions.emplace_back(r * std::cos(phi), z, r * std::sin(phi));
        }
        // A Hammersley set (k / n, radical inverse) stretched by n / (n - 1) to reach both
        // ends of each axis: N.V = 0 and 1, roughness 0 and 1 are where small LUTs are least
        // accurate.
        const double stretch = double(kLutPoints) / (kLutPoints - 1);
        for (int i = 0; i < kLutPoints; ++i) {
            const glm::dvec2 h = ref::hammersley(std::uint32_t(i), kLutPoints);
            s.lutPoints.emplace_back(h.x * stretch, h.y * stretch);
        }
        return s;
    }();
    return sample;
}

IblTruth::IblTruth(const Image& equirect, const IblErrorSample& sample)
    : sample_(sample), environment_(equirect), sums_(equirect) {
    const glm::dvec3 mean = sums_.meanRadiance();
    floor_ = 0.01 * (mean.x + mean.y + mean.z) / 3.0;
    irradiance_.resize(sample_.directions.size());
    parallelFor(irradiance_.size(),
                [&](size_t i) { irradiance_[i] = sums_.irradiance(sample_.directions[i]); });
}

const std::vector<glm::dvec3>& IblTruth::prefilter(double roughness) {
    auto it = prefilter_.find(roughness);
    if (it != prefilter_.end()) return it->second;
    std::vector<glm::dvec3> values(sample_.directions.size());
    parallelFor(values.size(), [&](size_t i) {
        const glm::dvec3& R = sample_.directions[i];
        // A lobe narrower than a texel: the map should hold the radiance itself, as the GPU
        // reads it (bilinear between texel centres).
        values[i] = roughness == 0.0 ? environment_.radiance(R) : sums_.prefilter(R, roughness);
    });
    return prefilter_.emplace(roughness, std::move(values)).first->second;
}

void IblTruth::prepare(const IblSettings& settings) {
    for (int mip = 0; mip < settings.prefilterMips; ++mip)
        prefilter(settings.prefilterMips > 1 ? double(mip) / (settings.prefilterMips - 1) : 0.0);
    lut(sample_);
}

const std::vector<glm::dvec2>& IblTruth::lut(const IblErrorSample& sample) {
    // The same for every environment: computed once per process (~0.6 ms a point).
    static std::mutex mutex;
    static std::map<const IblErrorSample*, std::vector<glm::dvec2>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(&sample);
    if (it != cache.end()) return it->second;
    std::vector<glm::dvec2> values(sample.lutPoints.size());
    parallelFor(values.size(), [&](size_t i) {
        values[i] = ref::brdfLutExact(sample.lutPoints[i].x, sample.lutPoints[i].y);
    });
    return cache.emplace(&sample, std::move(values)).first->second;
}

namespace {

void add(MapError& e, double error) {
    e.mean += error;
    e.max = std::max(e.max, error);
    ++e.samples;
}

void finish(MapError& e) {
    if (e.samples) e.mean /= e.samples;
}

}  // namespace

IblErrors measureIblErrors(IblPrecompute& precompute, const IblMaps& maps, IblTruth& truth) {
    const auto start = std::chrono::steady_clock::now();
    const IblErrorSample& sample = truth.sample();
    const IblSettings& s = maps.settings;
    IblErrors errors;
    {
        const auto values = precompute.sampleCube(maps.irradiance.id(), 0.0f, sample.directions);
        for (size_t i = 0; i < values.size(); ++i)
            add(errors.irradiance, radianceError(values[i], truth.irradiance()[i], truth.floor()));
        finish(errors.irradiance);
    }
    for (int mip = 0; mip < s.prefilterMips; ++mip) {
        const double roughness = s.prefilterMips > 1 ? double(mip) / (s.prefilterMips - 1) : 0.0;
        const auto values =
            precompute.sampleCube(maps.prefilter.id(), float(mip), sample.directions);
        const auto& reference = truth.prefilter(roughness);
        MapError e;
        for (size_t i = 0; i < values.size(); ++i) {
            const double error = radianceError(values[i], reference[i], truth.floor());
            add(e, error);
            add(errors.prefilter, error);
        }
        finish(e);
        errors.prefilterMips.push_back(e);
    }
    finish(errors.prefilter);
    {
        const Image lut = IblPrecompute::readLut(maps);
        const auto& reference = IblTruth::lut(sample);
        for (size_t i = 0; i < reference.size(); ++i) {
            const glm::dvec4 v = sampleTexture(lut, sample.lutPoints[i]);
            add(errors.lut, lutError({v.x, v.y}, reference[i]));
        }
        finish(errors.lut);
    }
    errors.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return errors;
}

}  // namespace pbrlab
