// Feedback that names what the student's function computes when it is the reference on other
// inputs, or a simple curve of one input (docs/grading.md, "Feedback: inputs used in another's
// place, and curves"). General: the transformations are those of the surface's fields and of
// the step's inputs (ModuleDesc::inputAxes, or the generic ones), never a list of mistakes.
//   nameSubstitution: the reference evaluated with one input transformed: a direction negated
//     (-L, with the scene's lights mirrored through the point), two directions or two inputs of
//     the same range swapped, an input squared, square-rooted or complemented (1 - x), a sign
//     (tangent.w) flipped, a texel stored in [0, 1] read without its remap to [-1, 1].
//   nameLength: a direction of the reference's, at another length (a normalize missing).
//   nameCurve: the value as a simple function of one input (a + b x, a x^p, a clamp(x)^p,
//     1 / (a + b x + c x^2)), alone or times a colour input (the light's colour x a falloff).
// Each is named only when it explains the student's values (within twice the band) at 95% of
// the failed check's points, 90% of the wrong ones, and no other candidate with other values
// does as well.
#pragma once

#include <string>

#include "grading/error_patterns.h"

namespace pbrlab {

std::string nameSubstitution(const FeedbackInputs& in);
std::string nameLength(const FeedbackInputs& in);
std::string nameCurve(const FeedbackInputs& in);

}  // namespace pbrlab
