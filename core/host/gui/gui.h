// The interactive lab: a GLFW window with Dear ImGui, for students working through the steps.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "frame_economies.h"

namespace pbrlab {

struct GuiOptions {
    std::vector<std::filesystem::path> modulesDirs;  // where the step libraries are (moduleDirs)
    std::filesystem::path submission;  // empty: the current directory when it holds <id>.glsl
    std::string module;                // start on this module id
    std::string view;                  // student|solution|reference|difference|split or a term
    std::string scene;
    std::filesystem::path model;        // a glTF model (.glb/.gltf), lit like the step's scene
    std::string tab;                    // open this side tab: handout|plot|log|programs
    std::vector<std::string> sets;      // name=value for the start module
    std::vector<std::string> commands;  // console lines to run from the first frame (--command)
    std::vector<std::string> globalArguments;  // --modules/--verbose, for the console's commands
    int frames = 0;  // > 0: render this many frames and until the commands end, then exit
    std::filesystem::path screenshot;  // with frames: save the window here before exiting
    // With frames: turn the camera a step every frame, as a mouse drag does, and print the
    // frame times (median, 95th percentile): how interactive the lab is, scripted.
    bool orbit = false;
    // With frames: print the frame times, and the longest frame while an evaluation against
    // the CPU reference (the settled picture and its statistics) runs: whether the window
    // keeps drawing meanwhile.
    bool frameTimes = false;
    // Draw every frame also whole and count the pixels where the frame drawn over the last
    // one (only where it changed: redraw.h) differs; printed at the end.
    bool checkRedraw = false;
    // What the frames leave out on a CPU rasteriser (frame_economies.h): all, or none with
    // --no-frame-economies.
    FrameEconomies economies;
    // > 0: each environment's maps are computed with the cheapest settings whose measured mean
    // errors stay within this (chooseIblSettings, as `pbrlab precompute --error-budget`).
    double errorBudget = 0;
    int width = 1600, height = 960;
    // The view the student chose per step (step id -> viewName), remembered from an earlier
    // run: a page's, from the browser's storage (a desktop's are in gui.json).
    std::map<std::string, std::string> chosenViews;
    // Called when the student chooses a view for a step (the page remembers it).
    std::function<void(const std::string& id, const std::string& view)> viewChosen;
    // A page's watchdog (shell.html; empty on the desktop), asked before the window runs the
    // student's file of step `id` (its picture, an evaluation, a live frame): "" run it;
    // kStudentFileNotYet: not yet, ask again (the page is noting, where a hang would leave it,
    // that the file runs); anything else: why it may not run, as a refusal.
    std::function<std::string(const std::string& id)> studentFileGate;
    // The window's evaluation of step `id` with the student's file has come back.
    std::function<void(const std::string& id)> studentFileCameBack;
};

inline constexpr const char* kStudentFileNotYet = "not yet";

int runGui(const GuiOptions& options);

// For the page around the GUI (core/host/web/main.cpp): the id of the step the running GUI
// shows (empty before it starts), and a line for its console, run from the next frame.
std::string guiStepOnScreen();
void guiSubmitConsoleLine(const std::string& line);
// What the status lines under the picture say, as JSON: {"step", "settled", "error",
// "errorLog", "notice", "renderError", "sceneError", "rows": [{"text", "ok"}], "bandNote",
// "badge", "gradeMessage", "grade", "gradeDetails", "view", "layout", "redraw"} (the
// page's tests read it).
std::string guiStatusJson();
// The step's settled solution picture, display-encoded as `pbrlab render --out x.png` writes
// it, saved to `file` (the page's tests compare it with the desktop's).
void guiSaveSolutionPicture(const std::filesystem::path& file);
// The page's canvas has a new size.
void guiResize(int width, int height);
// GuiOptions::checkRedraw, turned on or off (the page's tests; the status JSON's "redraw").
void guiCheckRedraw(bool on);

}  // namespace pbrlab
