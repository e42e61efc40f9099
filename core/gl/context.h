// An OpenGL 4.5 core context made current on this thread, from one of two backends:
// OSMesa (headless, no GPU or display: CLI, tests, grading) or a GLFW window (the GUI).
#pragma once

#include <memory>
#include <string>

struct GLFWwindow;

namespace pbrlab {

class GlContext {
public:
    virtual ~GlContext() = default;
    // "OSMesa: 4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)"
    virtual std::string description() const = 0;
    // The window, or nullptr for an off-screen context.
    virtual GLFWwindow* window() const { return nullptr; }
};

// Loads libOSMesa at run time; throws pbrlab::Error saying what is missing when it cannot.
std::unique_ptr<GlContext> createHeadlessContext();

// Loads libOSMesa (and llvmpipe's LLVM: 0.1 s of relocations) without creating a context, so
// that a process forking one grader per module pays it once. Loading starts no thread (a
// context does, and threads do not survive a fork).
void preloadHeadlessLibrary();

// Opens a window; throws pbrlab::Error when there is no display or no 4.5 core support.
std::unique_ptr<GlContext> createWindowContext(int width, int height, const std::string& title);

}  // namespace pbrlab
