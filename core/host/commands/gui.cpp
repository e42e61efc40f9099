// The `gui` command: the interactive lab's options.
#include "gui/gui.h"

#include <iostream>

#include "session.h"
#include "table.h"

namespace pbrlab {

namespace {

class GuiCommand : public Command {
public:
    GuiCommand() : Command("gui", "Open the interactive lab (needs a display)") {}
    void declare(CLI::App& cmd) override {
        // `gui ndf` as `render ndf`; --module is the spelling of earlier versions.
        cmd.add_option("step,--module", options_.module,
                       "Start on this step (--module ID: an alias, kept for older scripts)");
        cmd.add_option("--submission", options_.submission,
                       "Student folder with <id>.glsl files (default: the current directory "
                       "when it holds any)");
        cmd.add_option("--view", options_.view,
                       "student|solution|reference|difference|split, or a term view (albedo, "
                       "roughness, metallic, ao, normal, N.L, D, G, F, kS, kD, diffuse, "
                       "specular)");
        cmd.add_option("--scene", options_.scene, help::scene);
        cmd.add_option("--model", options_.model, help::model);
        cmd.add_option("--tab", options_.tab, "Open this side tab: handout|plot|log|programs");
        cmd.add_option("--set", options_.sets,
                       "Parameter name=value for the start step "
                       "(repeatable)");
        cmd.add_option("--command", options_.commands,
                       "Run this console line after the first frame, as if typed (repeatable; "
                       "`help` lists them)");
        cmd.add_option("--frames", options_.frames,
                       "Render this many frames (and until the --command lines have finished), "
                       "then exit");
        cmd.add_option("--screenshot", options_.screenshot,
                       "With --frames: save the window to this PNG");
        cmd.add_option("--window", window_, "Window size WxH (default 1600x960)");
        cmd.add_option("--size", oldWindow_, "Deprecated: the window's size; use --window");
        cmd.add_option("--error-budget", options_.errorBudget,
                       "Compute each environment's maps with the cheapest settings whose mean "
                       "errors stay within this (as precompute --error-budget)");
        cmd.add_flag("--orbit", options_.orbit,
                     "With --frames: orbit the camera a step each frame (as dragging does) and "
                     "print the frame times, median and 95th percentile");
        cmd.add_flag("--check-redraw", options_.checkRedraw,
                     "Draw each frame also whole and count the pixels where the frame drawn "
                     "only where it changed differs (printed at the end)");
        cmd.add_flag("--no-frame-economies{false}", options_.economies.on,
                     "Draw every frame whole, the live picture at full size with exact "
                     "spheres, as a GPU would (what a CPU rasteriser leaves out: "
                     "core/host/gui/frame_economies.h)");
        cmd.add_flag("--frame-times", options_.frameTimes,
                     "With --frames: print the frame times, and the longest frame while an "
                     "evaluation against the CPU reference runs");
    }
    int run(const GlobalOptions& global) override {
        // Every other command's --size is the rendered image; gui's was the window. Still
        // read as the window, so that older scripts run, with a note.
        if (!oldWindow_.empty()) {
            std::cerr << "note: gui --size is deprecated: it sets the window; use --window "
                      << oldWindow_ << "\n";
            if (window_.empty()) window_ = oldWindow_;
        }
        const Size s = parseSize(window_.empty() ? "1600x960" : window_,
                                 oldWindow_.empty() ? "--window" : "--size");
        options_.width = s.width;
        options_.height = s.height;
        options_.modulesDirs = modulesDirs(global);
        options_.globalArguments.clear();
        for (const std::string& dir : global.modulesDirs)
            options_.globalArguments.insert(options_.globalArguments.end(), {"--modules", dir});
        if (global.verbose) options_.globalArguments.push_back("--verbose");
        return runGui(options_);
    }

private:
    GuiOptions options_;
    std::string window_, oldWindow_;
};

}  // namespace

std::unique_ptr<Command> guiCommand() {
    return std::make_unique<GuiCommand>();
}

}  // namespace pbrlab
