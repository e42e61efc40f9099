#include "gl/objects.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <thread>

#include "util/error.h"

namespace pbrlab::gl {

Handle makeTexture() {
    GLuint id = 0;
    GenTextures(1, &id);
    return {id, [](GLuint i) { DeleteTextures(1, &i); }};
}
Handle makeBuffer() {
    GLuint id = 0;
    GenBuffers(1, &id);
    return {id, [](GLuint i) { DeleteBuffers(1, &i); }};
}
Handle makeVertexArray() {
    GLuint id = 0;
    GenVertexArrays(1, &id);
    return {id, [](GLuint i) { DeleteVertexArrays(1, &i); }};
}
Handle makeFramebuffer() {
    GLuint id = 0;
    GenFramebuffers(1, &id);
    return {id, [](GLuint i) { DeleteFramebuffers(1, &i); }};
}
Handle makeRenderbuffer() {
    GLuint id = 0;
    GenRenderbuffers(1, &id);
    return {id, [](GLuint i) { DeleteRenderbuffers(1, &i); }};
}

Handle uploadTexture(const Image& image, bool mipmaps, GLenum internalFormat) {
    static const GLenum formats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    static const GLenum floatFormats[] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
    if (image.channels < 1 || image.channels > 4 || image.width <= 0 || image.height <= 0)
        throw Error("cannot upload an image of " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + "x" + std::to_string(image.channels));
    if (kWebGl2 && image.channels == 3 && mipmaps && !internalFormat) {
        // WebGL 2 cannot render into RGB32F, so it builds no mipmaps of it: RGBA32F instead
        // (alpha 1; the shaders read .rgb).
        Image rgba;
        rgba.width = image.width;
        rgba.height = image.height;
        rgba.channels = 4;
        rgba.pixels.resize(size_t(image.width) * size_t(image.height) * 4, 1.0f);
        for (size_t i = 0; i < size_t(image.width) * size_t(image.height); ++i)
            for (size_t c = 0; c < 3; ++c) rgba.pixels[4 * i + c] = image.pixels[3 * i + c];
        return uploadTexture(rgba, mipmaps, internalFormat);
    }
    Handle texture = makeTexture();
    BindTexture(GL_TEXTURE_2D, texture.id());
    PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Image row 0 goes to t = 0: with glTF's uv convention (v = 0 at the image top) the
    // picture comes out upright without flipping.
    const GLint format = GLint(internalFormat ? internalFormat : floatFormats[image.channels - 1]);
    TexImage2D(GL_TEXTURE_2D, 0, format, image.width, image.height, 0, formats[image.channels - 1],
               GL_FLOAT, image.pixels.data());
    // The mip chain on the CPU, not glGenerateMipmap: llvmpipe and SwiftShader build it by
    // drawing each level with a shader they compile first, which cost 30 to 80 ms a texture
    // (more than a 256^2 picture's whole draw); the box filter here takes about a millisecond.
    if (mipmaps) {
        Image level = halfSize(image);
        for (GLint mip = 1;; ++mip) {
            TexImage2D(GL_TEXTURE_2D, mip, format, level.width, level.height, 0,
                       formats[image.channels - 1], GL_FLOAT, level.pixels.data());
            if (level.width == 1 && level.height == 1) break;
            level = halfSize(level);
        }
    }
    TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER,
                  mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST);
    TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, mipmaps ? GL_LINEAR : GL_NEAREST);
    TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    checkError("uploading a texture");
    return texture;
}

RenderTarget::RenderTarget(int width, int height, int colorCount, bool withDepth)
    : width_(width), height_(height) {
    framebuffer_ = makeFramebuffer();
    BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    for (int i = 0; i < colorCount; ++i) {
        Handle tex = makeTexture();
        BindTexture(GL_TEXTURE_2D, tex.id());
        TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
        TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, tex.id(), 0);
        colors_.push_back(std::move(tex));
    }
    if (withDepth) {
        depth_ = makeRenderbuffer();
        BindRenderbuffer(GL_RENDERBUFFER, depth_.id());
        RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
        FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.id());
    }
    if (CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("render target " + std::to_string(width) + "x" + std::to_string(height) +
                    " with " + std::to_string(colorCount) + " RGBA32F attachments is incomplete");
    checkError("creating a render target");
}

