// The live picture's side while the input moves (dynamic resolution, as Blender's and
// Unreal's viewports do): it shrinks while its frames take longer than the budget and grows
// back while they take much less, so that dragging stays at 30 frames a second or more
// whatever the step costs per pixel. The settled picture is always full size.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace pbrlab {

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

    explicit LiveSize(int fullSide) : full_(fullSide), side_(fullSide) {}

    int side() const { return side_; }
    // Full size again: another step, another cost.
    void reset() {
        side_ = full_;
        window_.clear();
    }
    // The view took `ms` at full size, its read-back included (the settled frame measures it;
    // in a browser glFinish returns before the GPU has drawn, and only the read-back waits):
    // the next drag starts at a side that fits, not with seconds-long frames at full size.
    void fullSizeTook(double ms) { side_ = std::min(side_, sideWithin(full_, ms)); }
    // A live frame at side() took `ms` (frames that compiled or precomputed left out: they
    // say nothing about what the picture costs). Resized at most every 4 frames, from their
    // median (a new size reallocates the targets, and the frames where llvmpipe's threads
    // lose the cores to another process are not what the picture costs), with a gap between
    // shrink and grow; at once after two frames far over the budget, to the side that would
    // have fitted.
    void frameTook(double ms) {
        window_.push_back(ms);
        const size_t n = window_.size();
        if (n >= 2 && std::min(window_[n - 2], window_[n - 1]) > 2 * kBudgetMs) {
            side_ = sideWithin(side_, std::min(window_[n - 2], window_[n - 1]));
            window_.clear();
            return;
        }
        if (n < 4) return;
        std::sort(window_.begin(), window_.end());
        const double median = (window_[1] + window_[2]) / 2;
        window_.clear();
        if (median > kBudgetMs)
            side_ = std::max(kMinSide, std::min(roundDown(side_ * 0.8), sideWithin(side_, median)));
        else if (median < 0.4 * kBudgetMs)
            side_ = std::min(full_, std::max(side_ + 8, roundDown(side_ * 1.25)));
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
    std::vector<double> window_;  // the live frames' times since the last resize
};

}  // namespace pbrlab
