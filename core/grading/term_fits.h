// Feedback that names a missing or extra term (docs/grading.md, "Feedback: the missing or
// extra term"). A step declares the named parts of its formula (ModuleDesc::namedTerms): its
// value recomputed in double with one part at another exponent. A term missing is its exponent
// 0, a term applied twice its exponent doubled, an input at a wrong power (1/d^3, gamma 3,
// alpha = roughness^4) the exponent that fits. Each candidate is measured on the failed
// check's points: the share of points where it is within twice the band of the student's
// value, over all points and over the points the reference does not explain. The one that
// explains them is named, only when no other candidate explains them as well.
#pragma once

#include <string>

#include "grading/error_patterns.h"

namespace pbrlab {

// "Your value is the reference divided by G: is the geometry term missing?", or "" when no
// term explains the error, or more than one does. Needs in.context for the steps that read
// the scene's lights or the environment (reflectance, tonemap, IBL steps).
std::string nameTerm(const FeedbackInputs& in);

}  // namespace pbrlab
