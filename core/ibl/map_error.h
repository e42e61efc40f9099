// The error of the precomputed IBL maps against the CPU references in double precision, on a
// fixed deterministic sample (docs/ibl.md, "Error of the maps"): what `pbrlab precompute`
// prints next to each pass, what `pbrlab precompute --bench` compares and what
// `--error-budget` chooses by.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ibl/precompute.h"
#include "pbrlab/ibl_reference.h"

namespace pbrlab {

// One map's error over the sample: the mean and the largest of the per-point errors.
struct MapError {
    double mean = 0, max = 0;
    int samples = 0;
};

// The error metric, defined once. Radiance maps (irradiance stores E/pi, the prefiltered
// mips): the largest channel difference relative to the reference's grey level, which for
// these maps is the mean radiance around the point (cosine- or GGX-weighted), floored at 1%
// of the environment's mean radiance so that nearly black points do not divide by ~0.
double radianceError(const glm::dvec3& value, const glm::dvec3& reference, double floor);
// The LUT: the largest absolute difference of scale A and bias B (both in [0, 1]).
double lutError(const glm::dvec2& value, const glm::dvec2& reference);

// Where the maps are read: directions (a spherical Fibonacci set) for the cubes, and points
// (N.V, roughness) of the unit square (a Hammersley set, ends included) for the LUT. The maps
// are read as the renderer reads them (bilinear, seamless, the mip of each roughness), at
// points that do not depend on the maps' sizes: a sample at texel centres would hide the
// interpolation error of a small map.
struct IblErrorSample {
    std::vector<glm::dvec3> directions;
    std::vector<glm::dvec2> lutPoints;        // x = N.V, y = roughness
    static const IblErrorSample& standard();  // 128 directions, 128 LUT points
};

// The CPU truth at the sample for one environment, computed once and reused for every
// setting measured against it (hierarchical texel sums, ref::TexelSums).
class IblTruth {
public:
    explicit IblTruth(const Image& equirect,
                      const IblErrorSample& sample = IblErrorSample::standard());
    const IblErrorSample& sample() const { return sample_; }
    double floor() const { return floor_; }  // 1% of the mean radiance
    const std::vector<glm::dvec3>& irradiance() const { return irradiance_; }
    // The converged prefilter at `roughness` (roughness 0: the bilinear lookup), computed on
    // first use.
    const std::vector<glm::dvec3>& prefilter(double roughness);
    // brdfLutExact at the sample's LUT points (the same for every environment).
    static const std::vector<glm::dvec2>& lut(const IblErrorSample& sample);
    // Computes every value measureIblErrors reads for maps of these settings, so that it can
    // run in a thread of its own while the maps are built (nothing else may use this object
    // meanwhile).
    void prepare(const IblSettings& settings);

private:
    const IblErrorSample& sample_;
    ref::EquirectEnvironment environment_;
    ref::TexelSums sums_;
    double floor_ = 0;
    std::vector<glm::dvec3> irradiance_;
    std::map<double, std::vector<glm::dvec3>> prefilter_;
};

struct IblErrors {
    MapError irradiance, prefilter, lut;
    std::vector<MapError> prefilterMips;  // per mip; `prefilter` pools them
    double milliseconds = 0;              // the GPU read-back and the comparison
};

// Reads the maps at the sample (GPU, as the renderer samples them) and compares them with the
// truth. `maps` must be derived (irradiance, prefilter and LUT built).
IblErrors measureIblErrors(IblPrecompute& precompute, const IblMaps& maps, IblTruth& truth);

}  // namespace pbrlab
