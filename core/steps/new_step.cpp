#include "steps/new_step.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "steps/contract.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

// "half_lambert" -> "halfLambert": the GLSL function's name.
std::string camelCase(const std::string& id) {
    std::string name;
    bool upper = false;
    for (char c : id) {
        if (c == '_') {
            upper = !name.empty();
            continue;
        }
        name += upper ? char(std::toupper(static_cast<unsigned char>(c))) : c;
        upper = false;
    }
    return name;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
    for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
        text.replace(at, from.size(), to);
    return text;
}

void write(const fs::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary);
    out << text;
    if (!out) throw Error(file.string() + ": cannot write");
}

constexpr const char* kCMakeLists =
    R"(# The step @ID@, built outside pbrlab's source tree against the installed package:
#   cmake -S . -B build -DCMAKE_PREFIX_PATH=<pbrlab's install prefix> && cmake --build build
#   pbrlab --modules build/modules list
cmake_minimum_required(VERSION 3.25)
project(@ID@_step LANGUAGES CXX)
set(CMAKE_CXX_STANDARD 20)
find_package(pbrlab REQUIRED)
pbrlab_add_step(${CMAKE_CURRENT_SOURCE_DIR}/@ID@)
)";

constexpr const char* kModule =
    R"(// @ID@: half-Lambert diffuse, (0.5 N.L + 0.5)^2, a wrapped cosine that lights the
// side turned away from the light. (The template of `pbrlab new-step`: rewrite it for your
// step; docs/authoring-a-module.md says what each field is for.)
#include "pbrlab/module.h"
#include "pbrlab/named_terms.h"

#include <algorithm>
#include <cmath>
#include <numbers>

using namespace pbrlab;

namespace {

double halfLambert(const glm::dvec3& N, const glm::dvec3& L) {
    const double wrapped = 0.5 * glm::dot(N, L) + 0.5;
    return wrapped * wrapped;
}

// The formula once more with its parts as fields (defaults: the reference), so that feedback
// can name the part a student got wrong (docs/authoring-a-module.md, "Feedback that names a
// term").
struct Knobs {
    double square = 2;     // the power of the wrapped cosine
    double unwrapped = 0;  // 1: max(N.L, 0) where the wrapped cosine 0.5 N.L + 0.5 belongs
};
glm::dvec3 halfLambertTerms(const Surface& s, const ReferenceContext&, const Knobs& k) {
    const double c = glm::dot(s.normal, s.light);
    return glm::dvec3(power(k.unwrapped != 0 ? std::max(c, 0.0) : 0.5 * c + 0.5, k.square));
}

ModuleDesc describeModule() {
    ModuleDesc d;  // id, lab, position and signature come from step.json
    d.title = "Half-Lambert diffuse (0.5 N.L + 0.5)^2";
    d.params = {lightDirectionParam()};
    d.components = 1;
    d.display = {DisplayMode::Grey, 0, 1};
    // Band: +- 1e-3 of the value, at least 1e-6, or the spread of 8 ulps of N and L.
    d.tolerance = {1e-6, 1e-3, 8};
    d.domain = [](DomainRandom& r) {
        Surface s;
        s.normal = r.direction();
        s.light = r.direction();
        s.view = r.around(s.normal, 0, 1);
        return s;
    };
    d.cases = {lessonGridCase()};
    d.reference = [](const Surface& s, const ReferenceContext&) {
        return glm::dvec3(halfLambert(s.normal, s.light));
    };
    d.namedTerms = namedTerms<Knobs>(
        halfLambertTerms,
        {exponent<Knobs>("^2", "the square", &Knobs::square, 2, 0.5, 4,
                         [](double e) { return "(0.5 N.L + 0.5)^" + exponentText(e); }),
         onOff<Knobs>("max(N.L, 0) (Lambert's cosine) where the wrapped cosine 0.5 N.L + 0.5 "
                      "belongs",
                      &Knobs::unwrapped)});
    // What the GUI can show over any picture (its view chooser, `gui --view @ID@`).
    d.termViews = {{"@ID@", TermView::Encode::None, [](const Surface& s) {
                        return glm::dvec3(halfLambert(s.normal, s.light));
                    }}};
    // x: angle between N and L, 0 to 180 degrees; y: azimuth of L around N.
    d.probe.xAxis = "angle(N, L) 0..180 deg";
    d.probe.yAxis = "azimuth of L 0..360 deg";
    d.probe.width = 65;
    d.probe.height = 17;
    d.probe.at = [](double x, double y) {
        const double theta = x * std::numbers::pi, phi = y * 2 * std::numbers::pi;
        Surface s;
        s.covered = true;
        s.normal = {0, 0, 1};
        s.light = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   std::cos(theta)};
        return s;
    };
    return d;
}

}  // namespace

