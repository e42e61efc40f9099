// What the GUI needs of the platform it runs on, declared once and implemented twice: by the
// desktop (host/desktop/gui_platform.cpp: child processes, a frame loop of its own) and by a
// browser page (host/web/gui_platform.cpp: the page's JavaScript, its grader in a Web Worker,
// the browser's frame loop). Each build links one (core/CMakeLists.txt, web/CMakeLists.txt), so
// the GUI's own files read the same on both.
#pragma once

#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pbrlab::platform {

// Grades steps out of the window's way, as `pbrlab check ID --json` does: a process of its own
// on the desktop, the page's grader (a Web Worker given the workspace's files) in a browser.
class StepGrades {
public:
    virtual ~StepGrades() = default;  // a grade still running is stopped
    enum class Start { Started, NotHere, Failed };
    // Starts grading step `id` from the submission's file. NotHere: this platform cannot grade
    // (a browser without WebGL 2 on an OffscreenCanvas); Failed: the grade could not start.
    virtual Start start(const std::string& id) = 0;
    // The JSON report of step `id`'s grade once it has arrived (empty text: it never came),
    // else nothing yet.
    virtual std::optional<std::string> report(const std::string& id) = 0;
    // Whether a grade must finish before the next starts: each desktop grade takes the cores,
    // while the page's grader keeps its own queue (the file just written, then the step on
    // screen).
    virtual bool oneAtATime() const = 0;
};
// modulesDirs: the step folders the grades load, as this process does.
std::unique_ptr<StepGrades> stepGrades(std::vector<std::filesystem::path> modulesDirs,
                                       std::filesystem::path submission);

// `pbrlab ARGS` as the shell would run it, in a process group of its own, its stdout and stderr
// handed to `output` from a thread of its own as they come, then a line with how it ended.
class PbrlabProcess {
public:
    virtual ~PbrlabProcess() = default;  // stops the process group, waits for the last output
    virtual bool finished() const = 0;   // it ended and `output` has had all of it
};
// Nothing when no process can start (a page starts none); `output` then has the reason.
std::unique_ptr<PbrlabProcess> startPbrlab(const std::vector<std::string>& args,
                                           std::function<void(const std::string&)> output);

// Runs `frame` for each frame until it returns false and returns true, or, where the platform
// calls the frames itself (a page's requestAnimationFrame), returns false at once and the frames
// go on: whatever `frame` uses must then outlive the call. An exception escaping a frame ends the
// loop on the desktop; in a page it goes to `failed` and the next frame is drawn (an ended loop
// would leave the page frozen).
bool runFrames(const std::function<bool()>& frame,
               const std::function<void(const std::exception&)>& failed);

// Whether the window keeps its pixels from one frame to the next, so that a frame can be drawn
// over the last one in place (a page's canvas asked for preserveDrawingBuffer).
bool windowKeepsItsPixels();

// Whether a frame with nothing new may be skipped: a page's frames cost the browser its
// compositing, while the desktop draws every frame (its GPU draws, with vsync).
bool skipsQuietFrames();
// Whether input arrived since the last call (the page's listeners; the desktop has GLFW's).
bool inputArrived();
// Tells the page a frame was drawn (its tests wait for frames); nothing on the desktop.
void frameDrawn();
// A test the evaluation may call to yield to the window's input in a page that has one thread
// (Chromium's navigator.scheduling.isInputPending); empty where there is none.
std::function<bool()> inputPending();

// The evaluation's threads and the grades yield the cores to the window's thread (on the desktop
// at nice 10; a page has no priorities): this thread and every thread it starts from now on,
// and the threads that `start` starts (a GL context's rasterizer threads, started on the
// window's thread).
void backgroundPriorityForThisThread();
void backgroundPriorityForThreadsStartedBy(const std::function<void()>& start);

}  // namespace pbrlab::platform
