// Named terms (ModuleDesc::namedTerms) from one model of the step. The model is the step's
// value written once more in double with every part raised to an exponent of its own, the
// exponents being the fields of a struct whose defaults are the reference's:
//
//     struct Knobs { double square = 2, wrap = 1; };
//     d.namedTerms = namedTerms<Knobs>(
//         [](const Surface& s, const ReferenceContext&, const Knobs& k) { ... },
//         {exponent<Knobs>("^2", "the square", &Knobs::square, 2, 0.5, 4, format),
//          factor<Knobs>("0.5", "the wrap 0.5", {&Knobs::wrap})});
//
// A term sets one or more of the fields (G sets both G1 exponents) to the exponent tried.
// A struct may derive from a shared one (pbrlab/shading_terms.h): the shared terms then apply.
#pragma once

#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "pbrlab/module.h"

namespace pbrlab {

// A named term whose exponents are fields of Knobs (the NamedTerm fields, with `knobs` the
// fields it sets).
template <class Knobs>
struct KnobbedTerm {
    NamedTerm::Kind kind = NamedTerm::Kind::Factor;
    std::string symbol, name;
    std::vector<double Knobs::*> knobs;
    double reference = 1;
    std::vector<double> tries;
    double lo = 0, hi = 0;
    std::function<std::string(double)> format;
    bool whole = false;

