// What a student's GLSL says by its text alone, before it runs: read by the preprocessor (a
// loop that never ends is reported before the compiler deletes it) and by the grader's
// feedback (why a function returns 0 everywhere).
#pragma once

#include <string>

namespace pbrlab {

// Why a function that returns 0 for every input does, read from its code: an endless loop
// (`while (true)`, `for (;;)` with no break or return: GLSL compilers delete a loop with no
// way out, and the function then returns an undefined value, 0 on Mesa), or the kit's stub
// left in place. "" when the code says neither.
std::string whyAlwaysZero(const std::string& code);

}  // namespace pbrlab
