// The words of a grade as types: a step's status, a check's kind and category, and what named
// a mistake. Each has one list of names, in its values' order, used where a report is written
// or read (JSON, CSV, text); inside the program they are compared as values.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>

#include "util/error.h"

namespace pbrlab {

// A step's grade.
enum class GradeStatus { Passed, Failed, CompileError, Timeout, Missing, Crashed };
// What a check measured: values against the band, a property (invariant), an estimator's
// convergence, the stability sweep, the reference's own quality report, the contract itself.
enum class CheckKind { Values, Invariant, Convergence, Robustness, Quality, Contract };
// What a check is about, for the weights of an assignment (assignment.h).
enum class CheckCategory {
    Contract,
    Probe,
    Scenes,
    Random,
    SphereGrid,
    Invariants,
    Estimator,
    Robustness
};
// What named the mistake: nothing, the shape of the error, a typical mistake, a mutant.
enum class NamedBy { Nothing, Pattern, Typical, Mutant };

template <class E>
struct VerdictNames;
template <>
struct VerdictNames<GradeStatus> {
    static constexpr std::string_view what = "status";
    static constexpr std::array<std::string_view, 6> list = {"passed",  "failed",  "compile_error",
                                                             "timeout", "missing", "crashed"};
};
template <>
struct VerdictNames<CheckKind> {
    static constexpr std::string_view what = "check kind";
    static constexpr std::array<std::string_view, 6> list = {
        "values", "invariant", "convergence", "robustness", "quality", "contract"};
};
template <>
struct VerdictNames<CheckCategory> {
    static constexpr std::string_view what = "check category";
    static constexpr std::array<std::string_view, 8> list = {
        "contract",    "probe",      "scenes",    "random",
        "sphere_grid", "invariants", "estimator", "robustness"};
};
template <>
struct VerdictNames<NamedBy> {
    static constexpr std::string_view what = "named_by";
    static constexpr std::array<std::string_view, 4> list = {"", "pattern", "typical", "mutant"};
};

template <class E, class = decltype(VerdictNames<E>::list)>
std::string_view nameOf(E value) {
    return VerdictNames<E>::list[size_t(value)];
}

// The value named `name`, or none.
template <class E>
std::optional<E> verdictNamed(std::string_view name) {
    const auto& list = VerdictNames<E>::list;
    for (size_t i = 0; i < list.size(); ++i)
        if (list[i] == name) return E(i);
    return std::nullopt;
}

// Every value, in order.
template <class E>
constexpr std::array<E, VerdictNames<E>::list.size()> allOf() {
    std::array<E, VerdictNames<E>::list.size()> out{};
    for (size_t i = 0; i < out.size(); ++i) out[i] = E(i);
    return out;
}

// Reports carry the names; reading one that is not a name is an error naming it.
template <class E, class = decltype(VerdictNames<E>::list)>
void to_json(nlohmann::json& j, E value) {
    j = std::string(nameOf(value));
}
template <class E, class = decltype(VerdictNames<E>::list)>
void from_json(const nlohmann::json& j, E& value) {
    const std::string name = j.get<std::string>();
    const std::optional<E> v = verdictNamed<E>(name);
    if (!v) throw Error("'" + name + "' is not a " + std::string(VerdictNames<E>::what));
    value = *v;
}
template <class E, class = decltype(VerdictNames<E>::list)>
std::ostream& operator<<(std::ostream& out, E value) {
    return out << nameOf(value);
}

}  // namespace pbrlab
