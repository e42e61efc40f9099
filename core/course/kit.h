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

// The step folders a browser site built for the kit's assignment carries (`kit --site-steps`,
// docs/web.md), in options.out/<id>: every step up to the last one the kit hands out, copied.
// Each step the kit hands out as a starter (`steps`, after `releaseThrough`) is withheld: its
// solution.glsl, its planted mistakes (each the solution with one error) and its module.cpp
// (the CPU reference's source; the site has it compiled) are left out, and its starter.glsl,
// the kit's file, is written in their place. Returns the ids withheld.
std::vector<std::string> writeSiteSteps(const ModuleRegistry& modules, const KitOptions& options);

}  // namespace pbrlab
