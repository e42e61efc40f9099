// Typed module parameters: declarations with defaults, ranges and a one-line description;
// values parsed from `--set name=value` text with errors that list what is allowed.
#pragma once

#include <glm/glm.hpp>
#include <map>
#include <string>
#include <vector>

namespace pbrlab {

enum class ParamType { Float, Int, Bool, Color, Enum, Direction };

// Where a value goes besides the uniform `u_<name>` of the module's view.
enum class ParamBinding {
    Uniform,         // only the uniform (and the CPU reference through ParamValues)
    LightDirection,  // also moves the scene's first light to this direction from the origin
};

struct ParamDecl {
    std::string name;
    ParamType type = ParamType::Float;
    std::string description;
    glm::dvec3 defaultValue{0};        // scalars in x; Enum: the index in x
    double min = 0, max = 1;           // Float, Int, and each Color component
    bool logScale = false;             // Float: slider in log space
    std::vector<std::string> choices;  // Enum
    ParamBinding binding = ParamBinding::Uniform;

    std::string uniformName() const { return "u_" + name; }
    std::string typeName() const;                       // "float in [0, 1]", "one of a|b", ...
    std::string format(const glm::dvec3& value) const;  // as `--set` would take it
};

ParamDecl floatParam(std::string name, double def, double min, double max, std::string desc,
                     bool logScale = false);
ParamDecl intParam(std::string name, int def, int min, int max, std::string desc);
ParamDecl boolParam(std::string name, bool def, std::string desc);
ParamDecl colorParam(std::string name, glm::dvec3 def, std::string desc, double max = 1);
ParamDecl enumParam(std::string name, int def, std::vector<std::string> choices, std::string desc);
ParamDecl directionParam(std::string name, glm::dvec3 def, std::string desc,
                         ParamBinding binding = ParamBinding::Uniform);
// "light_dir", the direct-lab steps' light: bound to the scene's light 0, default (5, 5, 8),
// where the default scene puts it (so the default view shows the scene as authored).
ParamDecl lightDirectionParam(
    std::string desc = "Direction from the scene centre to the light (moves light 0)");

// Current values of a module's parameters (all present; defaults until set).
class ParamValues {
public:
    ParamValues() = default;
    explicit ParamValues(const std::vector<ParamDecl>& decls);
    double number(const std::string& name) const;  // Float, Int, Bool (0/1), Enum index
    glm::dvec3 vector(const std::string& name) const;
    void set(const std::string& name, const glm::dvec3& value) { values_[name] = value; }
    const std::map<std::string, glm::dvec3>& all() const { return values_; }

private:
    std::map<std::string, glm::dvec3> values_;
};

// Parses "value" for one declaration; throws pbrlab::Error naming the parameter, the text and
// what is allowed.
glm::dvec3 parseParamValue(const ParamDecl& decl, const std::string& text);

// Applies "name=value"; throws pbrlab::Error for an unknown name (listing the known ones) or
// a bad value.
void applyAssignment(const std::vector<ParamDecl>& decls, ParamValues& values,
                     const std::string& assignment);

}  // namespace pbrlab
