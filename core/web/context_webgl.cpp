// gl/context.h in the browser: the page's canvas as a WebGL 2 context, through Emscripten's
// GLFW, and an OffscreenCanvas's as the headless one. WebGL 2 is OpenGL ES 3.0: the renderer writes
// its programs as GLSL ES 3.00 (GlslDialect::Es300) and every entry point gl/gl.h names exists
// there.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <emscripten/em_asm.h>
#include <emscripten/html5.h>

#include "gl/context.h"
#include "gl/gl.h"
#include "util/error.h"

namespace pbrlab {
namespace {

void* getProc(const char* name) {
    return reinterpret_cast<void*>(glfwGetProcAddress(name));
}

class WebGlContext final : public GlContext {
public:
    WebGlContext(int width, int height, const std::string& title) {
        if (!glfwInit()) throw Error("cannot start GLFW in the page");
        glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_ES_API);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 0);
        // The page's canvas holds the GUI's colours only: every pass renders into its own
        // framebuffer, and ImGui draws without depth or stencil. Without alpha the browser
        // composites the canvas as opaque; GLFW's defaults (alpha, a 24-bit depth and an 8-bit
        // stencil buffer) cost SwiftShader fill on each frame.
        glfwWindowHint(GLFW_ALPHA_BITS, 0);
        glfwWindowHint(GLFW_DEPTH_BITS, 0);
        glfwWindowHint(GLFW_STENCIL_BITS, 0);
        window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
        if (!window_) {
            glfwTerminate();
            throw Error("this browser gives no WebGL 2 context");
        }
        glfwMakeContextCurrent(window_);
        // Float colour targets (the G-buffer, the precomputed maps, read-back of values) are
        // an extension in WebGL 2; without it no step can be evaluated.
        const EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context = emscripten_webgl_get_current_context();
        if (!emscripten_webgl_enable_extension(context, "EXT_color_buffer_float"))
            throw Error(
                "this browser's WebGL 2 cannot render to float textures "
                "(EXT_color_buffer_float)");
        emscripten_webgl_enable_extension(context, "OES_texture_float_linear");
        gl::loadFunctions(getProc);
    }
    ~WebGlContext() override {
        glfwDestroyWindow(window_);
        glfwTerminate();
    }
    std::string description() const override {
        return std::string("WebGL: ") + reinterpret_cast<const char*>(gl::GetString(GL_VERSION)) +
               ", " + reinterpret_cast<const char*>(gl::GetString(GL_RENDERER));
    }
    GLFWwindow* window() const override { return window_; }

private:
    GLFWwindow* window_ = nullptr;
};

// The headless context of the browser: WebGL 2 on an OffscreenCanvas, which a Web Worker
// may create (the page's grader, core/host/web/grader.cpp), drawn into framebuffers only.
class OffscreenWebGlContext final : public GlContext {
public:
    OffscreenWebGlContext() {
        // Emscripten finds a canvas by selector; a worker has no document to look in.
        EM_ASM({ specialHTMLTargets["#pbrlab-offscreen"] = new OffscreenCanvas(16, 16); });
        EmscriptenWebGLContextAttributes attributes;
        emscripten_webgl_init_context_attributes(&attributes);
        attributes.majorVersion = 2;
        attributes.minorVersion = 0;
        attributes.alpha = attributes.depth = attributes.stencil = attributes.antialias = false;
        context_ = emscripten_webgl_create_context("#pbrlab-offscreen", &attributes);
        if (context_ <= 0)
            throw Error("this browser gives no WebGL 2 context on an OffscreenCanvas");
        emscripten_webgl_make_context_current(context_);
        if (!emscripten_webgl_enable_extension(context_, "EXT_color_buffer_float"))
            throw Error(
                "this browser's WebGL 2 cannot render to float textures "
                "(EXT_color_buffer_float)");
        emscripten_webgl_enable_extension(context_, "OES_texture_float_linear");
        gl::loadFunctions(getOffscreenProc);
    }
    ~OffscreenWebGlContext() override { emscripten_webgl_destroy_context(context_); }
    std::string description() const override {
        return std::string("WebGL (OffscreenCanvas): ") +
               reinterpret_cast<const char*>(gl::GetString(GL_VERSION)) + ", " +
               reinterpret_cast<const char*>(gl::GetString(GL_RENDERER));
    }

private:
    static void* getOffscreenProc(const char* name) {
        return emscripten_webgl_get_proc_address(name);
    }
    EMSCRIPTEN_WEBGL_CONTEXT_HANDLE context_ = 0;
};

}  // namespace

std::unique_ptr<GlContext> createWindowContext(int width, int height, const std::string& title) {
    return std::make_unique<WebGlContext>(width, height, title);
}

std::unique_ptr<GlContext> createHeadlessContext() {
    return std::make_unique<OffscreenWebGlContext>();
}

void preloadHeadlessLibrary() {}

}  // namespace pbrlab
