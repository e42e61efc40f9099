// An image on the CPU: float pixels plus what the file said about them. Reading and writing
// files is the host's (core/assets/image_io.h).
#pragma once

#include <cstddef>
#include <vector>

namespace pbrlab {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;
    // Row 0 is the top row of the picture (as in files; OpenGL read-back is flipped on copy).
    std::vector<float> pixels;  // width * height * channels, channel-interleaved

    // What the source file held, so loaders can honour it (not used when writing).
    int sourceBitsPerChannel = 32;  // 8, 16 or 32
    bool sourceIsSrgb = false;      // colour-space metadata, or an 8-bit PNG/JPEG without any

    float& at(int x, int y, int c) { return pixels[(size_t(y) * width + x) * channels + c]; }
    float at(int x, int y, int c) const { return pixels[(size_t(y) * width + x) * channels + c]; }
};

}  // namespace pbrlab
