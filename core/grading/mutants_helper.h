// Mutants that call, instead of computing, what a step's file can see (docs/grading.md,
// "Nothing reachable computes the step"). A step's program links the contract functions of its
// own and the earlier steps, the helpers those steps introduce, common.glsl's utilities and the
// host's code after the student's part; a student's file can name some of them. None of them
// may compute the step: each mutant here returns one of them, called with the step's own
// arguments, and must fail grading.
#pragma once

#include <string>
#include <vector>

#include "grading/mutants_mechanical.h"
#include "render/renderer.h"
#include "steps/plugin_host.h"

namespace pbrlab {

// A function declared or defined in a step's program outside the student's part.
struct VisibleFunction {
    std::string returnType, name;
    std::vector<std::string> parameterTypes, parameterNames;  // names "" in a bare prototype
    // Defined after the student's part: a student's file can call it only through a prototype
    // of its own, and only when every type in its signature is a built-in one.
    bool afterStudent = false;
    std::string source;             // the file or generated part that declares it first
    std::string signature() const;  // "vec3 name(float, vec3)"
};

// What a student's file of a step can see of the host's code.
struct VisibleNames {
    std::vector<VisibleFunction> functions;  // in program order, each once
    std::vector<std::string> macros;         // defined before the student's part
};

// Every function and macro of the step's view program (viewRecipe as grading compiles it: the
// probe, one light), parsed from the expanded program source before and after the student's
// part (the reference solution stands in the student's place). Prototypes and definitions
// alike; the student's part itself is left out.
VisibleNames namesVisibleToStudent(LabRenderer& renderer, const LoadedModule& module);

// For every visible function whose return type is the step's (the step's own function left
// out), a student file that returns it called with the step's arguments: mapped by name, then
// by type in order, and 0 or 1 of the type where the step has no argument left; that call
// first, then calls with one argument changed to another candidate (0, 1, another argument of
// the step of that type), 6 calls at most per function. A function defined after the student's
// part gets the prototype a student would write. Each must fail grading (a refusal, a compile
// error or a failed check): one that passed would be code reachable from a student's file that
// computes the step. Family "helper"; `line` is 0 (the whole file is the mutant's).
std::vector<Mutant> helperCallMutants(LabRenderer& renderer, const LoadedModule& module);

}  // namespace pbrlab
