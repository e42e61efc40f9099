#include "views.h"

#include "pbrlab/error.h"
#include "term_views.h"

namespace pbrlab {

std::string viewName(View view, int term) {
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
    return kTermViews[size_t(term)].name;
}

void parseView(const std::string& name, View& view, int& term) {
    std::string known;
    for (View v : kImageViews) {
        if (viewName(v, 0) == name) {
            view = v;
            return;
        }
        known += (known.empty() ? "" : ", ") + viewName(v, 0);
    }
    for (size_t i = 0; i < kTermViews.size(); ++i) {
        if (kTermViews[i].name == name) {
            view = View::Term;
            term = int(i);
            return;
        }
        known += std::string(", ") + kTermViews[i].name;
    }
    throw Error("--view " + name + ": unknown view; one of " + known);
}

}  // namespace pbrlab
