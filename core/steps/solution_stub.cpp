#include "steps/solution_stub.h"

#include "util/error.h"

namespace pbrlab {

namespace {

std::string neutralValue(const std::string& signature) {
    std::string type = signature.substr(0, signature.find(' '));
    if (type == "float") return "0.0";
    if (type == "vec2") return "vec2(0.0)";
    if (type == "vec3") return "vec3(0.0)";
    if (type == "vec4") return "vec4(0.0)";
    throw Error("no neutral value for return type '" + type + "'");
}

}  // namespace

std::string stubSolution(const std::string& solution, const std::string& signature,
                         const std::string& fileName) {
    const std::string begin = "// BEGIN SOLUTION", end = "// END SOLUTION";
    size_t b = solution.find(begin), e = solution.find(end);
    if (b == std::string::npos || e == std::string::npos || e < b)
        throw Error(fileName + ": missing '// BEGIN SOLUTION' ... '// END SOLUTION' markers");
    size_t lineStart = solution.rfind('\n', b) + 1;
    std::string indent = solution.substr(lineStart, b - lineStart);
    std::string body = begin + "\n" + indent + "// TODO: implement " + signature +
                       " (see the handout).\n" + indent + "return " + neutralValue(signature) +
                       ";\n" + indent;
    return solution.substr(0, b) + body + solution.substr(e);
}

}  // namespace pbrlab
