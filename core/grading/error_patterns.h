// Feedback that names the mistake from the shape of the error (docs/grading.md): a constant
// factor, an offset, a power, a sign, a constant output, an error confined to one region of
// an input, an input the function ignores or depends on wrongly, a NaN traced to the call
// that made it; the named terms (term_fits.h) and the reference on other inputs and curves
// (input_fits.h). General patterns, not a list of known files; grading/failure_message.cpp
// adds the nearest typical mistake on top.
#pragma once

#include <string>
#include <vector>

#include "pbrlab/module.h"
#include "shader/preprocess.h"

namespace pbrlab {

struct FeedbackInputs {
    const ModuleDesc* module = nullptr;
    std::vector<Surface> surfaces;             // covered points of the failing check
    std::vector<glm::dvec3> values, expected;  // the student's and the reference's
    std::vector<glm::dvec3> slack;             // the band's half-width there
    // The student's function on other inputs, and the reference there: for the sensitivity
    // test (which input does the error follow?). Optional.
    std::function<std::vector<glm::dvec3>(const std::vector<Surface>&)> student;
    std::function<glm::dvec3(const Surface&)> reference;
    DomainFn domain;
    // The student's file, when there is one: a constant 0 is told apart from the kit's stub
    // (an endless loop the compiler removed, for one). Optional.
    std::string studentCode;
    // What the reference reads besides the surface (the scene's lights, the parameters, the
    // environment's maps): the named-term fits recompute the step with it (term_fits.h).
    // Optional.
    const ReferenceContext* context = nullptr;
    // Where the student's function made its first NaN or Inf at these points (the diagnosis
    // build, shader/preprocess.h): the site (traced call and line) most of them share, another
    // site that made one there too, at how many points, of how many traced; `confirmed`: with
    // what those calls made replaced by 0 the value is finite there (the NaN or Inf the student
    // sees is theirs). Optional.
    // `cut`: a loop of the student's files the guard ended there (shader/loop_guard.h), the
    // one most of the traced points name (line 0: none), at `cutPoints` of them, with the
    // budget of iterations it ran out of.
    struct NonFiniteOrigin {
        TraceSite site, other;
        int points = 0, traced = 0;
        bool confirmed = false;
        LoopSite cut;
        int cutPoints = 0, loopBudget = 0;
    };
    std::function<NonFiniteOrigin(const std::vector<Surface>&)> traceNonFinite;
};

// The inputs a step's errors are located and substituted by: its own (ModuleDesc::inputAxes)
// or, when it declares none, the generic ones (N.V, N.L, V.L, roughness, metallic, ao, the
// mean albedo, the light's distance, extra.x, extra.y, tangent.w). Kept for the program's life.
const std::vector<InputAxis>& inputAxes(const ModuleDesc& module);

// What the inputs at a point were, in the module's terms: the fields its domain (or probe)
// varies, and the cosines between the directions it reads ("N.V 0.42, roughness 0.05").
std::string describeInputs(const ModuleDesc& module, const Surface& s);

// One sentence (or two) saying what the error looks like, or "" when no pattern fits.
// `exact`: the pattern accounts for every point (a factor, an offset, a power, a constant
// output, swapped components, a term), not only where the error lies.
std::string classifyError(const FeedbackInputs& in, bool* exact = nullptr);

// What the student reads when the loop guard (shader/loop_guard.h) cut `loop` after `budget`
// iterations in one evaluation, at `cut` of `points` points: the file, the line, the likely
// cause first.
std::string loopCutMessage(const LoopSite& loop, int budget, int cut, int points);

// The constant that `ratio` is closest to among the usual suspects (pi, 1/pi, 2, 4, ...), as
// "pi/4", when it is within 1%; else "".
std::string nameConstant(double ratio);

// A mistake named by a pattern, without the figures measured on this student's function
// ("only where N.V < 0.74 (1536 of 1584 points there)" -> "only where N.V < # (# of # points
// there)"; names such as F0 kept): the shape of the error, the same for every student who
// makes it, so that a class report can count it.
std::string withoutFigures(const std::string& mistake);

}  // namespace pbrlab
