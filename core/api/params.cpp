#include "pbrlab/params.h"

#include <charconv>
#include <cmath>
#include <locale>
#include <sstream>

#include "util/error.h"

namespace pbrlab {

namespace {

std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

bool parseDouble(const std::string& text, double& out) {
    const char* begin = text.data();
    const char* end = text.data() + text.size();
    while (begin < end && *begin == ' ') ++begin;
#if defined(_LIBCPP_VERSION) && _LIBCPP_VERSION < 170000
    // libc++ before 17 (Emscripten's, in the browser's build) has no from_chars for double: a
    // stream in the classic locale reads the same numbers (it also takes a '+', refused here).
    if (begin == end || *begin == '+') return false;
    std::istringstream in(std::string(begin, end));
    in.imbue(std::locale::classic());
    in >> out;
    return !in.fail() && in.peek() == std::char_traits<char>::eof() && std::isfinite(out);
#else
    auto [ptr, ec] = std::from_chars(begin, end, out);
    return ec == std::errc() && ptr == end && std::isfinite(out);
#endif
}

std::vector<std::string> split(const std::string& text, char sep) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, sep)) parts.push_back(part);
    if (!text.empty() && text.back() == sep) parts.push_back("");
    return parts;
}

}  // namespace

ParamDecl floatParam(std::string name, double def, double min, double max, std::string desc,
                     bool logScale) {
    ParamDecl d;
    d.name = std::move(name);
    d.description = std::move(desc);
    d.defaultValue = {def, 0, 0};
    d.min = min;
    d.max = max;
    d.logScale = logScale;
    return d;
}
ParamDecl intParam(std::string name, int def, int min, int max, std::string desc) {
    ParamDecl d = floatParam(std::move(name), def, min, max, std::move(desc));
    d.type = ParamType::Int;
    return d;
}
ParamDecl boolParam(std::string name, bool def, std::string desc) {
    ParamDecl d = floatParam(std::move(name), def ? 1 : 0, 0, 1, std::move(desc));
    d.type = ParamType::Bool;
    return d;
}
ParamDecl colorParam(std::string name, glm::dvec3 def, std::string desc, double max) {
    ParamDecl d = floatParam(std::move(name), 0, 0, max, std::move(desc));
    d.type = ParamType::Color;
    d.defaultValue = def;
    return d;
}
ParamDecl enumParam(std::string name, int def, std::vector<std::string> choices, std::string desc) {
    ParamDecl d = floatParam(std::move(name), def, 0, double(choices.size()) - 1, std::move(desc));
    d.type = ParamType::Enum;
    d.choices = std::move(choices);
    return d;
}
ParamDecl directionParam(std::string name, glm::dvec3 def, std::string desc, ParamBinding binding) {
    ParamDecl d = floatParam(std::move(name), 0, -1, 1, std::move(desc));
    d.type = ParamType::Direction;
    d.defaultValue = glm::normalize(def);
    d.binding = binding;
    return d;
}

ParamDecl lightDirectionParam(std::string desc) {
    return directionParam("light_dir", {5, 5, 8}, std::move(desc), ParamBinding::LightDirection);
}

std::string ParamDecl::typeName() const {
    switch (type) {
        case ParamType::Float:
            return "float in [" + num(min) + ", " + num(max) + "]" + (logScale ? " (log)" : "");
        case ParamType::Int:
            return "integer in [" + num(min) + ", " + num(max) + "]";
        case ParamType::Bool:
            return "true|false";
        case ParamType::Color:
            return "colour r,g,b each in [0, " + num(max) + "]";
        case ParamType::Direction:
            return "direction x,y,z (not all zero; normalised)";
        case ParamType::Enum: {
            std::string s = "one of ";
            for (size_t i = 0; i < choices.size(); ++i) s += (i ? "|" : "") + choices[i];
            return s;
        }
    }
    return "?";
}

std::string ParamDecl::format(const glm::dvec3& v) const {
    switch (type) {
        case ParamType::Float:
            return num(v.x);
        case ParamType::Int:
            return num(std::round(v.x));
        case ParamType::Bool:
            return v.x != 0 ? "true" : "false";
        case ParamType::Enum:
            return choices.at(size_t(v.x));
        case ParamType::Color:
        case ParamType::Direction:
            return num(v.x) + "," + num(v.y) + "," + num(v.z);
    }
    return "?";
}

ParamValues::ParamValues(const std::vector<ParamDecl>& decls) {
    for (const auto& d : decls) values_[d.name] = d.defaultValue;
}

double ParamValues::number(const std::string& name) const {
    return vector(name).x;
}

glm::dvec3 ParamValues::vector(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end()) throw Error("no parameter named '" + name + "'");
    return it->second;
}

glm::dvec3 parseParamValue(const ParamDecl& decl, const std::string& text) {
    auto bad = [&](const std::string& why) {
        return Error("parameter " + decl.name + "=" + text + ": " + why + "; expected " +
                     decl.typeName());
    };
    switch (decl.type) {
        case ParamType::Float:
        case ParamType::Int: {
            double v = 0;
            if (!parseDouble(text, v)) throw bad("not a number");
            if (decl.type == ParamType::Int && v != std::round(v)) throw bad("not an integer");
            if (v < decl.min || v > decl.max) throw bad("out of range");
            return {v, 0, 0};
        }
        case ParamType::Bool:
            if (text == "true" || text == "1" || text == "on" || text == "yes") return {1, 0, 0};
            if (text == "false" || text == "0" || text == "off" || text == "no") return {0, 0, 0};
            throw bad("not a boolean");
        case ParamType::Enum:
            for (size_t i = 0; i < decl.choices.size(); ++i)
                if (decl.choices[i] == text) return {double(i), 0, 0};
            throw bad("unknown choice");
        case ParamType::Color:
        case ParamType::Direction: {
            auto parts = split(text, ',');
            if (parts.size() != 3) throw bad("needs three comma-separated numbers");
            glm::dvec3 v;
            for (int i = 0; i < 3; ++i)
                if (!parseDouble(parts[size_t(i)], v[i])) throw bad("not a number");
            if (decl.type == ParamType::Color) {
                for (int i = 0; i < 3; ++i)
                    if (v[i] < 0 || v[i] > decl.max) throw bad("component out of range");
                return v;
            }
            double len = glm::length(v);
            if (!(len > 1e-12)) throw bad("zero vector has no direction");
            return v / len;
        }
    }
    throw bad("unsupported type");
}

void applyAssignment(const std::vector<ParamDecl>& decls, ParamValues& values,
                     const std::string& assignment) {
    auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0)
        throw Error("--set " + assignment + ": expected name=value");
    std::string name = assignment.substr(0, eq), text = assignment.substr(eq + 1);
    for (const auto& d : decls)
        if (d.name == name) {
            values.set(name, parseParamValue(d, text));
            return;
        }
    std::string known;
    for (const auto& d : decls) known += "\n  " + d.name + ": " + d.typeName();
    throw Error(
        "unknown parameter '" + name + "'" +
        (known.empty() ? "; this module has no parameters" : "; known parameters:" + known));
}

}  // namespace pbrlab
