#include "views.h"

#include "util/error.h"

namespace pbrlab {

std::string viewName(View view, int term, const std::vector<TermView>& terms) {
    switch (view) {
        case View::Student:
            return "student";
        case View::Solution:
            return "solution";
        case View::Reference:
            return "reference";
        case View::Difference:
            return "difference";
        case View::Split:
            return "split";
        case View::Term:
            break;
    }
    return terms.at(size_t(term)).name;
}

void parseView(const std::string& name, const std::vector<TermView>& terms, View& view, int& term) {
    std::string known;
    for (View v : kImageViews) {
        if (viewName(v, 0) == name) {
            view = v;
            return;
        }
        known += (known.empty() ? "" : ", ") + viewName(v, 0);
    }
    for (size_t i = 0; i < terms.size(); ++i) {
        if (terms[i].name == name) {
            view = View::Term;
            term = int(i);
            return;
        }
        known += ", " + terms[i].name;
    }
    throw Error("--view " + name + ": unknown view; one of " + known);
}

}  // namespace pbrlab
