// Image I/O (core/src/image.cpp) and the procedural metal-plates texture set (texgen).
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "pbrlab/error.h"
#include "pbrlab/image.h"
#include "pbrlab/texgen.h"

namespace fs = std::filesystem;
using pbrlab::FileDepth;
using pbrlab::Image;

namespace {

// A fresh directory per test under the system temp directory; removed afterwards.
class ImageTest : public ::testing::Test {
protected:
    void SetUp() override {
        static std::atomic<unsigned> counter{0};
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
        dir_ = fs::temp_directory_path() /
               ("pbrlab-test-image-" + std::string(info->name()) + "-" + std::to_string(stamp) +
                "-" + std::to_string(std::random_device{}()) + "-" + std::to_string(counter++));
        ASSERT_TRUE(fs::create_directories(dir_)) << dir_;
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    fs::path dir_;
};

Image makeImage(int w, int h, int c) {
    Image img;
    img.width = w;
    img.height = h;
    img.channels = c;
    img.pixels.resize(size_t(w) * h * c);
    return img;
}

std::vector<char> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const fs::path& path, const std::vector<char>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

void truncateFile(const fs::path& path, double keepFraction) {
    auto bytes = readBytes(path);
    bytes.resize(size_t(double(bytes.size()) * keepFraction));
    writeBytes(path, bytes);
}

// Removes the PNG chunks that say how to interpret the values (gAMA, sRGB, cHRM, iCCP, text),
// leaving an untagged file. The other chunks keep their own CRCs, so the file stays valid.
void stripPngColourChunks(const fs::path& path) {
    const auto bytes = readBytes(path);
    ASSERT_GT(bytes.size(), 8u);
    std::vector<char> out(bytes.begin(), bytes.begin() + 8);
    size_t i = 8;
    while (i + 12 <= bytes.size()) {
        auto b = [&](size_t k) { return std::uint32_t(std::uint8_t(bytes[i + k])); };
        const std::uint32_t length = (b(0) << 24) | (b(1) << 16) | (b(2) << 8) | b(3);
        const std::string type(bytes.begin() + long(i) + 4, bytes.begin() + long(i) + 8);
        const size_t end = i + 12 + length;
        ASSERT_LE(end, bytes.size());
        if (type != "gAMA" && type != "sRGB" && type != "cHRM" && type != "iCCP" &&
            type != "tEXt" && type != "iTXt" && type != "zTXt")
            out.insert(out.end(), bytes.begin() + long(i), bytes.begin() + long(end));
        i = end;
    }
    writeBytes(path, out);
}

// Reading `path` must throw pbrlab::Error (not crash, not return) naming the file.
void expectReadError(const fs::path& path, const std::string& aboutWhat) {
    try {
        (void)pbrlab::readImage(path);
        ADD_FAILURE() << "no error for " << aboutWhat << ": " << path;
    } catch (const pbrlab::Error& e) {
        EXPECT_NE(std::string(e.what()).find(path.filename().string()), std::string::npos)
            << aboutWhat << ": message does not name the file: " << e.what();
    }
}

// A noisy 8-bit PNG / float EXR big enough that truncating it cuts into the pixel data.
Image noiseImage(int size, int channels) {
    Image img = makeImage(size, size, channels);
    std::uint32_t state = 12345;
    for (float& v : img.pixels) {
        state = state * 1664525u + 1013904223u;
        v = float(state >> 8) / 16777216.0f;
    }
    return img;
}

size_t countEntries(const fs::path& dir) {
    return size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}));
}

}  // namespace

// ---------------------------------------------------------------- round trips

