// The window drawn only where it changed (core/host/gui/redraw.h), on the CPU: which tiles a
// change marks, and that the restricted commands' scissors are exactly the rectangles. That the
// frames drawn so are the frames drawn whole, pixel for pixel through ImGui's OpenGL backend,
// is Gui.OrbitRedrawsOnlyWhatChanged (--check-redraw) and the site test's check in a page.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "gui/redraw.h"

using namespace pbrlab;

namespace {

// An ImDrawData over one list of commands, as ImGui hands it to the backend.
struct OneList {
    ImDrawList list{nullptr};
    ImDrawList* lists[1] = {&list};
    ImDrawData data;
    OneList(ImVec2 displayPos, ImVec2 displaySize, ImVec2 scale) {
        data.Valid = true;
        data.CmdLists = lists;
        data.CmdListsCount = 1;
        data.DisplayPos = displayPos;
        data.DisplaySize = displaySize;
        data.FramebufferScale = scale;
    }
    // A command drawing one triangle with these corners (display coordinates).
    void addTriangle(ImVec2 a, ImVec2 b, ImVec2 c, ImVec4 clip) {
        ImDrawCmd cmd;
        cmd.ClipRect = clip;
        cmd.IdxOffset = unsigned(list.IdxBuffer.Size);
        cmd.VtxOffset = unsigned(list.VtxBuffer.Size);
        cmd.ElemCount = 3;
        for (ImVec2 p : {a, b, c}) {
            ImDrawVert v{};
            v.pos = p;
            list.IdxBuffer.push_back(ImDrawIdx(list.VtxBuffer.Size - int(cmd.VtxOffset)));
            list.VtxBuffer.push_back(v);
        }
        list.CmdBuffer.push_back(cmd);
    }
};

// An ImGui context without a backend: a frame's draw data is made on the CPU.
class ImGuiFrames {
public:
    explicit ImGuiFrames(ImVec2 size) {
        ImGui::CreateContext();
        ImGuiIO& io = ImGui::GetIO();
        io.IniFilename = nullptr;
        io.DisplaySize = size;
        unsigned char* pixels = nullptr;
        int w = 0, h = 0;
        io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);
        io.Fonts->SetTexID(kFont);
    }
    ~ImGuiFrames() { ImGui::DestroyContext(); }
    // One frame: a window of static text, one line that says `line`, and, when `image`, a
    // picture (another texture) at 200x200; its bounds are pictureMin/Max.
    ImDrawData& frame(const std::string& line, bool image) {
        ImGuiIO& io = ImGui::GetIO();
        io.DeltaTime = 1.0f / 60;
        ImGui::NewFrame();
        ImGui::SetNextWindowPos(ImVec2(0, 0));
        ImGui::SetNextWindowSize(io.DisplaySize);
        ImGui::Begin("window", nullptr, ImGuiWindowFlags_NoDecoration);
        for (int i = 0; i < 20; ++i) ImGui::Text("a line that stays the same, number %d", i);
        ImGui::TextUnformatted(line.c_str());
        lineMin = ImGui::GetItemRectMin();
        lineMax = ImGui::GetItemRectMax();
        if (image) {
            ImGui::Image(kPicture, ImVec2(200, 200));
            pictureMin = ImGui::GetItemRectMin();
            pictureMax = ImGui::GetItemRectMax();
        }
        ImGui::Text("and a line under it");
        ImGui::End();
        ImGui::Render();
        return *ImGui::GetDrawData();
    }
    static inline const ImTextureID kFont = reinterpret_cast<ImTextureID>(std::intptr_t(1));
    static inline const ImTextureID kPicture = reinterpret_cast<ImTextureID>(std::intptr_t(7));
    ImVec2 lineMin, lineMax, pictureMin, pictureMax;
};

long long areaOf(const std::vector<PixelRect>& rects) {
    long long area = 0;
    for (const PixelRect& r : rects) area += r.area();
    return area;
}

// Every pixel of [lo, hi) lies in one of the rectangles.
bool covers(const std::vector<PixelRect>& rects, ImVec2 lo, ImVec2 hi) {
    for (int y = int(lo.y); y < int(hi.y); ++y)
        for (int x = int(lo.x); x < int(hi.x); ++x) {
            bool in = false;
            for (const PixelRect& r : rects) in |= x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1;
            if (!in) return false;
        }
    return true;
}

}  // namespace

