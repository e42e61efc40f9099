// The window drawn over its last frame, only where this frame draws something else.
//
// While the mouse orbits the picture, the rest of the window (the steps' list, the module's
// panel, the handout, most of the view's text) is the frame before's, pixel for pixel. In a
// page, SwiftShader (the browser's GPU drawn on the CPU) fills every pixel of every frame:
// ImGui's panels cost about 10 ms of a 28 ms frame at 1280x720 (docs/web.md, "Orbiting").
// Redrawing only the tiles whose triangles changed leaves that out, and says how much it
// drew (RedrawStats: the status JSON's "redraw", --orbit's report).
#pragma once

#include <imgui.h>

#include <cstdint>
#include <vector>

#include "gl/objects.h"

namespace pbrlab {

// A rectangle of framebuffer pixels, rows counted from the top: [x0, x1) x [y0, y1).
struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    long long area() const { return empty() ? 0 : (long long)(x1 - x0) * (y1 - y0); }
    PixelRect intersect(const PixelRect& o) const;
    bool operator==(const PixelRect&) const = default;
};

// The framebuffer's size for this draw data, as ImGui's OpenGL 3 backend computes it.
PixelRect framebufferRect(const ImDrawData& data);

// The scissor ImGui's OpenGL 3 backend (1.86) draws `cmd` with: its ClipRect scaled to the
// framebuffer and truncated to integers as the backend truncates it (empty: not drawn).
PixelRect backendScissor(const ImDrawCmd& cmd, const ImDrawData& data);

// Which pixels this frame's draw data draws differently from the last frame's. Per tile of
// kTile x kTile pixels, a hash of the triangles that touch it in the order they are drawn (their
// vertices, texture and scissor): a tile whose hash is the last frame's is drawn the same,
// because a triangle touches no pixel outside its bounds and its scissor. A texture other than
// `fixedTexture` (the font's) can change its texels while its triangles stay (the live picture,
// drawn anew each frame): the tiles it touches are redrawn every frame.
class FrameDamage {
public:
    static constexpr int kTile = 32;
    // The rectangles to draw again, disjoint, in tiles clipped to the framebuffer: none when
    // nothing changed; the whole framebuffer on the first frame, after a resize or
    // invalidate(), when a command is a callback (its pixels are not known), or when the
    // changed tiles would need more than kMostRects rectangles or cover more than
    // kWholeFraction of the framebuffer (then one draw is cheaper than several).
    std::vector<PixelRect> update(const ImDrawData& data, ImTextureID fixedTexture);
    void invalidate() { tiles_.clear(); }
    static constexpr int kMostRects = 24;
    static constexpr double kWholeFraction = 0.6;

private:
    PixelRect framebuffer_;
    std::vector<std::uint64_t> tiles_;  // the last frame's hashes, row by row
};

// The draw data restricted to `rects` (disjoint): each command repeated once for each rectangle
// its scissor meets, with only its triangles that touch the rectangle (their indices appended to
// the list's) and its ClipRect chosen so that the backend's scissor is exactly the
// intersection. Drawn over the last frame (the rectangles cleared first), it gives the frame the
// whole draw data gives.
void restrictDrawData(ImDrawData& data, const std::vector<PixelRect>& rects);

// What the window's redraws drew (the status JSON's "redraw", --orbit's report).
struct RedrawStats {
    long long framesDrawn = 0;      // frames with any pixel drawn
    long long framesInPart = 0;     // of which drawn only where they changed
    long long framesUnchanged = 0;  // frames with nothing to draw
    double lastFraction = 1;        // of the window's pixels, the last frame drawn
    std::vector<double> fractions;  // each frame's, for --orbit's median
    // --check-redraw: frames also drawn whole and compared, and the pixels that differed.
    long long framesChecked = 0, pixelsDiffering = 0;
};

// The window's frames, drawn over the last one. The last frame is kept in the window's own
// framebuffer where it keeps its pixels (a page's canvas made with preserveDrawingBuffer,
// shell.html); elsewhere (a desktop's back buffer is undefined after a swap) in an RGBA8
// framebuffer of this class's, copied to the window after each frame.
class WindowRedraw {
public:
    // `partial`: false draws every frame whole (FrameEconomies::partialRedraw).
    WindowRedraw(bool windowKeepsItsPixels, bool partial)
        : windowKeeps_(windowKeepsItsPixels), partial_(partial) {}
    // Draws ImGui's draw data of this frame (after ImGui::Render) where it changed: the
    // rectangles cleared to `background`, then the commands restricted to them.
    void draw(ImDrawData& data, ImTextureID fontTexture, const ImVec4& background);
    // Also draw each frame whole into a framebuffer of its own and count the pixels where the
    // two differ (RedrawStats::pixelsDiffering): a check, at the cost of a second draw and two
    // read-backs a frame.
    void setChecking(bool on) { checking_ = on; }
    void invalidate() { damage_.invalidate(); }
    const RedrawStats& stats() const { return stats_; }

private:
    struct Target {
        gl::Handle framebuffer, texture;
        int width = 0, height = 0;
        void resize(int w, int h);  // RGBA8, made again when the size changes
    };
    FrameDamage damage_;
    bool windowKeeps_, partial_;
    Target kept_, whole_;  // kept_: unless windowKeeps_; whole_: when checking
    bool checking_ = false;
    RedrawStats stats_;
};

}  // namespace pbrlab
