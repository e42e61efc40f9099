// What the student has chosen in the GUI, as plain data: the panels edit it, the frame
// function (lab.h) reads it, and part of it is remembered across runs in gui.json.
#pragma once

#include <array>
#include <filesystem>
#include <map>
#include <string>

#include "pbrlab/params.h"
#include "views.h"

namespace pbrlab {

class ModuleRegistry;

// The orbit camera around the scene's target.
struct OrbitCamera {
    double yaw = 0, pitch = 0, distance = 3;
};

// The three windows side by side: steps | picture | module; the middle takes what is left.
// Computed, not saved (ImGui's ini file is off).
struct WindowLayout {
    float stepsWidth = 250, moduleWidth = 430;
    // As drawn in the last frame (the page's tests read them): narrower than
    // kCompactLayoutWidth, the steps panel folds into a line at the top of the picture's window.
    bool compact = false;
    float steps = 0, view = 0, module = 0;  // the windows' widths
    float pictureSide = 0;
    std::array<float, 2> pictureOrigin{};  // the picture's top-left corner: x, y
    std::array<float, 4> viewToggle{};     // the one-click view button: x, y, width, height
};

// A window narrower than this (a laptop's page beside its editor: 896 and 956 pixels at
// 1280 and 1366) shows the steps as a line over the picture: with the steps panel, three
// windows in that width left the picture under 370 pixels and cut its status lines.
inline constexpr float kCompactLayoutWidth = 1000;

struct GuiState {
    int step = 0;  // index into ModuleRegistry::modules()
    View view = View::Student;
    int term = 0;  // with View::Term: the index into kTermViews
    // The scene shown: empty sceneName is the step's own; a model is lit like that scene.
    std::string sceneName;
    std::filesystem::path model;  // absolute and canonical (canonicalFile); empty: none
    std::map<std::string, ParamValues> params;  // per step id
    OrbitCamera camera;
    std::string openTab;  // --tab: selected on the first frame, then cleared
    WindowLayout layout;
    float differenceRange = 1e-3f;  // View::Difference: the value shown at full colour
    float split = 0.5f;             // View::Split: where the reference starts, of the width
    int plotRow = 0;                // the probe row the plot shows
    bool polarPlot = true;          // probes over the light's angle: the row as a lobe
    bool polarTimesCosine = true;
    std::array<char, 512> environmentInput{};  // the environment field's text
    // The view the student chose per step (step id -> viewName): a step shows it when chosen
    // again; a step without one shows the student's picture when their file exists, else the
    // solution's. Remembered across runs.
    std::map<std::string, std::string> chosenViews;
};

// $XDG_CONFIG_HOME/pbrlab/gui.json (~/.config/pbrlab when unset).
std::filesystem::path configFile();

// Model files are compared (chooser entries, --model, the saved choice) as absolute,
// canonical paths, so one file is one entry however it was named.
std::filesystem::path canonicalFile(const std::filesystem::path& file);

// What gui.json remembers besides the parameters, which restoreState writes into the state.
struct RememberedChoice {
    std::string step;             // empty: none remembered
    std::filesystem::path model;  // empty: none
};

// Reads gui.json: the parameters go into state.params (a value an older version of the step
// no longer accepts keeps the default). A file that does not parse adds a line to `messages`.
RememberedChoice restoreState(const ModuleRegistry& registry, GuiState& state,
                              std::string& messages);

// Writes the step, the model, every step's parameters and the views chosen to gui.json.
void saveState(const ModuleRegistry& registry, const GuiState& state);

}  // namespace pbrlab
