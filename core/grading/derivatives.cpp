// Whether a check drawn as a picture failed because of screen-space derivatives
// (step_grader.h): the same inputs, each drawn alone, pass.

#include "grading/step_grader.h"

namespace pbrlab::step_grading {

std::string derivativesCause(int outsideAlone, int comparedAlone) {
    return "depends on screen derivatives: right where each pixel is drawn alone (" +
           std::to_string(outsideAlone) + " of " + std::to_string(comparedAlone) +
           " outside the band), wrong in the picture, where its neighbours are drawn beside it: "
           "an implicit-LOD texture(), dFdx, dFdy or fwidth in the function?";
}

std::string StepGrader::derivativesCauseOf(const ValuesRun& run) {
    if (!run.fromScene) return "";
    stage(run.report.name + ": the pixels drawn alone");
    RenderRequest request{&m_,           &run.params, &run.scene, source_,
                          &run.surfaces, run.width,   run.height};
    request.seamlessCubes = false;
    request.isolatePoints = true;
    const Image alone = renderer_.render(request).value;
    const Comparison c = compareWithBand(alone, run.surfaces, run.band, d_.components,
                                         d_.nonNegative, run.outlierFraction);
    return c.passes(d_.nonNegative, run.outlierFraction) ? derivativesCause(c.outside, c.compared)
                                                         : "";
}

}  // namespace pbrlab::step_grading