TEST_F(ImageTest, Png8RoundTripIsExactAndRow0IsTop) {
    // Not square, so a swapped width/height or a flipped row order shows.
    Image img = makeImage(7, 5, 3);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c)
                img.at(x, y, c) = float((y * 50 + x * 7 + c * 3) % 256) / 255.0f;
    const fs::path file = dir_ / "rgb8.png";
    pbrlab::writeImage(file, img, FileDepth::Uint8);

    const Image back = pbrlab::readImage(file);
    ASSERT_EQ(back.width, 7);
    ASSERT_EQ(back.height, 5);
    ASSERT_EQ(back.channels, 3);
    EXPECT_EQ(back.sourceBitsPerChannel, 8);
    EXPECT_FALSE(back.sourceIsSrgb);  // written without markSrgb: tagged linear (gAMA 1.0)
    for (size_t i = 0; i < img.pixels.size(); ++i) ASSERT_EQ(back.pixels[i], img.pixels[i]) << i;
    EXPECT_EQ(back.at(0, 0, 0), 0.0f);             // top-left
    EXPECT_EQ(back.at(0, 4, 0), 200.0f / 255.0f);  // bottom-left
}

TEST_F(ImageTest, Png8ClampsAndRoundsToNearest) {
    Image img = makeImage(6, 1, 1);
    img.pixels = {-0.5f, 2.0f,           std::numeric_limits<float>::quiet_NaN(),
                  0.5f,  10.4f / 255.0f, 10.6f / 255.0f};
    const fs::path file = dir_ / "clamp.png";
    pbrlab::writeImage(file, img, FileDepth::Uint8);
    const Image back = pbrlab::readImage(file);
    const std::vector<float> expected = {0.0f,           1.0f,          0.0f, 128.0f / 255.0f,
                                         10.0f / 255.0f, 11.0f / 255.0f};
    ASSERT_EQ(back.pixels.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(back.pixels[i], expected[i]) << i;
}

TEST_F(ImageTest, Png16KeepsEvery16BitCodeValue) {
    // 600 distinct code values spread over the whole range, most of them not multiples of 257
    // (the 8-bit codes widened to 16 bits): any detour through 8 bits would collapse them.
    Image img = makeImage(300, 2, 1);
    std::vector<int> codes(img.pixels.size());
    for (size_t i = 0; i < codes.size(); ++i) {
        codes[i] = int((i * 109 + 7) % 65536);
        img.pixels[i] = float(codes[i]) / 65535.0f;
    }
    const fs::path file = dir_ / "gray16.png";
    pbrlab::writeImage(file, img, FileDepth::Uint16);

    const Image back = pbrlab::readImage(file);
    ASSERT_EQ(back.pixels.size(), img.pixels.size());
    EXPECT_EQ(back.sourceBitsPerChannel, 16);
    EXPECT_FALSE(back.sourceIsSrgb);
    std::set<float> distinct(back.pixels.begin(), back.pixels.end());
    EXPECT_GT(distinct.size(), 256u);
    EXPECT_EQ(distinct.size(), 600u);
    for (size_t i = 0; i < codes.size(); ++i) {
        ASSERT_EQ(std::lround(double(back.pixels[i]) * 65535.0), codes[i]) << i;
        ASSERT_EQ(back.pixels[i], float(codes[i]) / 65535.0f) << i;
    }
}

TEST_F(ImageTest, ExrFloatRoundTripIsBitExact) {
    Image img = makeImage(5, 3, 4);
    const float specials[] = {0.0f, -2.5f, 1.0f / 3.0f, 1e-20f, 65504.0f, 3.4e38f, 1.0f + 1e-7f};
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] = specials[i % 7] * (1.0f + float(i) * 0.01f);
    const fs::path file = dir_ / "float.exr";
    pbrlab::writeImage(file, img, pbrlab::defaultDepthFor(file));

    const Image back = pbrlab::readImage(file);
    ASSERT_EQ(back.width, 5);
    ASSERT_EQ(back.height, 3);
    ASSERT_EQ(back.channels, 4);
    EXPECT_EQ(back.sourceBitsPerChannel, 32);
    EXPECT_FALSE(back.sourceIsSrgb);
    for (size_t i = 0; i < img.pixels.size(); ++i) ASSERT_EQ(back.pixels[i], img.pixels[i]) << i;
}