// For clip rectangles anywhere between pixels, at the scales of common displays (1, 1.25,
// 1.5, 2) and with the display not at the origin: each part of a restricted command is drawn
// with exactly its rectangle's share of the command's scissor, and no part is empty or lost.
TEST(Redraw, RestrictedCommandsDrawExactlyTheirShareOfTheScissor) {
    std::mt19937 random(12345);
    std::uniform_real_distribution<float> coordinate(-20.0f, 700.0f);
    std::uniform_int_distribution<int> pixel(0, 640);
    for (ImVec2 scale : {ImVec2(1, 1), ImVec2(1.25f, 1.25f), ImVec2(1.5f, 1.5f), ImVec2(2, 2)})
        for (ImVec2 pos : {ImVec2(0, 0), ImVec2(3.5f, -7.25f)})
            for (int trial = 0; trial < 500; ++trial) {
                OneList one(pos, ImVec2(640 / scale.x, 480 / scale.y), scale);
                const PixelRect framebuffer = framebufferRect(one.data);
                const float x0 = coordinate(random), x1 = coordinate(random);
                const float y0 = coordinate(random), y1 = coordinate(random);
                // A triangle over the whole display: every rectangle the scissor meets draws it.
                one.addTriangle(
                    ImVec2(-1000, -1000), ImVec2(5000, -1000), ImVec2(-1000, 5000),
                    ImVec4(std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)));
                const ImDrawCmd cmd = one.list.CmdBuffer[0];
                const PixelRect scissor = backendScissor(cmd, one.data);
                // Two disjoint rectangles: a vertical cut through a random one.
                const int a = pixel(random), b = pixel(random), cut = pixel(random);
                const int top = std::min(a, b) % framebuffer.y1;
                const int bottom = std::min(std::max(a, b), framebuffer.y1);
                const std::vector<PixelRect> rects = {{0, top, cut, bottom},
                                                      {cut, top, framebuffer.x1, bottom}};
                restrictDrawData(one.data, rects);
                size_t part = 0;
                for (const PixelRect& rect : rects) {
                    const PixelRect expected = scissor.intersect(rect);
                    if (expected.empty()) continue;
                    ASSERT_LT(part, size_t(one.list.CmdBuffer.size()));
                    EXPECT_EQ(backendScissor(one.list.CmdBuffer[int(part)], one.data), expected)
                        << "scale " << scale.x << " trial " << trial;
                    EXPECT_EQ(one.list.CmdBuffer[int(part)].ElemCount, 3u);
                    ++part;
                }
                EXPECT_EQ(part, size_t(one.list.CmdBuffer.size()));
            }
}

// A rectangle that no triangle of a command touches gets no part of it; one that some touch
// gets those only.
TEST(Redraw, ARectangleDrawsOnlyTheTrianglesThatTouchIt) {
    OneList one(ImVec2(0, 0), ImVec2(256, 128), ImVec2(1, 1));
    const ImVec4 everywhere(0, 0, 256, 128);
    one.addTriangle(ImVec2(10, 10), ImVec2(50, 10), ImVec2(10, 50), everywhere);     // left
    one.addTriangle(ImVec2(200, 10), ImVec2(250, 10), ImVec2(200, 60), everywhere);  // right
    // The two triangles as one command, as ImGui merges draws with one texture and clip.
    ImDrawCmd both = one.list.CmdBuffer[0];
    both.ElemCount = 6;
    for (int i = 3; i < 6; ++i) one.list.IdxBuffer[i] = ImDrawIdx(one.list.IdxBuffer[i] + 3);
    one.list.CmdBuffer.clear();
    one.list.CmdBuffer.push_back(both);
    restrictDrawData(one.data, {{0, 0, 64, 64}, {64, 64, 128, 128}, {192, 0, 256, 64}});
    ASSERT_EQ(one.list.CmdBuffer.Size, 2);
    for (int part = 0; part < 2; ++part) {
        const ImDrawCmd& cmd = one.list.CmdBuffer[part];
        EXPECT_EQ(cmd.ElemCount, 3u);
        const ImDrawIdx first = one.list.IdxBuffer[int(cmd.IdxOffset)];
        EXPECT_EQ(one.list.VtxBuffer[int(cmd.VtxOffset + first)].pos.x, part == 0 ? 10.0f : 200.0f);
    }
}

TEST(Redraw, OnlyTheTilesWhoseTrianglesChangedAreDrawnAgain) {
    const ImVec2 size(800, 600);
    ImGuiFrames frames(size);
    FrameDamage damage;
    const long long window = 800 * 600;
    // The first frame: all of it.
    std::vector<PixelRect> rects = damage.update(frames.frame("1111.1", false), ImGuiFrames::kFont);
    ASSERT_EQ(rects.size(), 1u);
    EXPECT_EQ(rects[0], (PixelRect{0, 0, 800, 600}));
    // The same frame again: nothing.
    EXPECT_TRUE(damage.update(frames.frame("1111.1", false), ImGuiFrames::kFont).empty());
    // One line's text changed (every glyph of it): its tiles, a small part of the window.
    rects = damage.update(frames.frame("2222.2", false), ImGuiFrames::kFont);
    EXPECT_FALSE(rects.empty());
    EXPECT_TRUE(covers(rects, frames.lineMin, frames.lineMax));
    EXPECT_LT(areaOf(rects), window / 20);
    // A picture appears: its tiles (it pushes the line under it down, which is drawn again).
    rects = damage.update(frames.frame("2222.2", true), ImGuiFrames::kFont);
    EXPECT_TRUE(covers(rects, frames.pictureMin, frames.pictureMax));
    // The same frame again: the picture's texels may have changed, so its tiles, and only
    // them: 200x200 in whole tiles of 32 is at most 8x8 tiles.
    rects = damage.update(frames.frame("2222.2", true), ImGuiFrames::kFont);
    EXPECT_TRUE(covers(rects, frames.pictureMin, frames.pictureMax));
    EXPECT_LE(areaOf(rects), 8 * 8 * FrameDamage::kTile * FrameDamage::kTile);
    // A new size, and after invalidate(): all of it.
    ImGui::GetIO().DisplaySize = ImVec2(640, 600);
    rects = damage.update(frames.frame("2222.2", true), ImGuiFrames::kFont);
    ASSERT_EQ(rects.size(), 1u);
    EXPECT_EQ(rects[0], (PixelRect{0, 0, 640, 600}));
    damage.invalidate();
    rects = damage.update(frames.frame("2222.2", true), ImGuiFrames::kFont);
    ASSERT_EQ(rects.size(), 1u);
    EXPECT_EQ(rects[0], (PixelRect{0, 0, 640, 600}));
}
