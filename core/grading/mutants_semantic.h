// Semantic mutants of a reference solution (docs/grading.md, "Semantic mutants"): changes of
// meaning that a mechanical edit of one token does not make, each applied in every place it
// fits: a nonlinearity on every texture read, a cap on every count, fewer bits in every bit
// operation, every host-provided value replaced by the value the host gives it today. Each
// carries its witness: the inputs, beyond the graded ones, where its change shows, on which a
// proof of equivalence must also hold (course/mutation_score.cpp).
//
// Unlike generateMutants(solution), the generator needs the step's descriptor and the host
// (the values it binds today: the light count, uPrefilterMaxLod, texture sizes), so it runs
// where a GL context is current (`pbrlab mutants` calls it in a child process).
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "grading/mutants_mechanical.h"
#include "steps/paths.h"
#include "steps/plugin_host.h"

namespace pbrlab {

class LabRenderer;

// What a family reads to make its mutants.
struct SemanticContext {
    LabRenderer& renderer;
    const LoadedModule& module;
    const DataPaths& paths;
    const std::string& solution;  // the reference solution's text
};

struct SemanticFamily {
    const char* name;
    const char* meaning;
    const char* mistake;  // the mistake's class, as feedback says it
    // Null: a survivor is equivalent when its values are the reference solution's on the
    // graded inputs and on its witness. Else why a survivor never is (the helper family:
    // code that computes the step has the same values by construction).
    const char* neverEquivalent;
    std::function<std::vector<Mutant>(const SemanticContext&)> generate;
};

// The families, in the order they are generated. One line each: a family of another file
// (grading/mutants_helper.h) joins with its entry here.
const std::vector<SemanticFamily>& semanticFamilies();
const SemanticFamily* semanticFamily(const std::string& name);

// Every semantic mutant of the step's reference solution; texts unique, none equal to the
// solution.
std::vector<Mutant> generateSemanticMutants(const SemanticContext& context);

// Mutants through a pipe (the generator runs in a child process).
nlohmann::json mutantsToJson(const std::vector<Mutant>& mutants);
std::vector<Mutant> mutantsFromJson(const nlohmann::json& j);

}  // namespace pbrlab