TEST_F(ImageTest, RgbaPngKeepsStraightAlpha) {
    // OIIO premultiplies PNG colour by alpha unless told not to; colour under alpha 0 must stay.
    Image img = makeImage(2, 1, 4);
    img.pixels = {1.0f, 0.5f, 0.25f, 0.0f, 0.2f, 0.4f, 0.6f, 128.0f / 255.0f};
    const fs::path file = dir_ / "rgba.png";
    pbrlab::writeImage(file, img, FileDepth::Uint8);
    const Image back = pbrlab::readImage(file);
    ASSERT_EQ(back.channels, 4);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        EXPECT_NEAR(back.pixels[i], img.pixels[i], 0.5 / 255.0 + 1e-7) << i;
    EXPECT_EQ(back.pixels[0], 1.0f);
}

TEST_F(ImageTest, ColourSpaceTagsAndUntaggedDefaults) {
    Image rgb = makeImage(4, 4, 3), gray = makeImage(4, 4, 1);
    pbrlab::writeImage(dir_ / "srgb.png", rgb, FileDepth::Uint8, /*markSrgb=*/true);
    pbrlab::writeImage(dir_ / "linear8.png", rgb, FileDepth::Uint8, false);
    EXPECT_TRUE(pbrlab::readImage(dir_ / "srgb.png").sourceIsSrgb);
    EXPECT_FALSE(pbrlab::readImage(dir_ / "linear8.png").sourceIsSrgb);

    // Untagged files: 8-bit counts as sRGB, 16-bit grayscale as linear data.
    pbrlab::writeImage(dir_ / "plain8.png", rgb, FileDepth::Uint8, false);
    pbrlab::writeImage(dir_ / "plain16.png", gray, FileDepth::Uint16, false);
    pbrlab::writeImage(dir_ / "plain16srgb.png", gray, FileDepth::Uint16, true);
    for (const char* name : {"plain8.png", "plain16.png", "plain16srgb.png"})
        stripPngColourChunks(dir_ / name);
    EXPECT_TRUE(pbrlab::readImage(dir_ / "plain8.png").sourceIsSrgb);
    EXPECT_FALSE(pbrlab::readImage(dir_ / "plain16.png").sourceIsSrgb);
    EXPECT_FALSE(pbrlab::readImage(dir_ / "plain16srgb.png").sourceIsSrgb);
    EXPECT_EQ(pbrlab::readImage(dir_ / "plain16.png").sourceBitsPerChannel, 16);
}

TEST_F(ImageTest, DefaultDepthFollowsExtension) {
    EXPECT_EQ(pbrlab::defaultDepthFor("a.exr"), FileDepth::Float32);
    EXPECT_EQ(pbrlab::defaultDepthFor("a.EXR"), FileDepth::Float32);
    EXPECT_EQ(pbrlab::defaultDepthFor("a.hdr"), FileDepth::Float32);
    EXPECT_EQ(pbrlab::defaultDepthFor("a.png"), FileDepth::Uint8);
    EXPECT_EQ(pbrlab::defaultDepthFor("a.jpg"), FileDepth::Uint8);
}

// ---------------------------------------------------------------- errors

TEST_F(ImageTest, MissingFileIsAnError) {
    expectReadError(dir_ / "no-such-file.png", "missing");
}

TEST_F(ImageTest, TextFileNamedPngIsAnError) {
    const fs::path file = dir_ / "not-an-image.png";
    std::ofstream(file) << "This is not a PNG file, just some text.\n";
    expectReadError(file, "text file");
}

TEST_F(ImageTest, EmptyFileIsAnError) {
    const fs::path file = dir_ / "empty.png";
    std::ofstream{file};
    ASSERT_EQ(fs::file_size(file), 0u);
    expectReadError(file, "empty file");
}

TEST_F(ImageTest, TruncatedPngIsAnError) {
    for (double keep : {0.5, 0.9, 0.05}) {
        const fs::path file = dir_ / ("truncated-" + std::to_string(int(keep * 100)) + ".png");
        pbrlab::writeImage(file, noiseImage(64, 3), FileDepth::Uint8);
        truncateFile(file, keep);
        expectReadError(file, "truncated PNG");
    }
}

