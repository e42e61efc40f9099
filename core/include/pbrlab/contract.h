// The student-facing assignment contract (DESIGN.md): the 21 step ids in lab order, their
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
const ContractStep* findContractStep(const std::string& id);

// The contract steps whose GLSL a program for `id` needs, in step order: every earlier step
// of the same lab (students may call any of them), `extra` ids, and what those call in turn.
std::vector<const ContractStep*> contractClosure(const std::string& id,
                                                 const std::vector<std::string>& extra);

}  // namespace pbrlab
