// Small RAII owners for OpenGL objects (no glDelete* anywhere else), float render targets
// with read-back, and meshes on the GPU.
#pragma once

#include <utility>
#include <vector>

#include "assets/image_io.h"
#include "assets/mesh.h"
#include "gl/gl.h"

namespace pbrlab::gl {

// Owns one GL object name; moves, never copies.
class Handle {
public:
    using Deleter = void (*)(GLuint);
    Handle() = default;
    Handle(GLuint id, Deleter deleter) : id_(id), deleter_(deleter) {}
    Handle(Handle&& other) noexcept { *this = std::move(other); }
    Handle& operator=(Handle&& other) noexcept {
        if (this != &other) {
            reset();
            std::swap(id_, other.id_);
            std::swap(deleter_, other.deleter_);
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;
    ~Handle() { reset(); }
    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }
    void reset() {
        if (id_ && deleter_) deleter_(id_);
        id_ = 0;
    }

private:
    GLuint id_ = 0;
    Deleter deleter_ = nullptr;
};

Handle makeTexture();
Handle makeBuffer();
Handle makeVertexArray();
Handle makeFramebuffer();
Handle makeRenderbuffer();

// A 2D texture uploaded from an image (1-4 channels, float upload; internal format chosen
// from the channel count: R32F, RG32F, RGB32F or RGBA32F unless `internalFormat` is given).
// With `mipmaps`, every level down to 1x1, each made by halfSize from the one above.
Handle uploadTexture(const Image& image, bool mipmaps, GLenum internalFormat = 0);

// Off-screen target: `colorCount` RGBA32F attachments plus a depth buffer.
class RenderTarget {
public:
    RenderTarget(int width, int height, int colorCount, bool withDepth = true);
    void bind() const;  // binds the framebuffer, sets the viewport, enables all draw buffers
    int width() const { return width_; }
    int height() const { return height_; }
    GLuint colorTexture(int i) const { return colors_[i].id(); }
    // Reads attachment i as RGBA floats, row 0 at the top (GL rows are bottom-up).
    Image read(int i) const;

private:
    int width_, height_;
    Handle framebuffer_, depth_;
    std::vector<Handle> colors_;
};

// A mesh on the GPU: positions (0), normals (1), uvs (2), tangents (3).
class GpuMesh {
public:
    explicit GpuMesh(const MeshData& mesh);
    void draw() const;

private:
    Handle vertexArray_, vertices_, indices_;
    GLsizei indexCount_ = 0;
};

// The longest a fullscreen draw made on this thread may keep the rasterizer (0, the default:
// no limit). llvmpipe rasterizes one submission at a time for every context of the process
// (its rasterizer threads belong to the screen, not to a context), so while the evaluation
// thread's view pass rasterizes, the window's swap waits for it: 177 ms measured for prefilter
// at 128 samples, 512x512. With a budget, FullscreenTriangle::draw draws bands of rows, each
// finished before the next, sized from the band before to take about `ms`: another context
// waits about one band. The pixels are the same (each is shaded once, by the same program).
void setDrawBudgetOnThisThread(double ms);

// This build's GL is a page's WebGL 2 (OpenGL ES 3.0: GLSL ES 3.00, cube maps always seamless).
#ifdef __EMSCRIPTEN__
constexpr bool kWebGl2 = true;
#else
constexpr bool kWebGl2 = false;
#endif

// Whether cube maps are filtered across face edges. WebGL 2's always are (it has no switch):
// there this does nothing, and RendererOptions::seamlessCubesAlways says so to the renderer.
void setSeamlessCubeFiltering(bool on);
// The rows of the next band after one of `rows` took `ms`: as many as fit the budget at that
// cost, even, at least 2, growing at most 1.5 times (or by 2 rows, from 2 or 4): a view's cost
// per row varies across the picture (brdf_lut's at 1024 samples: 0.5-2.5 ms a row), and a band
// that grew 4 times took 45 ms. A band slowed by a compile or another context shrinks the
// next one, which grows back as the draws run at their own cost.
int nextBandRows(int rows, double ms, double budgetMs);

// One triangle covering the viewport (vertex shader: shaders/fullscreen.vert). Core profile
// needs a bound vertex array even when the shader makes up the vertices; it belongs to the
// context that was current at construction.
class FullscreenTriangle {
public:
    FullscreenTriangle() : vertexArray_(makeVertexArray()) {}
    // In bands on a thread with a draw budget (setDrawBudgetOnThisThread), else one draw.
    // Returns the number of draws.
    int draw() const;

private:
    Handle vertexArray_;
};

}  // namespace pbrlab::gl