PBRLAB_MODULE(describeModule)
)";

constexpr const char* kSolution =
    R"(// Half-Lambert: N.L mapped from [-1, 1] to [0, 1] and squared, so that light wraps around
// the terminator instead of stopping at it.
@FUNCTION@
{
    // BEGIN SOLUTION
    float wrapped = 0.5 * dot(N, L) + 0.5;
    return wrapped * wrapped;
    // END SOLUTION
}
)";

constexpr const char* kView = R"(// What the step shows: @NAME@(N, L) in grey on the sphere.
vec3 view(Surface s)
{
    return vec3(@NAME@(s.normal, s.light));
}
)";

constexpr const char* kReadme = R"(# @ID@: half-Lambert diffuse

**Write** `@FUNCTION@` in `@ID@.glsl`.

## Goal

Lambert's cosine stops at the terminator: the side turned away from the light is black. The
half-Lambert term maps N·L from [−1, 1] to [0, 1] and squares it, so light wraps around:

    @NAME@(N, L) = (0.5 N·L + 0.5)²

## What the image shows

`pbrlab render @ID@ --out @ID@.png`: the sphere in grey, white facing the light, fading to
black only at the point exactly opposite it.

## Tolerance and why

The value is compared with the CPU reference in double precision on the same inputs, within
±1e-3 of the value (at least 1e-6), or the spread of 8 ulps of N and L where the function is
steeper than that.
)";

}  // namespace

void writeStepTemplate(const NewStepOptions& o) {
    auto isIdChar = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    if (o.id.empty() || !std::all_of(o.id.begin(), o.id.end(), isIdChar) ||
        std::isdigit(static_cast<unsigned char>(o.id[0])))
        throw Error("new-step: '" + o.id +
                    "' is not a step id (letters, digits and _, not starting with a digit)");
    const std::vector<ContractStep>& steps = contractSteps();
    if (const ContractStep* taken = findContractStep(o.id))
        throw Error("new-step: '" + o.id + "' is already a step (" + taken->folder.string() + ")");
    const fs::path folder = o.out / o.id;
    std::error_code ec;
    if (fs::exists(folder, ec)) throw Error("new-step: " + folder.string() + " already exists");
    const std::string name = camelCase(o.id);
    const std::string function = "float " + name + "(vec3 N, vec3 L)";
    for (const ContractStep& s : steps)
        if (s.function.find(" " + name + "(") != std::string::npos)
            throw Error("new-step: the function name " + name + " is already " + s.id + "'s");

    nlohmann::ordered_json step;
    step["id"] = o.id;
    // By default after the last step, in its lab; with --order, in the lab of the step before.
    const double order = o.order > 0 ? o.order : steps.empty() ? 10.0 : steps.back().order + 10;
    std::string lab = o.lab;
    if (lab.empty()) {
        lab = steps.empty() ? "lab" : steps.front().lab;
        for (const ContractStep& s : steps)
            if (s.order < order) lab = s.lab;
    }
    step["lab"] = lab;
    step["order"] = order;
    step["function"] = function;
    step["calls"] = nlohmann::json::array();

    fs::create_directories(folder);
    auto fill = [&](const char* text) {
        return replaced(replaced(replaced(text, "@ID@", o.id), "@FUNCTION@", function), "@NAME@",
                        name);
    };
    write(folder / "step.json", step.dump(2) + "\n");
    write(folder / "module.cpp", fill(kModule));
    write(folder / "solution.glsl", fill(kSolution));
    write(folder / "view.glsl", fill(kView));
    write(folder / "README.md", fill(kReadme));
    if (!fs::exists(o.out / "CMakeLists.txt", ec))
        write(o.out / "CMakeLists.txt", fill(kCMakeLists));
}

}  // namespace pbrlab
