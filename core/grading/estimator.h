// What the estimator checks share (step_grader.h): the band around converged integrals, the
// values check against it, the points they are judged on, and how a count is set and named.
// Each check has its file:
//   estimator_band.cpp         the order of the checks; converged integrals, the band, finite
//                              values, the scale, the quality report
//   estimator_convergence.cpp  the band at the graded counts, the error's fall, the bias test,
//                              the noise budget
//   estimator_counts.cpp       counts above the graded ones; the environment at another size
//   sun.cpp                    an environment with a real sun
//   estimator_picture.cpp      the lab's picture, with screen derivatives
#pragma once

#include "grading/step_grader.h"

namespace pbrlab::step_grading {

// The noise a value at n samples has around the converged value: the estimator's own,
// sigma / sqrt(n), and the converged value's own error (independent of it).
glm::dvec3 noiseAt(const Estimate& t, int n);

// The band around the converged integrals at n samples (0: no noise term), for the covered
// points: |v - mean| <= systematic + sigmas * sqrt(sigma^2 / n + error^2).
Band convergedBand(const ModuleDesc& d, const std::vector<Surface>& surfaces,
                   const std::vector<Estimate>& truth, int n, const Tolerance& systematic);

// A values check against the converged integral (`value` compared with `band` here), as
// feedback keeps it: the estimator's own category (not the probe's or the random inputs' band
// of the reference) and its band's rule.
ValuesRun estimatorRun(const std::string& name, const ModuleDesc& d,
                       const std::vector<Surface>& surfaces, Image value, Band band,
                       const Scene& scene, const ParamValues& params, const Probe* probe, int width,
                       int height, const Tolerance* systematicHere = nullptr);

// NaN, Inf and (for a non-negative step) negatives among the covered points: never excused,
// whatever the noise.
CheckReport finiteValues(const std::string& name, const ModuleDesc& d, const Image& value,
                         const std::vector<Surface>& surfaces, const std::string& points);

// The module's parameters with its sample count set to n.
ParamValues withSamples(const ModuleDesc& d, int n);

// The parameters a check at n samples renders with: the defaults at 0 (no count to set).
ParamValues paramsAt(const ModuleDesc& d, int n);

// " with samples = n" in a check's name ("" at 0: no count).
std::string atCount(const EstimatorSpec& e, int n);

// The addresses of `surfaces`, as convergedIntegrals takes its points.
std::vector<const Surface*> addresses(const std::vector<Surface>& surfaces);

// Points an estimator is judged on (the subsampled probe, the random inputs) with their
// converged integrals.
struct StepGrader::PointSet {
    std::string name;
    std::vector<Surface> surfaces;
    int width, height;
    const Probe* probe;
    std::vector<Estimate> truth;
    Image last;  // the values at the largest count
};

// The mean relative error of values against their converged integrals, over every component of
// the covered points added, as the error's fall measures it (infinite values left out).
struct StepGrader::RelativeError {
    double sum = 0;
    int count = 0;
    void add(const ModuleDesc& d, const Image& value, const std::vector<Surface>& surfaces,
             const std::vector<Estimate>& truth) {
        for (size_t i = 0; i < surfaces.size() && i < truth.size(); ++i) {
            if (!surfaces[i].covered) continue;
            for (int c = 0; c < d.components; ++c) {
                const double v = value.pixels[i * 4 + size_t(c)], t = truth[i].mean[c];
                if (!std::isfinite(v)) continue;
                sum += std::abs(v - t) / std::max(std::abs(t), d.estimator->systematic.absolute);
                ++count;
            }
        }
    }
    double mean() const { return count ? sum / count : 0.0; }
    // The mean relative error of one image's values.
    static double of(const ModuleDesc& d, const Image& value, const std::vector<Surface>& surfaces,
                     const std::vector<Estimate>& truth) {
        RelativeError error;
        error.add(d, value, surfaces, truth);
        return error.mean();
    }
};

}  // namespace pbrlab::step_grading
