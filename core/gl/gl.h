// OpenGL 4.5 core entry points, resolved at run time through the active context backend's
// get-proc-address (GLEW and libepoxy fail under OSMesa). They live in namespace
// pbrlab::gl (gl::CreateShader, ...) so they never interpose on libGL's exported symbols.
#pragma once

#include <GL/glcorearb.h>

#include <string>

#define PBRLAB_GL_FUNCTIONS(X)                                   \
    X(PFNGLGETSTRINGPROC, GetString)                             \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                         \
    X(PFNGLGETERRORPROC, GetError)                               \
    X(PFNGLVIEWPORTPROC, Viewport)                               \
    X(PFNGLCLEARPROC, Clear)                                     \
    X(PFNGLCLEARCOLORPROC, ClearColor)                           \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                     \
    X(PFNGLENABLEPROC, Enable)                                   \
    X(PFNGLDISABLEPROC, Disable)                                 \
    X(PFNGLISENABLEDPROC, IsEnabled)                             \
    X(PFNGLSCISSORPROC, Scissor)                                 \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                             \
    X(PFNGLFINISHPROC, Finish)                                   \
    X(PFNGLREADPIXELSPROC, ReadPixels)                           \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                           \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                         \
    X(PFNGLCREATESHADERPROC, CreateShader)                       \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                       \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                     \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                         \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)               \
    X(PFNGLDELETESHADERPROC, DeleteShader)                       \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                     \
    X(PFNGLATTACHSHADERPROC, AttachShader)                       \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                         \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                       \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)             \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                     \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                           \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)           \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                             \
    X(PFNGLUNIFORM1UIPROC, Uniform1ui)                           \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                             \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                             \
    X(PFNGLUNIFORM3FPROC, Uniform3f)                             \
    X(PFNGLUNIFORM4FPROC, Uniform4f)                             \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv)                           \
    X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)               \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)               \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                 \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                 \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)           \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                           \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                           \
    X(PFNGLBUFFERDATAPROC, BufferData)                           \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                   \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                     \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)         \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray) \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)                       \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                           \
    X(PFNGLGENTEXTURESPROC, GenTextures)                         \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                         \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                     \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                           \
    X(PFNGLTEXSTORAGE2DPROC, TexStorage2D)                       \
    X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                     \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                     \
    X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap)                   \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                   \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                 \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                 \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)       \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)   \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                         \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)           \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)               \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)               \
    X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)         \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer) \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)         \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)

namespace pbrlab::gl {

#define PBRLAB_GL_DECLARE(type, name) extern type name;
PBRLAB_GL_FUNCTIONS(PBRLAB_GL_DECLARE)
#undef PBRLAB_GL_DECLARE

using GetProcAddress = void* (*)(const char* name);

// Resolves every entry point above; throws pbrlab::Error naming the first one missing.
void loadFunctions(GetProcAddress getProc);

// Throws pbrlab::Error with `what` and the GL error name when glGetError reports one.
void checkError(const char* what);

}  // namespace pbrlab::gl