TEST_F(ImageTest, TruncatedExrIsAnError) {
    for (double keep : {0.5, 0.9, 0.05}) {
        const fs::path file = dir_ / ("truncated-" + std::to_string(int(keep * 100)) + ".exr");
        pbrlab::writeImage(file, noiseImage(64, 3), FileDepth::Float32);
        truncateFile(file, keep);
        expectReadError(file, "truncated EXR");
    }
}

TEST_F(ImageTest, CorruptedFilesGiveErrorsNotCrashes) {
    // Deterministic byte mutations (overwrites, sometimes a cut) of a valid file: each read
    // must either succeed or throw pbrlab::Error; anything else (crash, other exception) fails.
    // Checked further under AddressSanitizer with 9000 mutations while writing image.cpp.
    std::uint32_t state = 7;
    auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        return state >> 8;
    };
    for (const char* name : {"fuzz.png", "fuzz.exr", "fuzz.hdr"}) {
        const fs::path original = dir_ / name;
        const bool png = fs::path(name).extension() == ".png";
        pbrlab::writeImage(original, noiseImage(32, 3),
                           png ? FileDepth::Uint16 : FileDepth::Float32);
        const auto bytes = readBytes(original);
        const fs::path file = dir_ / ("mutated" + fs::path(name).extension().string());
        int errors = 0;
        for (int i = 0; i < 150; ++i) {
            auto mutated = bytes;
            for (std::uint32_t k = 0, n = 1 + next() % 8; k < n; ++k)
                mutated[next() % mutated.size()] = char(next() & 0xff);
            if (next() % 4 == 0) mutated.resize(next() % mutated.size());
            writeBytes(file, mutated);
            try {
                (void)pbrlab::readImage(file);
            } catch (const pbrlab::Error& e) {
                ++errors;
                EXPECT_NE(std::string(e.what()).find(file.filename().string()), std::string::npos);
            }
        }
        EXPECT_GT(errors, 0) << name;
    }
}

TEST_F(ImageTest, FailedWritesThrowAndLeaveNothingBehind) {
    const Image img = makeImage(4, 4, 3);
    auto expectWriteError = [&](const fs::path& file, FileDepth depth) {
        try {
            pbrlab::writeImage(file, img, depth);
            ADD_FAILURE() << "no error writing " << file;
        } catch (const pbrlab::Error& e) {
            EXPECT_NE(std::string(e.what()).find(file.filename().string()), std::string::npos)
                << e.what();
        }
    };
    expectWriteError(dir_ / "float.png", FileDepth::Float32);  // PNG holds no floats
    expectWriteError(dir_ / "image.unknownext", FileDepth::Uint8);
    expectWriteError(dir_ / "missing-dir" / "x.png", FileDepth::Uint8);
    Image broken = img;
    broken.pixels.pop_back();
    EXPECT_THROW(pbrlab::writeImage(dir_ / "short.png", broken, FileDepth::Uint8), pbrlab::Error);
    EXPECT_EQ(countEntries(dir_), 0u) << "a temporary or partial file was left behind";
}

TEST_F(ImageTest, WriteReplacesAnExistingFile) {
    const fs::path file = dir_ / "replace.png";
    Image a = makeImage(2, 2, 1), b = makeImage(3, 1, 1);
    b.pixels = {1.0f, 0.0f, 1.0f};
    pbrlab::writeImage(file, a, FileDepth::Uint8);
    pbrlab::writeImage(file, b, FileDepth::Uint8);
    const Image back = pbrlab::readImage(file);
    EXPECT_EQ(back.width, 3);
    EXPECT_EQ(back.pixels, b.pixels);
    EXPECT_EQ(countEntries(dir_), 1u);
}

// ---------------------------------------------------------------- texgen