void RenderTarget::bind() const {
    BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    Viewport(0, 0, width_, height_);
    std::vector<GLenum> buffers;
    for (size_t i = 0; i < colors_.size(); ++i) buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
    DrawBuffers(GLsizei(buffers.size()), buffers.data());
}

Image RenderTarget::read(int i) const {
    Image image;
    image.width = width_;
    image.height = height_;
    image.channels = 4;
    image.pixels.resize(size_t(width_) * height_ * 4);
    BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.id());
    ReadBuffer(GL_COLOR_ATTACHMENT0 + i);
    PixelStorei(GL_PACK_ALIGNMENT, 1);
    ReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, image.pixels.data());
    checkError("reading back a render target");
    return flipRows(std::move(image));
}

GpuMesh::GpuMesh(const MeshData& mesh) : indexCount_(GLsizei(mesh.indices.size())) {
    vertexArray_ = makeVertexArray();
    vertices_ = makeBuffer();
    indices_ = makeBuffer();
    BindVertexArray(vertexArray_.id());
    BindBuffer(GL_ARRAY_BUFFER, vertices_.id());
    BufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertices.size() * sizeof(Vertex)),
               mesh.vertices.data(), GL_STATIC_DRAW);
    BindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.id());
    BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
               mesh.indices.data(), GL_STATIC_DRAW);
    struct Attribute {
        GLint size;
        size_t offset;
    };
    const Attribute attributes[] = {{3, offsetof(Vertex, position)},
                                    {3, offsetof(Vertex, normal)},
                                    {2, offsetof(Vertex, uv)},
                                    {4, offsetof(Vertex, tangent)}};
    for (GLuint i = 0; i < 4; ++i) {
        EnableVertexAttribArray(i);
        VertexAttribPointer(i, attributes[i].size, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                            reinterpret_cast<const void*>(attributes[i].offset));
    }
    BindVertexArray(0);
    checkError("uploading a mesh");
}

void GpuMesh::draw() const {
    BindVertexArray(vertexArray_.id());
    DrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
}

namespace {

thread_local double drawBudgetMs = 0;

}  // namespace

void setDrawBudgetOnThisThread(double ms) {
    drawBudgetMs = ms;
}

int nextBandRows(int rows, double ms, double budgetMs) {
    const double fits = rows * budgetMs / std::max(ms, 1e-3);
    return std::max(2, int(std::min(fits, std::max(1.5 * rows, rows + 2.0))) / 2 * 2);
}

int FullscreenTriangle::draw() const {
    BindVertexArray(vertexArray_.id());
    if (drawBudgetMs <= 0) {
        DrawArrays(GL_TRIANGLES, 0, 3);
        return 1;
    }
    GLint viewport[4] = {0, 0, 0, 0};
    GetIntegerv(GL_VIEWPORT, viewport);
    GLint scissorBox[4] = {0, 0, 0, 0};
    GetIntegerv(GL_SCISSOR_BOX, scissorBox);
    const GLboolean scissorWas = IsEnabled(GL_SCISSOR_TEST);
    Enable(GL_SCISSOR_TEST);
    Finish();  // what came before is not this draw's to time
    // Bands of an even number of rows, starting on even rows: the 2x2 quads that derivatives
    // read are never split. The first is small, for a program whose cost is not known yet
    // (its first draw also compiles it, on llvmpipe); each next one nextBandRows.
    int rows = 16, draws = 0;
    for (int y = 0; y < viewport[3]; ++draws) {
        rows = std::min(rows, viewport[3] - y);
        Scissor(viewport[0], viewport[1] + y, viewport[2], rows);
        const auto start = std::chrono::steady_clock::now();
        DrawArrays(GL_TRIANGLES, 0, 3);
        Finish();
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        y += rows;
        // A context waiting for the rasterizer takes it now: a mutex is not handed over in
        // order, and this thread could take it again before the waiting one runs.
        if (y < viewport[3]) std::this_thread::sleep_for(std::chrono::milliseconds(1));
        rows = nextBandRows(rows, ms, drawBudgetMs);
    }
    Scissor(scissorBox[0], scissorBox[1], scissorBox[2], scissorBox[3]);
    if (!scissorWas) Disable(GL_SCISSOR_TEST);
    return draws;
}

void setSeamlessCubeFiltering(bool on) {
    if (kWebGl2) return;
    if (on)
        Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    else
        Disable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
}

}  // namespace pbrlab::gl
