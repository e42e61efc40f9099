// The live picture's side while the input moves (dynamic resolution, as Blender's and
// Unreal's viewports do): it shrinks while its frames take longer than the budget and grows
// back while they take much less, so that dragging stays at 30 frames a second or more
// whatever the step costs per pixel. The settled picture is always full size.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "gl/objects.h"

namespace pbrlab {

// Whether a live frame's time is what its picture costs, for the live size to follow. Not in a
// browser's WebGL 2: there the frame's first GL query waits for the GPU process to finish
// everything queued before it, the previous frame's panels and the page's compositing included,
// and glFinish returns at once (in headless Chromium a live frame measured 16-32 ms at any side
// from 16 to 176 pixels, so every frame looked over the budget and the picture shrank to 16
// pixels in every drag).
constexpr bool kLiveFramesTimed = !gl::kWebGl2;

class LiveSize {
public:
    // The picture's time budget, of the 33 ms a frame at 30 a second has: the rest of a frame
    // takes about 10 ms at the default window size on llvmpipe (the panels 4, the picture's
    // quad 4, the clear 1), 11 at 1920x1080, more while other processes share the cores.
    static constexpr double kBudgetMs = 15;
    // Low enough for the costliest view: irradiance sums 6144 texels a pixel, seconds at 512
    // and about 27 ms of one core at 32 (a picture within one of llvmpipe's 64-pixel tiles is
    // drawn by one thread).
    static constexpr int kMinSide = 16;

    // `framesTimed`: whether a live frame's time is the picture's. In a browser it is not (see
    // kLiveFramesTimed): there the side stays between half and all of the side that the
    // settled picture's cost allows, and the frames move it only within that range.
    // `shrinks`: false keeps the full side whatever the frames take
    // (FrameEconomies::liveSize).
    explicit LiveSize(int fullSide, bool framesTimed = true, bool shrinks = true)
        : full_(fullSide), side_(fullSide), framesTimed_(framesTimed), shrinks_(shrinks) {}

    int side() const { return side_; }
    // Full size again: another step, another cost.
    void reset() {
        side_ = ceiling_ = full_;
        floor_ = kMinSide;
        window_.clear();
    }
    // The view took `ms` at full size, its read-back included (the settled frame measures it;
    // in a browser glFinish returns before the GPU has drawn, and only the read-back waits):
    // the next drag starts at a side that fits, not with seconds-long frames at full size.
    // Without timed frames this measure is the only one to trust: the picture then costs the
    // budget at most and a quarter of it at least (half the side), whatever the frames say.
    void fullSizeTook(double ms) {
        if (!shrinks_) return;
        const int fits = sideWithin(full_, ms);
        if (framesTimed_) {
            side_ = std::min(side_, fits);
            return;
        }
        side_ = ceiling_ = fits;
        floor_ = std::max(kMinSide, roundDown(fits / 2.0));
        window_.clear();
    }
    // A live frame at side() took `ms` (frames that compiled or precomputed left out: they
    // say nothing about what the picture costs). Resized at most every 4 frames, from their
    // median (a new size reallocates the targets, and the frames where llvmpipe's threads
    // lose the cores to another process are not what the picture costs), with a gap between
    // shrink and grow; at once after two frames far over the budget, to the side that would
    // have fitted.
    void frameTook(double ms) {
        if (!shrinks_) return;
        window_.push_back(ms);
        const size_t n = window_.size();
        if (n >= 2 && std::min(window_[n - 2], window_[n - 1]) > 2 * kBudgetMs) {
            side_ = std::max(floor_, sideWithin(side_, std::min(window_[n - 2], window_[n - 1])));
            window_.clear();
            return;
        }
        if (n < 4) return;
        std::sort(window_.begin(), window_.end());
        const double median = (window_[1] + window_[2]) / 2;
        window_.clear();
        if (median > kBudgetMs)
            side_ = std::max(floor_, std::min(roundDown(side_ * 0.8), sideWithin(side_, median)));
        else if (median < 0.4 * kBudgetMs)
            side_ = std::min(ceiling_, std::max(side_ + 8, roundDown(side_ * 1.25)));
    }

private:
    static int roundDown(double side) { return int(side) / 8 * 8; }
    // The side at which a picture that took `ms` at `side` would take the budget: its cost
    // is mostly per pixel, so the side goes with the square root.
    int sideWithin(int side, double ms) const {
        return std::clamp(roundDown(side * std::sqrt(kBudgetMs / std::max(ms, 1e-3))), kMinSide,
                          full_);
    }

    int full_, side_;
    bool framesTimed_, shrinks_;
    int floor_ = kMinSide, ceiling_ = full_;  // the sides the frames may choose from
    std::vector<double> window_;              // the live frames' times since the last resize
};

}  // namespace pbrlab