namespace {
const char* const kMaps[] = {"albedo.png", "roughness.png", "metallic.png", "ao.png", "normal.png"};
}

TEST_F(ImageTest, MetalPlatesAreDeterministicAndSmall) {
    pbrlab::generateMetalPlates(dir_ / "a");
    pbrlab::generateMetalPlates(dir_ / "b");
    std::uintmax_t total = 0;
    for (const char* name : kMaps) {
        const auto a = readBytes(dir_ / "a" / name), b = readBytes(dir_ / "b" / name);
        ASSERT_FALSE(a.empty()) << name;
        EXPECT_TRUE(a == b) << name << " differs between two runs";
        total += a.size();
        const Image img = pbrlab::readImage(dir_ / "a" / name);
        EXPECT_EQ(img.width, 256) << name;
        EXPECT_EQ(img.height, 256) << name;
    }
    EXPECT_LT(total, 600u * 1024u) << "texture set too large for the repository";
}

TEST_F(ImageTest, MetalPlatesMapsHaveTheDeclaredFormats) {
    pbrlab::generateMetalPlates(dir_, 128);

    const Image albedo = pbrlab::readImage(dir_ / "albedo.png");
    EXPECT_EQ(albedo.channels, 3);
    EXPECT_EQ(albedo.sourceBitsPerChannel, 8);
    EXPECT_TRUE(albedo.sourceIsSrgb);

    const Image roughness = pbrlab::readImage(dir_ / "roughness.png");
    EXPECT_EQ(roughness.channels, 1);
    EXPECT_EQ(roughness.sourceBitsPerChannel, 16);
    EXPECT_FALSE(roughness.sourceIsSrgb);
    const std::set<float> levels(roughness.pixels.begin(), roughness.pixels.end());
    EXPECT_GT(levels.size(), 256u) << "roughness does not use 16-bit precision";

    const Image metallic = pbrlab::readImage(dir_ / "metallic.png");
    EXPECT_EQ(metallic.channels, 1);
    EXPECT_EQ(metallic.sourceBitsPerChannel, 16);
    EXPECT_FALSE(metallic.sourceIsSrgb);
    size_t binary = 0, zeros = 0, ones = 0;
    for (float m : metallic.pixels) {
        binary += (m < 0.02f || m > 0.98f);
        zeros += (m == 0.0f);
        ones += (m == 1.0f);
    }
    EXPECT_GT(binary, metallic.pixels.size() * 9 / 10) << "metallic should be mostly 0 or 1";
    EXPECT_GT(zeros, 0u);
    EXPECT_GT(ones, 0u);

    const Image ao = pbrlab::readImage(dir_ / "ao.png");
    EXPECT_EQ(ao.channels, 1);
    EXPECT_EQ(ao.sourceBitsPerChannel, 8);
    EXPECT_FALSE(ao.sourceIsSrgb);
    float aoMin = 1.0f;
    for (float a : ao.pixels) aoMin = std::min(aoMin, a);
    EXPECT_LT(aoMin, 0.6f) << "grooves should be occluded";

    const Image normal = pbrlab::readImage(dir_ / "normal.png");
    EXPECT_EQ(normal.channels, 3);
    EXPECT_EQ(normal.sourceBitsPerChannel, 8);
    EXPECT_FALSE(normal.sourceIsSrgb);
}

