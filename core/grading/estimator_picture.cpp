// An estimator in the lab's picture (estimator.h), where screen derivatives exist.

#include <algorithm>
#include <cmath>

#include "grading/estimator.h"

namespace pbrlab::step_grading {

// The step in the picture the lab draws of it: the module's scene drawn whole, so that each
// pixel's neighbours are its neighbours in the picture and screen-space derivatives (an
// implicit-LOD texture(), dFdx, fwidth) are those of the GUI's picture, not the zero of a
// point drawn alone. Judged at up to `picturePixels` of its pixels (a seeded choice: the
// converged integral costs thousands of samples a pixel) against the converged integral
// there, at the largest graded count, with the band and the bias test of the other point
// sets, on the environment where every correct estimator converges. Where it fails, the same
// pixels drawn alone tell whether the error comes from the derivatives.
void StepGrader::gradePicture(const Scene& scene) {
    const EstimatorSpec& e = *d_.estimator;
    Scene judged = scene;
    const bool environment = d_.needs & NeedsEnvironment;
    if (environment) judged.environment = e.environment;
    const std::string on = environment ? " (" + judged.environment + ")" : "";
    const int n = e.sampleCounts.empty() ? 0 : e.sampleCounts.back();
    const ParamValues params = paramsAt(d_, n);
    const int side = settings_.size;
    const std::string name = "picture: scene " + scene.file.stem().string() + atCount(e, n) + on;
    stage(name);
    RenderRequest request{&m_, &params, &judged, source_, nullptr, side, side};
    request.seamlessCubes = false;
    request.readSurfaces = true;
    request.cacheGBuffer = true;
    RenderResult r = renderer_.render(request);
    std::vector<size_t> covered;
    for (size_t i = 0; i < r.surfaces.size(); ++i)
        if (r.surfaces[i].covered) covered.push_back(i);
    DomainRandom pick(settings_.seed * 0x2545F4914F6CDD1Dull + 11);
    for (size_t k = 0; k + 1 < covered.size(); ++k)  // Fisher-Yates
        std::swap(covered[k], covered[k + size_t(pick.uniform() * double(covered.size() - k))]);
    covered.resize(std::min(covered.size(), size_t(e.picturePixels)));
    std::vector<Surface> pixels(r.surfaces.size());  // uncovered but the chosen
    for (size_t i : covered) pixels[i] = r.surfaces[i];
    const std::vector<const Surface*> points = addresses(pixels);
    const ParamValues defaults(d_.params);
    const ReferenceContext context = referenceContext(renderer_, d_, judged, defaults, kGradingIbl);
    stage("converged integrals: " + name);
    const std::vector<Estimate> truth = convergedIntegrals(points, judged, context, e.truthSamples);
    stage(name);
    if (e.scaleTolerance > 0) rescale(name, r.value, pixels, truth);
    Band band = convergedBand(d_, pixels, truth, n, e.systematic);
    ValuesRun run =
        estimatorRun(name, d_, pixels, r.value, band, judged, params, nullptr, side, side);
    run.fromScene = true;
    run.tier = ValuesRun::Tier::LabUse;
    if (!run.report.passed) {
        // The same pixels, each drawn alone (zero derivatives).
        const Grid alone = grid(std::vector<Surface>(pixels));
        Image value = renderPoints(params, judged, alone.surfaces, alone.width, alone.height).value;
        if (e.scaleTolerance > 0) rescale(name + ", pixels drawn alone", value, pixels, truth);
        const Comparison a = compareWithBand(value, pixels, band, d_.components, d_.nonNegative,
                                             e.systematic.outlierFraction);
        if (a.passes(d_.nonNegative, e.systematic.outlierFraction)) {
            run.cause = derivativesCause(a.outside, a.compared);
            run.report.detail = run.cause + "; " + run.report.detail;
        }
    }
    keep(std::move(run));
    if (n > 0) {
        PointSet set{"pixels of the picture", pixels, side, side, nullptr, truth, r.value};
        biasTest({set}, n, on + " in the picture");
    }
}

}  // namespace pbrlab::step_grading
