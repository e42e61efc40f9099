// The views of the lab picture: four images, a comparison, and the term views (term_views.h).
#pragma once

#include <string>
#include <vector>

#include "pbrlab/module.h"

namespace pbrlab {

enum class View {
    Student,     // the student's function (the solution's until their file has compiled)
    Solution,    // the reference solution, rendered on the GPU
    Reference,   // the CPU reference (the middle of its pass band)
    Difference,  // |student - reference|, false colour
    Split,       // student left, reference right, at GuiState::split
    Term,        // one term of the BRDF or its inputs: GuiState::term indexes Lab::termViews()
};

// The name --view and the view chooser use ("student", ..., or the name of terms[term]).
std::string viewName(View view, int term, const std::vector<TermView>& terms = {});

// Parses a --view name into the view and, for a term, its index; throws pbrlab::Error
// listing the known names.
void parseView(const std::string& name, const std::vector<TermView>& terms, View& view, int& term);

// The four image views and the comparison, in the chooser's order (the terms follow).
constexpr View kImageViews[] = {View::Student, View::Solution, View::Reference, View::Difference,
                                View::Split};

// Views that show the student's picture (or say why they cannot).
inline bool showsStudent(View view) {
    return view == View::Student || view == View::Difference || view == View::Split;
}

}  // namespace pbrlab
