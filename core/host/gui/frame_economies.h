// What the window leaves out to keep its frames near 30 a second where a CPU draws them
// (llvmpipe on a desktop without a GPU, SwiftShader in a page), in one place with one switch.
// Each was measured to matter there (docs/speed.md, "The GUI on a CPU rasteriser"); a real GPU
// needs none of them. With the switch off (`pbrlab gui --no-frame-economies`) every frame goes
// the same way with each economy at its plain value: the live picture at full size with exact
// spheres, the evaluation's draws in one piece, the whole window drawn, no frame skipped.
#pragma once

namespace pbrlab {

struct FrameEconomies {
    bool on = true;

    // The live picture's side follows a time budget while the input moves (live_size.h): at
    // full size the costliest view, irradiance, takes seconds a frame on llvmpipe.
    bool liveSize() const { return on; }
    // Live pictures draw spheres with as few segments as keep the outline within half a pixel
    // (RenderRequest::coarseSpheres); the settled picture's are exact.
    bool coarseLiveSpheres() const { return on; }
    // The evaluation thread's draws go in bands of rows that take at most this long
    // (gl::setDrawBudgetOnThisThread; 0: one draw). llvmpipe's rasterizer is shared with the
    // window's context, and the window's frame, 4-5 ms of its own, waits about this much at
    // most instead of a 512x512 evaluation, inside the 33 ms of a frame at 30 a second.
    double evaluationDrawMs() const { return on ? 8 : 0; }
    // The window is drawn only where this frame differs from the last (redraw.h): SwiftShader
    // fills every pixel of every frame, and ImGui's panels cost about 10 ms of a 28 ms frame at
    // 1280x720 while the picture orbits (docs/web.md, "Orbiting").
    bool partialRedraw() const { return on; }
    // A page draws its window 4 times a second while nothing on screen changes
    // (platform::skipsQuietFrames; the desktop draws every frame, with vsync): a grade in the
    // page's worker took 3x as long beside a window drawn 25 times a second.
    bool quietFrames() const { return on; }
};

}  // namespace pbrlab
