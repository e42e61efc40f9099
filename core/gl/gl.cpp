#include "gl/gl.h"

#include "util/error.h"

namespace pbrlab::gl {

#define PBRLAB_GL_DEFINE(type, name) type name = nullptr;
PBRLAB_GL_FUNCTIONS(PBRLAB_GL_DEFINE)
#undef PBRLAB_GL_DEFINE

void loadFunctions(GetProcAddress getProc) {
#define PBRLAB_GL_LOAD(type, name)                      \
    name = reinterpret_cast<type>(getProc("gl" #name)); \
    if (!name) throw Error("OpenGL entry point gl" #name " is missing from the active context");
    PBRLAB_GL_FUNCTIONS(PBRLAB_GL_LOAD)
#undef PBRLAB_GL_LOAD
}

void checkError(const char* what) {
    GLenum e = GetError();
    if (e == GL_NO_ERROR) return;
    const char* name = e == GL_INVALID_ENUM                    ? "GL_INVALID_ENUM"
                       : e == GL_INVALID_VALUE                 ? "GL_INVALID_VALUE"
                       : e == GL_INVALID_OPERATION             ? "GL_INVALID_OPERATION"
                       : e == GL_OUT_OF_MEMORY                 ? "GL_OUT_OF_MEMORY"
                       : e == GL_INVALID_FRAMEBUFFER_OPERATION ? "GL_INVALID_FRAMEBUFFER_OPERATION"
                                                               : "unknown GL error";
    throw Error(std::string(what) + ": " + name);
}

}  // namespace pbrlab::gl
