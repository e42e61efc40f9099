// The makers of each command, defined with their group (render.cpp, grade.cpp, assets.cpp,
// gallery.cpp, gui.cpp) and listed in one table (table.cpp).
#pragma once

#include <memory>

#include "command.h"

namespace pbrlab {

// render.cpp: steps on screen.
std::unique_ptr<Command> listCommand();
std::unique_ptr<Command> renderCommand();
std::unique_ptr<Command> checkCommand();
std::unique_ptr<Command> permutationsCommand();
// grade.cpp: grading and the kit.
std::unique_ptr<Command> gradeCommand();
std::unique_ptr<Command> classroomCommand();
std::unique_ptr<Command> kitCommand();
std::unique_ptr<Command> autograderCommand();
std::unique_ptr<Command> mutantsCommand();
std::unique_ptr<Command> newStepCommand();
// assets.cpp: the project's generated and precomputed data.
std::unique_ptr<Command> modelsCommand();
std::unique_ptr<Command> environmentCommand();
std::unique_ptr<Command> convergeCommand();
std::unique_ptr<Command> precomputeCommand();
std::unique_ptr<Command> texturesCommand();
// gallery.cpp: every step at once.
std::unique_ptr<Command> stabilityCommand();
std::unique_ptr<Command> galleryCommand();
// gui.cpp: the window.
std::unique_ptr<Command> guiCommand();

}  // namespace pbrlab
