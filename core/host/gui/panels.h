// The GUI's panels: functions drawn every frame (Dear ImGui), each reading the Lab and the
// state, and changing only the state and the requests (carried out by the next frame).
#pragma once

#include <string>

#include "console.h"
#include "lab.h"

namespace pbrlab {

// The left window: the workspace and the steps with their badges.
void drawStepsPanel(const Lab& lab, GuiState& state, Requests& requests);

// The steps in one line (the step, its badge, the list a click away, previous / next): at the
// top of the view panel in a window too narrow for the steps panel.
void drawStepsLine(const Lab& lab, GuiState& state, Requests& requests);

// The middle window: the step's title, the view chooser with its settings, the picture (drag
// to orbit, wheel to zoom, hover to inspect a pixel) and the statistics under it.
void drawViewPanel(const Lab& lab, GuiState& state, Requests& requests);

// The right window's top: the step's parameters and the scene (chooser, light, environment).
void drawModulePanel(const Lab& lab, GuiState& state, Requests& requests);

// What the side tabs remember between frames besides the state.
struct SideTabsMemory {
    std::string shownLog;  // the compile log last shown: a new one selects the Log tab once
};

// The right window's bottom: the Handout, Plot, Log, Programs and Console tabs.
void drawSideTabs(const Lab& lab, GuiState& state, SideTabsMemory& memory, Console& console);

// The tabs' contents.
void drawPlotTab(const Lab& lab, GuiState& state);
void drawLogTab(const Lab& lab, const GuiState& state);
void drawProgramsTab(const Lab& lab);
void drawConsoleTab(const Lab& lab, Console& console);

}  // namespace pbrlab
