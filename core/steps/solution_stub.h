// A step's solution file with the solution taken out: what the kit hands students, and what
// the grader grades to show that a stub earns nothing.
#pragma once

#include <string>

namespace pbrlab {

// The student version of a solution file: what is between BEGIN/END SOLUTION becomes a TODO
// comment and a stub returning a neutral value of the function's return type. Throws
// pbrlab::Error naming the file when the markers are missing.
std::string stubSolution(const std::string& solution, const std::string& signature,
                         const std::string& fileName);

}  // namespace pbrlab
