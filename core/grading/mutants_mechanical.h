// Mechanical mutants of a reference solution (docs/grading.md, "Mutation score"): each is the
// solution file with one small, typical change: an operator swapped, a constant scaled, PI
// removed, a max/clamp or a condition dropped, arguments or components swapped, a square
// added or removed, a normalize or sqrt removed, a sample count fixed, a term dropped. Graded
// exactly as submissions are, they measure what the grader lets through.
#pragma once

#include <string>
#include <vector>

namespace pbrlab {

// Where a semantic mutant's change of meaning shows beyond the inputs grading uses
// (grading/mutants_semantic.h): a proof that it is equivalent must hold there too. Empty for
// mechanical mutants.
struct Witness {
    std::vector<double> environmentScales;  // the step's environment, its radiance times these
    std::vector<int> counts;                // the step's count parameters at these
    // Other maps the host builds (IblSettings fields): {"prefilterMips", 6}.
    std::vector<std::pair<std::string, int>> ibl;
    bool otherLights = false;  // the scene with another light count, other positions and colours
    // Where it differs that no step's view can show ("i >= 2^16"): a survivor is not
    // equivalent, by construction.
    std::string byConstruction;
    bool empty() const {
        return environmentScales.empty() && counts.empty() && ibl.empty() && !otherLights &&
               byConstruction.empty();
    }
};

struct Mutant {
    std::string family;       // "operator", "constant", "pi", "guard", ...
    std::string description;  // where and what, for instructors: "line 9: `*` -> `/`"
    // The change in a few tokens, as a student can read it: "`r * r * 8.0` for `r * r / 8.0`".
    std::string change;
    int line = 0;      // in the solution file
    std::string text;  // the whole mutated file
    Witness witness;   // semantic mutants only
};

// The families, in the order they are generated, with what each means.
struct MutantFamily {
    const char* name;
    const char* meaning;
    const char* mistake;  // the mistake it stands for, as feedback says it
};
const std::vector<MutantFamily>& mutantFamilies();

// A GLSL file as tokens, every character in one (spaces and comments too): shared by the
// mechanical and the semantic generators (grading/mutants_semantic.h).
struct GlslToken {
    enum Kind { Space, Comment, Preprocessor, Identifier, Number, Operator } kind;
    std::string text;
    int line;       // 1-based, where the token starts
    size_t offset;  // in the file
};
std::vector<GlslToken> tokenizeGlsl(const std::string& source);

// Characters [begin, end) of a file replaced by `text`.
struct TextEdit {
    size_t begin, end;
    std::string text;
};
// The mutant the edits (non-overlapping, at least one) make of `source`, with its line,
// description and change written as generateMutants writes them.
Mutant mutantFromEdits(const std::string& family, const std::string& source,
                       std::vector<TextEdit> edits);

// Every mutant of a solution file. Comments and preprocessor lines are left alone; mutants
// whose text equals the original (or another mutant's) are dropped.
std::vector<Mutant> generateMutants(const std::string& solution);

}  // namespace pbrlab
