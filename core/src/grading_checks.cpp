// The checks of gradeStep that are not values (step_grader.h): the contract (what a step may
// read), the module's invariants and the extreme-input sweep.

#include "pbrlab/contract.h"
#include "stability.h"
#include "step_grader.h"

namespace pbrlab::step_grading {

// No step may read what its own or a later step's reference solution computed (the
// host precomputes those maps with the reference solutions).
void StepGrader::checkSamplers(const Program& program) {
    const std::vector<std::string> forbidden = LabRenderer::forbiddenSamplers(d_, program);
    CheckReport c;
    c.name = "reads only the inputs this step may read";
    c.kind = "contract";
    c.category = "contract";
    c.passed = forbidden.empty();
    if (forbidden.empty()) {
        c.detail = "no map computed by this step's or a later step's reference solution";
    } else {
        for (const std::string& f : forbidden) {
            const ContractStep* step = findProvider(f);
            c.detail += (c.detail.empty() ? "" : "; ") + f +
                        (step ? " is computed by the reference solution of step " +
                                    std::to_string(step->step) + " (" + step->id + ")"
                              : " is not an input of this step");
        }
        c.detail +=
            ": your function may not read it here (it reads black); compute the "
            "value from uEnvironment instead";
    }
    record(c);
}

void StepGrader::gradeInvariants(const Scene& scene) {
    if (!d_.invariants) return;
    stage("invariants");
    Evaluator evaluator;
    evaluator.run = [&](const std::vector<Surface>& surfaces, const std::string& view,
                        const std::vector<std::string>& set) {
        // Rows of kRowWidth points; a copy only when the last row needs padding (the
        // chi-square test's 131072 samples do not).
        const bool whole = !surfaces.empty() && surfaces.size() % kRowWidth == 0;
        const Grid g = whole ? Grid() : grid(surfaces);
        const ParamValues params = withSets(d_, set);
        RenderRequest request{&m_,
                              &params,
                              &scene,
                              source_,
                              whole ? &surfaces : &g.surfaces,
                              kRowWidth,
                              whole ? int(surfaces.size() / kRowWidth) : g.height};
        request.seamlessCubes = false;
        request.isolatePoints = true;
        request.view = view;
        return pointValues(renderer_.render(request).value, surfaces.size());
    };
    for (const InvariantResult& inv : d_.invariants(evaluator)) {
        CheckReport c;
        c.name = inv.name;
        c.kind = "invariant";
        c.category = "invariants";
        c.measured = inv.measured;
        c.expected = inv.expected;
        c.passed = inv.holds;
        c.detail = inv.name + " = " + number(inv.measured) + ", expected " + inv.expected;
        if (!inv.holds && !inv.hint.empty()) c.detail += " (" + inv.hint + ")";
        record(c);
    }
}

void StepGrader::gradeRobustness(const Scene& scene) {
    stage("robustness");
    const StabilityResult st = stabilitySweep(renderer_, m_, scene, source_);
    CheckReport c;
    c.name = "robustness on extreme inputs";
    c.kind = "robustness";
    c.category = "robustness";
    c.deducted = false;
    c.points = st.gpu.compared;
    c.nan = st.gpu.nanCount;
    c.inf = st.gpu.infCount;
    c.negative = d_.nonNegative ? st.gpu.negativeCount : 0;
    c.passed = c.nan + c.inf + c.negative == 0;
    c.worstAt = st.firstProblem;
    c.detail = std::to_string(c.points) + " extreme inputs: " + std::to_string(c.nan) + " NaN, " +
               std::to_string(c.inf) + " Inf, " + std::to_string(c.negative) + " negative" +
               (st.firstProblem.empty() ? "" : "; first at " + st.firstProblem);
    record(c);
}

}  // namespace pbrlab::step_grading
