// The student-facing assignment contract (docs/design.md): the 21 step ids in lab order, their
// GLSL signatures, and which other contract functions each reference solution calls.
#pragma once

#include <string>
#include <vector>

namespace pbrlab {

struct ContractStep {
    int step;
    std::string id;
    std::string lab;                 // "direct" or "ibl"
    std::string function;            // the GLSL signature
    std::vector<std::string> calls;  // ids its reference solution calls
    std::string folder() const;      // "04-ndotl"
};

const std::vector<ContractStep>& contractSteps();

// The contract helper every step may call besides the steps' functions (shaders/
// fresnel_roughness.glsl).
inline constexpr const char* kFresnelSchlickRoughness =
    "vec3 fresnelSchlickRoughness(float cosTheta, vec3 F0, float roughness)";

// GLSL prototypes of every contract function (and the helper), for programs that link them all.
std::string contractPrototypes();
const ContractStep* findContractStep(const std::string& id);

// The contract steps whose GLSL a program for `id` needs, in step order: every earlier step
// of the same lab (students may call any of them), `extra` ids, and what those call in turn.
std::vector<const ContractStep*> contractClosure(const std::string& id,
                                                 const std::vector<std::string>& extra);

}  // namespace pbrlab
