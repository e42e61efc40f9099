// Every loop of a student's file bounded (ShaderPreprocessor::expand): a loop that never ends
// must fail the same way on every GPU. Without a guard the verdict is the compiler's: Mesa
// deletes a loop with no side effect and the function passes, while WebGL's compiler keeps it
// and the page hangs.
//
// Each loop's condition is wrapped, `while (c)` -> `while (pbrlab_loop(K, (c)))`, and the same
// for a for's condition (an empty one: `pbrlab_loop(K, true)`) and a do-while's; K names the
// loop (LoopSite). pbrlab_loop counts the iterations of one invocation in a global (GLSL globals
// are per invocation), so nested loops share one budget instead of multiplying theirs; once the
// budget is spent it returns false, every loop of the students' files ends at its next test, and
// the entry point writes NaN in place of the value (shaders/view_main.frag): a cut never passes
// for a value. The diagnosis build (kTraceNonFinite) also notes which loop was cut: the one
// whose current run had the most iterations (an endless outer loop with a short inner one names
// the outer, an endless inner one the inner).
#pragma once

#include <string>
#include <vector>

namespace pbrlab {

// A loop of a student's file: the file as the student names it (its path in the submission
// folder) and the line of its `for` or `while`.
struct LoopSite {
    std::string file;
    int line = 0;
};

// The budget's uniform (int), set by whoever draws a program that links a student's part.
inline constexpr const char* kLoopBudgetUniform = "pbrlab_loopBudget";
// Defined in such a program, so that its entry point can test pbrlab_loopCut.
inline constexpr const char* kLoopGuardMacro = "PBRLAB_LOOP_GUARD";

// What the host lets one invocation of a program loop over, from which its budget follows.
struct LoopLimits {
    size_t lightSlots = 0;       // the light arrays' length (PBRLAB_LIGHT_SLOTS)
    int environmentSize = 0;     // uEnvironment's side where the program may read it, else 0
    std::vector<double> counts;  // counts a loop may run over (a sample count, a point count)
};

// The most iterations the loops of the students' files may run in one invocation: what a
// correct function needs at the counts the host allows, and no more, because a loop that is
// cut costs the whole budget per pixel (in the browser's software rasteriser too); and below
// what llvmpipe runs (65535 iterations per invocation, every loop together), so that the guard,
// not llvmpipe's silent stop, ends a runaway loop on the desktop as in the page.
int loopBudget(const LoopLimits& limits);

// `text` (a student's file, named `name` in messages) with every loop's condition wrapped;
// each loop is appended to `sites` (K = its index + 1), as file `file`. Throws ShaderError at the
// student's line for a loop the guard cannot wrap: a condition that is a declaration, a `for` or
// `while` without its parenthesis, a #define of for, while or do.
std::string guardLoops(const std::string& text, const std::string& name, const std::string& file,
                       std::vector<LoopSite>& sites);

// The guard's GLSL, before the first student's part: the budget, the counters and pbrlab_loop
// (in the diagnosis build only its prototype; loopGuardDiagnosis defines it after every part,
// when the number of loops is known).
std::string loopGuardPrelude(bool diagnosis);
std::string loopGuardDiagnosis(size_t sites);
// The guard's names, which no student's file may write.
const std::vector<std::string>& loopGuardNames();

}  // namespace pbrlab
