// Mechanical mutants of a reference solution (docs/grading.md, "Mutation score"): each is the
// solution file with one small, typical change: an operator swapped, a constant scaled, PI
// removed, a max/clamp or a condition dropped, arguments or components swapped, a square
// added or removed, a normalize or sqrt removed, a sample count fixed, a term dropped. Graded
// exactly as submissions are, they measure what the grader lets through.
#pragma once

#include <string>
#include <vector>

namespace pbrlab {

struct Mutant {
    std::string family;       // "operator", "constant", "pi", "guard", ...
    std::string description;  // where and what, for instructors: "line 9: `*` -> `/`"
    // The change in a few tokens, as a student can read it: "`r * r * 8.0` for `r * r / 8.0`".
    std::string change;
    int line = 0;      // in the solution file
    std::string text;  // the whole mutated file
};

// The families, in the order they are generated, with what each means.
struct MutantFamily {
    const char* name;
    const char* meaning;
    const char* mistake;  // the mistake it stands for, as feedback says it
};
const std::vector<MutantFamily>& mutantFamilies();

// Every mutant of a solution file. Comments and preprocessor lines are left alone; mutants
// whose text equals the original (or another mutant's) are dropped.
std::vector<Mutant> generateMutants(const std::string& solution);

}  // namespace pbrlab
