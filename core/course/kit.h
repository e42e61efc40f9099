// The student kit: one <id>.glsl per module with the solution replaced by a TODO and a stub,
// the handouts, and a README on how to run and test.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "steps/plugin_host.h"
#include "steps/solution_stub.h"

namespace pbrlab {

struct KitOptions {
    std::filesystem::path out;
    bool withSolutions = false;  // reference solutions in the same shape (instructors, tests)
    std::string releaseThrough;  // solutions of the steps up to this id, stubs after
    bool force = false;          // write into a non-empty folder
    std::vector<std::string> steps =
        {};                // only these steps (an assignment's released ones); empty: all
    std::string due = {};  // shown in the README when set
};

// Writes the kit; returns how many module files were written.
int writeKit(const ModuleRegistry& modules, const KitOptions& options);

}  // namespace pbrlab