    KnobbedTerm() = default;
    KnobbedTerm(NamedTerm::Kind kind, std::string symbol, std::string name,
                std::vector<double Knobs::*> knobs, double reference = 1,
                std::vector<double> tries = {}, double lo = 0, double hi = 0,
                std::function<std::string(double)> format = {}, bool whole = false)
        : kind(kind),
          symbol(std::move(symbol)),
          name(std::move(name)),
          knobs(std::move(knobs)),
          reference(reference),
          tries(std::move(tries)),
          lo(lo),
          hi(hi),
          format(std::move(format)),
          whole(whole) {}
    // A term of a struct this one derives from (the shared Cook-Torrance terms).
    template <class Base>
    KnobbedTerm(const KnobbedTerm<Base>& t)  // NOLINT(google-explicit-constructor)
        : KnobbedTerm(t.kind, t.symbol, t.name, {}, t.reference, t.tries, t.lo, t.hi, t.format,
                      t.whole) {
        static_assert(std::is_base_of_v<Base, Knobs>, "a term of a struct Knobs derives from");
        for (double Base::*k : t.knobs) knobs.push_back(k);
    }
};

template <class Knobs>
using KnobbedTerms = std::vector<KnobbedTerm<Knobs>>;

// A factor of the value: tried missing and twice (reference 1), or extra (reference 0).
template <class Knobs>
KnobbedTerm<Knobs> factor(std::string symbol, std::string name, std::vector<double Knobs::*> knobs,
                          double reference = 1) {
    return {NamedTerm::Kind::Factor, std::move(symbol), std::move(name), std::move(knobs),
            reference};
}
// A factor of the whole value: the message says "the reference divided by G".
template <class Knobs>
KnobbedTerm<Knobs> wholeFactor(std::string symbol, std::string name,
                               std::vector<double Knobs::*> knobs, double reference = 1) {
    KnobbedTerm<Knobs> t =
        factor<Knobs>(std::move(symbol), std::move(name), std::move(knobs), reference);
    t.whole = true;
    return t;
}
// A factor tried only at the given exponents.
template <class Knobs>
KnobbedTerm<Knobs> factorTried(std::string symbol, std::string name,
                               std::vector<double Knobs::*> knobs, double reference,
                               std::vector<double> tries) {
    return {NamedTerm::Kind::Factor, std::move(symbol), std::move(name),
            std::move(knobs),        reference,         std::move(tries)};
}
// An input's power tried only at the given exponents.
template <class Knobs>
KnobbedTerm<Knobs> exponentTried(std::string symbol, std::string name, double Knobs::*knob,
                                 double reference, std::vector<double> tries,
                                 std::function<std::string(double)> format) {
    return {NamedTerm::Kind::Exponent,
            std::move(symbol),
            std::move(name),
            {knob},
            reference,
            std::move(tries),
            0,
            0,
            std::move(format)};
}
// An input's power fitted over [lo, hi], said by `format` ("alpha = roughness^4").
template <class Knobs>
KnobbedTerm<Knobs> exponent(std::string symbol, std::string name, double Knobs::*knob,
                            double reference, double lo, double hi,
                            std::function<std::string(double)> format) {
    KnobbedTerm<Knobs> t =
        exponentTried(std::move(symbol), std::move(name), knob, reference, {}, std::move(format));
    t.lo = lo;
    t.hi = hi;
    return t;
}
// Another way of writing the step, set by `knob` = `value` (a 0/1 switch by default).
template <class Knobs>
KnobbedTerm<Knobs> onOff(std::string name, double Knobs::*knob, double value = 1) {
    return {NamedTerm::Kind::Switch, "", std::move(name), {knob}, 0, {value}};
}
// A part of a sum, tried removed (its switch 1 in the reference, 0 tried).
template <class Knobs>
KnobbedTerm<Knobs> removed(std::string name, double Knobs::*knob) {
    return {NamedTerm::Kind::Switch, "", std::move(name), {knob}, 1, {0}};
}

// Terms of a shared struct, for a struct derived from it.
template <class Knobs, class Base>
KnobbedTerms<Knobs> derivedTerms(const KnobbedTerms<Base>& terms) {
    return {terms.begin(), terms.end()};
}

template <class Knobs>
KnobbedTerms<Knobs> joined(KnobbedTerms<Knobs> a, const KnobbedTerms<Knobs>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

// The NamedTerms of `model`: each term's value is the model with that term's fields at the
// exponent tried and every other field at its default.
template <class Knobs>
std::vector<NamedTerm> namedTerms(
    std::function<glm::dvec3(const Surface&, const ReferenceContext&, const Knobs&)> model,
    const KnobbedTerms<Knobs>& terms) {
    std::vector<double Knobs::*> seen;  // a field's id: its place here
    auto id = [&seen](double Knobs::*k) {
        for (size_t i = 0; i < seen.size(); ++i)
            if (seen[i] == k) return int(i);
        seen.push_back(k);
        return int(seen.size() - 1);
    };
    std::vector<NamedTerm> out;
    for (const KnobbedTerm<Knobs>& t : terms) {
        NamedTerm n;
        n.kind = t.kind;
        n.symbol = t.symbol;
        n.name = t.name;
        n.reference = t.reference;
        n.tries = t.tries;
        n.lo = t.lo;
        n.hi = t.hi;
        n.format = t.format;
        n.whole = t.whole;
        for (double Knobs::*k : t.knobs) n.knobs.push_back(id(k));
        n.value = [model, fields = t.knobs](const Surface& s, const ReferenceContext& c, double e) {
            Knobs k;
            for (double Knobs::*f : fields) k.*f = e;
            return model(s, c, k);
        };
        out.push_back(std::move(n));
    }
    return out;
}

// x^e for a term's exponent: 1 when e = 0 (the term missing, even where x is 0), x itself when
// e = 1 (the reference, bit for bit), and a division by a term that is 0 here kept finite.
inline double power(double x, double e) {
    if (e == 0) return 1;
    if (e == 1) return x;
    if (e < 0) x = std::max(x, 1e-6);
    return std::pow(std::max(x, 0.0), e);
}
inline glm::dvec3 power(const glm::dvec3& x, double e) {
    return {power(x.x, e), power(x.y, e), power(x.z, e)};
}

// An exponent as a message writes it: 3 significant digits.
inline std::string exponentText(double v) {
    std::ostringstream o;
    o.precision(3);
    o << v;
    return o.str();
}

}  // namespace pbrlab
