// The GUI's live view maps values for display on the GPU (DisplayPass); files, reports and the
// settled GUI image map them on the CPU (displayImage). The two must show the same picture.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "gl/context.h"
#include "render/display.h"
#include "render/display_pass.h"
#include "render/renderer.h"

using namespace pbrlab;

namespace {

// Values over every regime a mapping has: below, inside and above [lo, hi], zero, negative,
// large, NaN, Inf, and background (alpha 0).
Image sampleValues() {
    Image v;
    v.width = 16;
    v.height = 8;
    v.channels = 4;
    v.pixels.resize(size_t(v.width) * v.height * 4);
    const float nan = std::numeric_limits<float>::quiet_NaN(),
                inf = std::numeric_limits<float>::infinity();
    for (int y = 0; y < v.height; ++y)
        for (int x = 0; x < v.width; ++x) {
            const int i = y * v.width + x;
            const float t = float(i) / float(v.width * v.height - 1);
            v.at(x, y, 0) = -0.5f + 3.0f * t;
            v.at(x, y, 1) = std::pow(10.0f, -4.0f + 8.0f * t);
            v.at(x, y, 2) = 1.0f - 2.0f * t;
            v.at(x, y, 3) = i % 13 == 5 ? 0.0f : 1.0f;
        }
    v.at(3, 0, 0) = nan;
    v.at(4, 0, 1) = inf;
    v.at(5, 0, 2) = -inf;
    return v;
}

}  // namespace

TEST(DisplayPass, GpuMappingIsTheCpuMappingForEveryMode) {
    auto context = createHeadlessContext();
    DataPaths paths{PBRLAB_SOURCE_DIR};
    ProgramCache programs{ShaderPreprocessor({paths.shaders()})};
    DisplayPass pass(programs, paths.shaders());
    const Image values = sampleValues();
    // The pass reads a render target as it is (GL rows bottom-up): upload flipped.
    gl::Handle texture = gl::uploadTexture(flipRows(values), false, GL_RGBA32F);
    const Display displays[] = {
        {DisplayMode::Grey, 0, 1, false},           {DisplayMode::Grey, -1, 2, false},
        {DisplayMode::LinearColor, 0, 1, false},    {DisplayMode::HdrColor, 0, 1, false},
        {DisplayMode::SignedVector, 0, 1, false},   {DisplayMode::FalseColor, 0, 2, false},
        {DisplayMode::FalseColor, 1e-3, 1e3, true}, {DisplayMode::Encoded, 0, 1, false}};
    for (const Display& d : displays)
        for (int components : {1, 2, 3}) {
            const Image cpu = displayImage(values, d, components);
            pass.run(texture.id(), values.width, values.height, d, components);
            // The pass writes the picture's top row into GL row 0, which readTexture returns
            // first, as it is stored.
            const Image gpu =
                IblPrecompute::readTexture(pass.texture(), values.width, values.height);
            ASSERT_EQ(gpu.width, cpu.width);
            double worst = 0;
            for (size_t i = 0; i < cpu.pixels.size(); ++i)
                if (i % 4 != 3)
                    worst = std::max(worst, double(std::abs(gpu.pixels[i] - cpu.pixels[i])));
            // float against double arithmetic (pow, log): measured 3e-7 at worst; a tenth of
            // one 8-bit display step is the bound (what a person could ever see).
            EXPECT_LT(worst, 0.1 / 255) << "mode " << int(d.mode) << ", components " << components;
        }
}