TEST_F(ImageTest, MetalPlatesNormalsAreUnitVectors) {
    pbrlab::generateMetalPlates(dir_);
    const Image normal = pbrlab::readImage(dir_ / "normal.png");
    ASSERT_EQ(normal.channels, 3);
    // Each channel stores n * 0.5 + 0.5 rounded to the nearest of 255 steps: an error of at
    // most 0.5 / 255 there, 1 / 255 per component after decoding (2c - 1). The decoded vector
    // is at most sqrt(3) / 255 (about 0.0068) away from the unit vector, so its length is
    // within that of 1 (triangle inequality). 1e-6 covers float rounding in the decode.
    const double tolerance = std::sqrt(3.0) / 255.0 + 1e-6;
    double worst = 0.0, sumZ = 0.0, minZ = 1.0;
    size_t tilted = 0;
    for (int y = 0; y < normal.height; ++y) {
        for (int x = 0; x < normal.width; ++x) {
            const double nx = 2.0 * normal.at(x, y, 0) - 1.0;
            const double ny = 2.0 * normal.at(x, y, 1) - 1.0;
            const double nz = 2.0 * normal.at(x, y, 2) - 1.0;
            worst = std::max(worst, std::abs(std::sqrt(nx * nx + ny * ny + nz * nz) - 1.0));
            sumZ += nz;
            minZ = std::min(minZ, nz);
            tilted += (nz < 0.95);
        }
    }
    EXPECT_LE(worst, tolerance);
    EXPECT_GT(minZ, 0.0) << "a tangent-space normal must point out of the surface";
    EXPECT_GT(sumZ / (normal.width * normal.height), 0.9) << "mostly flat plates: bluish map";
    EXPECT_GT(tilted, size_t(normal.width * normal.height / 50)) << "seams and rivets missing";
}

TEST_F(ImageTest, MetalPlatesNormalMapIsOpenGlConvention) {
    // OpenGL convention: +Y (green above 0.5) points to the image top. Just below a horizontal
    // groove the lower plate's bevel rises towards the top of the image, so it faces up; just
    // above it the upper plate's bevel faces down. The groove is the darkest row of the ao map
    // (horizontal seams cross the whole width, vertical ones do not).
    pbrlab::generateMetalPlates(dir_, 256);
    const Image normal = pbrlab::readImage(dir_ / "normal.png");
    const Image ao = pbrlab::readImage(dir_ / "ao.png");
    auto rowMean = [](const Image& img, int y, int c) {
        double sum = 0.0;
        for (int x = 0; x < img.width; ++x) sum += img.at(x, y, c);
        return sum / img.width;
    };
    int seam = 8;
    for (int y = 8; y < ao.height - 8; ++y)
        if (rowMean(ao, y, 0) < rowMean(ao, seam, 0)) seam = y;
    double below = 0.0, above = 0.0;
    for (int d = 1; d <= 3; ++d) {
        below += rowMean(normal, seam + d, 1) / 3.0;
        above += rowMean(normal, seam - d, 1) / 3.0;
    }
    EXPECT_GT(below, 0.55) << "bevel below the groove at row " << seam << " should face +Y";
    EXPECT_LT(above, 0.45) << "bevel above the groove at row " << seam << " should face -Y";
}

TEST_F(ImageTest, MetalPlatesRejectsBadSize) {
    EXPECT_THROW(pbrlab::generateMetalPlates(dir_, 0), pbrlab::Error);
    EXPECT_THROW(pbrlab::generateMetalPlates(dir_, -5), pbrlab::Error);
}

TEST_F(ImageTest, ShippedTexturesAreWhatTheGeneratorMakes) {
    // assets/textures/metal-plates is `pbrlab textures` output, committed so a fresh clone
    // needs no generation step. Regenerating must give the same pixels; one code value of
    // slack (1/255, 1/65535) because another compiler's libm may round a sin() differently.
    pbrlab::generateMetalPlates(dir_ / "fresh");
    const fs::path shipped = fs::path(PBRLAB_SOURCE_DIR) / "assets/textures/metal-plates";
    for (const char* name : kMaps) {
        const Image a = pbrlab::readImage(dir_ / "fresh" / name);
        const Image b = pbrlab::readImage(shipped / name);
        ASSERT_EQ(a.pixels.size(), b.pixels.size()) << name;
        const double step = a.sourceBitsPerChannel == 16 ? 1.0 / 65535 : 1.0 / 255;
        double worst = 0;
        for (size_t i = 0; i < a.pixels.size(); ++i)
            worst = std::max(worst, double(std::abs(a.pixels[i] - b.pixels[i])));
        EXPECT_LE(worst, step * 1.01) << name;
    }
}
