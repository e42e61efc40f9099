// GLFW backend: a window with a 4.5 core context, for the interactive GUI.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "gl/context.h"
#include "gl/gl.h"
#include "util/error.h"

namespace pbrlab {
namespace {

std::string lastGlfwError() {
    const char* text = nullptr;
    glfwGetError(&text);
    return text ? text : "unknown reason";
}

void* getProc(const char* name) {
    return reinterpret_cast<void*>(glfwGetProcAddress(name));
}

class GlfwContext final : public GlContext {
public:
    GlfwContext(int width, int height, const std::string& title) {
        if (!glfwInit())
            throw Error("cannot open a window (" + lastGlfwError() +
                        "); is there a display? Headless commands work without one");
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
        if (!window_) {
            std::string why = lastGlfwError();
            glfwTerminate();
            throw Error("cannot create an OpenGL 4.5 core window (" + why + ")");
        }
        glfwMakeContextCurrent(window_);
        glfwSwapInterval(1);
        gl::loadFunctions(getProc);
    }
    ~GlfwContext() override {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    std::string description() const override {
        return std::string("GLFW: ") + reinterpret_cast<const char*>(gl::GetString(GL_VERSION)) +
               ", " + reinterpret_cast<const char*>(gl::GetString(GL_RENDERER));
    }
    GLFWwindow* window() const override { return window_; }

private:
    GLFWwindow* window_ = nullptr;
};

}  // namespace

std::unique_ptr<GlContext> createWindowContext(int width, int height, const std::string& title) {
    return std::make_unique<GlfwContext>(width, height, title);
}

}  // namespace pbrlab
