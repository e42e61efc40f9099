// `pbrlab new-step ID --out DIR`: a step folder outside the source tree, ready to build against
// the installed package (find_package(pbrlab)) and to load with `pbrlab --modules
// DIR/build/modules`. The template is a complete, gradeable step (half-Lambert diffuse) that
// the author then rewrites: docs/authoring-a-module.md follows it file by file.
#pragma once

#include <filesystem>
#include <string>

namespace pbrlab {

struct NewStepOptions {
    std::string id;             // letters, digits and _: the student's file is <id>.glsl
    std::filesystem::path out;  // DIR: DIR/CMakeLists.txt and DIR/<id>/
    std::string lab;            // default: the lab of the step before it
    double order = 0;           // 0: after the last step (its order + 10)
};

// Writes DIR/CMakeLists.txt and DIR/<id>/{step.json, module.cpp, solution.glsl, view.glsl,
// README.md}. Throws pbrlab::Error when the id is taken or not an identifier, or when DIR/<id>
// already exists (nothing is overwritten).
void writeStepTemplate(const NewStepOptions& options);

}  // namespace pbrlab
