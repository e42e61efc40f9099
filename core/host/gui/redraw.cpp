#include "redraw.h"

#include <backends/imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gl/gl.h"
#include "util/error.h"

namespace pbrlab {

namespace {

std::uint64_t mix(std::uint64_t hash, std::uint64_t value) {
    hash ^= value + 0x9e3779b97f4a7c15ULL + (hash << 6) + (hash >> 2);
    return hash * 0x100000001b3ULL;
}

// A vertex's position, uv and colour, as the words the hash reads.
constexpr size_t kVertexWords = sizeof(ImDrawVert) / sizeof(std::uint32_t);
static_assert(sizeof(ImDrawVert) % sizeof(std::uint32_t) == 0);

// The vertex of the command's index number `index` (from cmd.IdxOffset).
const ImDrawVert& vertexOf(const ImDrawList& list, const ImDrawCmd& cmd, unsigned index) {
    return list.VtxBuffer[int(cmd.VtxOffset + list.IdxBuffer[int(cmd.IdxOffset + index)])];
}

// Every pixel whose centre the triangle whose first index is `first` may cover, within the
// command's scissor.
PixelRect triangleBounds(const ImDrawList& list, const ImDrawCmd& cmd, unsigned first,
                         const ImDrawData& data, const PixelRect& scissor) {
    float loX = INFINITY, loY = INFINITY, hiX = -INFINITY, hiY = -INFINITY;
    for (unsigned j = 0; j < 3; ++j) {
        const ImVec2 p = vertexOf(list, cmd, first + j).pos;
        loX = std::min(loX, p.x), hiX = std::max(hiX, p.x);
        loY = std::min(loY, p.y), hiY = std::max(hiY, p.y);
    }
    const ImVec2 off = data.DisplayPos, scale = data.FramebufferScale;
    // Far outside any framebuffer is as good as there, and converts to int.
    auto pixel = [](float v) { return int(std::clamp(v, -1e6f, 1e6f)); };
    return PixelRect{
        pixel(std::floor((loX - off.x) * scale.x)), pixel(std::floor((loY - off.y) * scale.y)),
        pixel(std::ceil((hiX - off.x) * scale.x)), pixel(std::ceil((hiY - off.y) * scale.y))}
        .intersect(scissor);
}

// The longest the fraction list grows (a page draws frames for hours): the older half goes.
constexpr size_t kFractionsKept = 8192;

}  // namespace

PixelRect PixelRect::intersect(const PixelRect& o) const {
    return {std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
}

PixelRect framebufferRect(const ImDrawData& data) {
    return {0, 0, int(data.DisplaySize.x * data.FramebufferScale.x),
            int(data.DisplaySize.y * data.FramebufferScale.y)};
}

PixelRect backendScissor(const ImDrawCmd& cmd, const ImDrawData& data) {
    const ImVec2 off = data.DisplayPos, scale = data.FramebufferScale;
    const int height = framebufferRect(data).y1;
    const ImVec2 lo((cmd.ClipRect.x - off.x) * scale.x, (cmd.ClipRect.y - off.y) * scale.y);
    const ImVec2 hi((cmd.ClipRect.z - off.x) * scale.x, (cmd.ClipRect.w - off.y) * scale.y);
    if (hi.x <= lo.x || hi.y <= lo.y) return {};
    // glScissor(x, y, w, h) as imgui_impl_opengl3.cpp calls it, rows from the bottom.
    const int x = int(lo.x), w = int(hi.x - lo.x);
    const int y = int(float(height) - hi.y), h = int(hi.y - lo.y);
    return {x, height - y - h, x + w, height - y};
}

namespace {

// Each tile's hash of the triangles that touch it, in the order they are drawn, and whether a
// texture other than the fixed one touches it (its texels may change under the same triangles).
struct TileHashes {
    int columns = 0, rows = 0;
    std::vector<std::uint64_t> hashes;
    std::vector<char> texelsMayChange;
    bool callback = false;  // a command is a callback: its pixels are not known
};

TileHashes hashTiles(const ImDrawData& data, const PixelRect& framebuffer, ImTextureID fixedTexture,
                     int tile) {
    TileHashes h;
    h.columns = (framebuffer.x1 + tile - 1) / tile;
    h.rows = (framebuffer.y1 + tile - 1) / tile;
    h.hashes.assign(size_t(h.columns) * size_t(h.rows), 0);
    h.texelsMayChange.assign(h.hashes.size(), 0);
    for (int l = 0; l < data.CmdListsCount; ++l) {
        const ImDrawList& list = *data.CmdLists[l];
        for (const ImDrawCmd& cmd : list.CmdBuffer) {
            if (cmd.UserCallback) {
                h.callback = true;
                continue;
            }
            const PixelRect scissor = backendScissor(cmd, data).intersect(framebuffer);
            if (scissor.empty()) continue;
            const bool fixed = cmd.TextureId == fixedTexture;
            std::uint64_t command = mix(0, reinterpret_cast<std::uintptr_t>(cmd.TextureId));
            for (int v : {scissor.x0, scissor.y0, scissor.x1, scissor.y1})
                command = mix(command, std::uint64_t(v));
            for (unsigned k = 0; k + 2 < cmd.ElemCount; k += 3) {
                const PixelRect bounds = triangleBounds(list, cmd, k, data, scissor);
                if (bounds.empty()) continue;
                std::uint64_t triangle = command;
                for (unsigned j = 0; j < 3; ++j) {
                    std::uint32_t words[kVertexWords];
                    std::memcpy(words, &vertexOf(list, cmd, k + j), sizeof(words));
                    for (std::uint32_t word : words) triangle = mix(triangle, word);
                }
                for (int ty = bounds.y0 / tile; ty <= (bounds.y1 - 1) / tile; ++ty)
                    for (int tx = bounds.x0 / tile; tx <= (bounds.x1 - 1) / tile; ++tx) {
                        const size_t t = size_t(ty) * size_t(h.columns) + size_t(tx);
                        h.hashes[t] = mix(h.hashes[t], triangle);
                        if (!fixed) h.texelsMayChange[t] = 1;
                    }
            }
        }
    }
    return h;
}

// The tiles changed since `last` as rectangles: runs of changed tiles, row by row; a run with
// the same columns as one in the row above extends its rectangle.
std::vector<PixelRect> changedRects(const TileHashes& h, const std::vector<std::uint64_t>& last,
                                    const PixelRect& framebuffer, int tile) {
    std::vector<PixelRect> rects;
    std::vector<size_t> open, nowOpen;
    for (int ty = 0; ty < h.rows; ++ty) {
        nowOpen.clear();
        for (int tx = 0; tx < h.columns;) {
            auto changed = [&](int x) {
                const size_t t = size_t(ty) * size_t(h.columns) + size_t(x);
                return h.texelsMayChange[t] || h.hashes[t] != last[t];
            };
            if (!changed(tx)) {
                ++tx;
                continue;
            }
            const int start = tx;
            while (tx < h.columns && changed(tx)) ++tx;
            const PixelRect run =
                PixelRect{start * tile, ty * tile, tx * tile, (ty + 1) * tile}.intersect(
                    framebuffer);
            auto above = std::find_if(open.begin(), open.end(), [&](size_t i) {
                return rects[i].x0 == run.x0 && rects[i].x1 == run.x1;
            });
            if (above != open.end()) {
                rects[*above].y1 = run.y1;
                nowOpen.push_back(*above);
            } else {
                rects.push_back(run);
                nowOpen.push_back(rects.size() - 1);
            }
        }
        std::swap(open, nowOpen);
    }
    return rects;
}

}  // namespace

std::vector<PixelRect> FrameDamage::update(const ImDrawData& data, ImTextureID fixedTexture) {
    const PixelRect framebuffer = framebufferRect(data);
    if (framebuffer.empty()) return {};
    TileHashes tiles = hashTiles(data, framebuffer, fixedTexture, kTile);
    bool whole =
        !(framebuffer == framebuffer_) || tiles_.size() != tiles.hashes.size() || tiles.callback;
    std::vector<PixelRect> rects;
    if (!whole) {
        rects = changedRects(tiles, tiles_, framebuffer, kTile);
        long long area = 0;
        for (const PixelRect& r : rects) area += r.area();
        whole = rects.size() > size_t(kMostRects) ||
                double(area) > kWholeFraction * double(framebuffer.area());
    }
    framebuffer_ = framebuffer;
    tiles_ = std::move(tiles.hashes);
    if (whole) return {framebuffer};
    return rects;
}

void restrictDrawData(ImDrawData& data, const std::vector<PixelRect>& rects) {
    const ImVec2 off = data.DisplayPos, scale = data.FramebufferScale;
    data.TotalIdxCount = 0;
    for (int l = 0; l < data.CmdListsCount; ++l) {
        ImDrawList& list = *data.CmdLists[l];
        ImVector<ImDrawCmd> restricted;
        for (const ImDrawCmd& cmd : list.CmdBuffer) {
            if (cmd.UserCallback) {  // FrameDamage draws whole with one; kept as it is
                restricted.push_back(cmd);
                continue;
            }
            const PixelRect scissor = backendScissor(cmd, data);
            for (const PixelRect& rect : rects) {
                const PixelRect r = scissor.intersect(rect);
                if (r.empty()) continue;
                // Only the triangles that touch the rectangle: the others would be set up and
                // scissored away, once per rectangle (a software GPU's time).
                ImDrawCmd part = cmd;
                part.IdxOffset = unsigned(list.IdxBuffer.Size);
                part.ElemCount = 0;
                for (unsigned k = 0; k + 2 < cmd.ElemCount; k += 3) {
                    if (triangleBounds(list, cmd, k, data, r).empty()) continue;
                    for (unsigned j = 0; j < 3; ++j) {
                        const ImDrawIdx index = list.IdxBuffer[int(cmd.IdxOffset + k + j)];
                        list.IdxBuffer.push_back(index);  // a copy: push_back may move the buffer
                    }
                    part.ElemCount += 3;
                }
                if (part.ElemCount == 0) continue;
                // The backend truncates: these quarters and halves of a pixel give back exactly
                // r's columns [x0, x1) and rows [y0, y1) (backendScissor), at any scale.
                part.ClipRect = ImVec4((float(r.x0) + 0.25f) / scale.x + off.x,
                                       (float(r.y0) - 0.5f) / scale.y + off.y,
                                       (float(r.x1) + 0.5f) / scale.x + off.x,
                                       (float(r.y1) - 0.25f) / scale.y + off.y);
                restricted.push_back(part);
            }
        }
        // The parts' indices follow the whole frame's, which WindowRedraw's check draws again.
        list.CmdBuffer.swap(restricted);
        data.TotalIdxCount += list.IdxBuffer.Size;
    }
}

void WindowRedraw::Target::resize(int w, int h) {
    if (framebuffer && w == width && h == height) return;
    texture = gl::makeTexture();
    gl::BindTexture(GL_TEXTURE_2D, texture.id());
    gl::TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl::TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    framebuffer = gl::makeFramebuffer();
    gl::BindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    gl::FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture.id(), 0);
    if (gl::CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw Error("the window's kept frame (" + std::to_string(w) + "x" + std::to_string(h) +
                    " RGBA8) is incomplete");
    width = w;
    height = h;
}

void WindowRedraw::draw(ImDrawData& data, ImTextureID fontTexture, const ImVec4& background) {
    const PixelRect framebuffer = framebufferRect(data);
    if (framebuffer.empty()) return;
    if (!windowKeeps_ &&
        (!kept_.framebuffer || kept_.width != framebuffer.x1 || kept_.height != framebuffer.y1)) {
        kept_.resize(framebuffer.x1, framebuffer.y1);
        damage_.invalidate();
    }
    const std::vector<PixelRect> rects =
        partial_ ? damage_.update(data, fontTexture) : std::vector<PixelRect>{framebuffer};
    const bool whole = rects.size() == 1 && rects[0] == framebuffer;
    long long drawn = 0;
    for (const PixelRect& r : rects) drawn += r.area();
    stats_.lastFraction = double(drawn) / double(framebuffer.area());
    if (stats_.fractions.size() >= kFractionsKept)
        stats_.fractions.erase(stats_.fractions.begin(),
                               stats_.fractions.begin() + kFractionsKept / 2);
    stats_.fractions.push_back(stats_.lastFraction);
    if (rects.empty()) {
        ++stats_.framesUnchanged;
    } else {
        ++stats_.framesDrawn;
        stats_.framesInPart += !whole;
    }

    std::vector<ImVector<ImDrawCmd>> wholeCommands;  // the check draws the frame whole too
    if (checking_)
        for (int l = 0; l < data.CmdListsCount; ++l)
            wholeCommands.push_back(data.CmdLists[l]->CmdBuffer);
    const GLuint target = windowKeeps_ ? 0 : kept_.framebuffer.id();
    auto clearAndDraw = [&](GLuint framebufferId, const std::vector<PixelRect>& where) {
        gl::BindFramebuffer(GL_FRAMEBUFFER, framebufferId);
        gl::Viewport(0, 0, framebuffer.x1, framebuffer.y1);
        gl::ClearColor(background.x, background.y, background.z, background.w);
        gl::Enable(GL_SCISSOR_TEST);
        for (const PixelRect& r : where) {
            gl::Scissor(r.x0, framebuffer.y1 - r.y1, r.x1 - r.x0, r.y1 - r.y0);
            gl::Clear(GL_COLOR_BUFFER_BIT);
        }
        gl::Disable(GL_SCISSOR_TEST);
        ImGui_ImplOpenGL3_RenderDrawData(&data);
    };
    if (!rects.empty()) {
        if (!whole) restrictDrawData(data, rects);
        clearAndDraw(target, rects);
    }
    if (checking_) {
        for (int l = 0; l < data.CmdListsCount; ++l)
            data.CmdLists[l]->CmdBuffer.swap(wholeCommands[size_t(l)]);
        whole_.resize(framebuffer.x1, framebuffer.y1);
        clearAndDraw(whole_.framebuffer.id(), {framebuffer});
        auto read = [&](GLuint framebufferId) {
            std::vector<unsigned char> pixels(size_t(framebuffer.area()) * 4);
            gl::BindFramebuffer(GL_FRAMEBUFFER, framebufferId);
            gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
            gl::ReadPixels(0, 0, framebuffer.x1, framebuffer.y1, GL_RGBA, GL_UNSIGNED_BYTE,
                           pixels.data());
            return pixels;
        };
        const std::vector<unsigned char> kept = read(target),
                                         wholeFrame = read(whole_.framebuffer.id());
        for (size_t i = 0; i < kept.size(); i += 4)  // colour only: the window may have no alpha
            stats_.pixelsDiffering += kept[i] != wholeFrame[i] ||
                                      kept[i + 1] != wholeFrame[i + 1] ||
                                      kept[i + 2] != wholeFrame[i + 2];
        ++stats_.framesChecked;
    }
    if (!windowKeeps_) {
        gl::BindFramebuffer(GL_READ_FRAMEBUFFER, kept_.framebuffer.id());
        gl::BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        gl::BlitFramebuffer(0, 0, framebuffer.x1, framebuffer.y1, 0, 0, framebuffer.x1,
                            framebuffer.y1, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace pbrlab
