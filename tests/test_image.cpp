// Image I/O (core/assets/image_io.cpp) and the procedural metal-plates texture set (texgen).
#include <gtest/gtest.h>
#include <png.h>

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

#include "assets/image_codecs.h"
#include "assets/image_io.h"
#include "assets/texgen.h"
#include "util/error.h"

namespace fs = std::filesystem;
using pbrlab::FileDepth;
using pbrlab::Image;
using pbrlab::ImageCodecs;

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

// ---------------------------------------------------------------- row order

TEST(FlipRows, ReversesTheRowsAndKeepsEachRow) {
    for (int height : {1, 3, 4}) {  // odd heights keep their middle row
        Image img = makeImage(5, height, 2);
        for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(i);
        const Image flipped = pbrlab::flipRows(img);
        ASSERT_EQ(flipped.width, 5);
        ASSERT_EQ(flipped.height, height);
        ASSERT_EQ(flipped.channels, 2);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < 5; ++x)
                for (int c = 0; c < 2; ++c)
                    EXPECT_EQ(flipped.at(x, y, c), img.at(x, height - 1 - y, c)) << height;
    }
}

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
    // Checked further under AddressSanitizer with 9000 mutations while writing assets/image_io.cpp.
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
    expectWriteError(dir_ / "bytes.exr", FileDepth::Uint8);    // pbrlab's EXRs are float
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

// ---------------------------------------------------------------- in-process codecs

// PNG and Radiance HDR are read (and PNG written) in-process; OpenImageIO, which read and wrote
// them before, is the yardstick: both paths must give the same image for every kind of file.

namespace {

void expectSameImage(const Image& a, const Image& b, const std::string& what) {
    ASSERT_EQ(a.width, b.width) << what;
    ASSERT_EQ(a.height, b.height) << what;
    ASSERT_EQ(a.channels, b.channels) << what;
    EXPECT_EQ(a.sourceBitsPerChannel, b.sourceBitsPerChannel) << what;
    EXPECT_EQ(a.sourceIsSrgb, b.sourceIsSrgb) << what;
    ASSERT_EQ(a.pixels.size(), b.pixels.size()) << what;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        ASSERT_EQ(a.pixels[i], b.pixels[i]) << what << ": value " << i;
}

// Reads `file` both ways, from the file and from its bytes in memory, and compares.
void expectBothPathsAgree(const fs::path& file, const std::string& what) {
    const Image ours = pbrlab::readImage(file, ImageCodecs::Default);
    const Image theirs = pbrlab::readImage(file, ImageCodecs::OpenImageIO);
    expectSameImage(ours, theirs, what);
    const auto bytes = readBytes(file);
    const std::vector<unsigned char> encoded(bytes.begin(), bytes.end());
    const std::string name = "memory" + file.extension().string();
    expectSameImage(pbrlab::decodeImage(encoded, name, ImageCodecs::Default),
                    pbrlab::decodeImage(encoded, name, ImageCodecs::OpenImageIO),
                    what + " (in memory)");
}

enum class ColourTag { None, Srgb, Gamma1, Gamma22, Gamma18, TextLinear, TextSrgb, SrgbTextLinear };

struct PngVariant {
    const char* name;
    int colourType;
    int bits;
    bool transparency = false;  // tRNS: palette alphas, or a colour key
    bool interlaced = false;
    ColourTag tag = ColourTag::None;
};

constexpr int kVariantWidth = 13, kVariantHeight = 7;

int channelsOf(int colourType) {
    switch (colourType) {
        case PNG_COLOR_TYPE_GRAY_ALPHA:
            return 2;
        case PNG_COLOR_TYPE_RGB:
            return 3;
        case PNG_COLOR_TYPE_RGB_ALPHA:
            return 4;
        default:
            return 1;  // grey, palette indices
    }
}

// Writes the variant with libpng directly, not with pbrlab's writer. libpng reports errors by
// longjmp: nothing in this frame needs a destructor.
bool writeWithLibpng(std::FILE* file, const PngVariant& v, png_bytepp rows) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        return false;
    }
    png_color palette[256];
    png_byte alphas[256];
    png_color_16 key{};
    png_text text{};
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, file);
    png_set_IHDR(png, info, kVariantWidth, kVariantHeight, v.bits, v.colourType,
                 v.interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (v.colourType == PNG_COLOR_TYPE_PALETTE) {
        for (int i = 0; i < 256; ++i) {
            palette[i] = {png_byte(i * 37), png_byte(i * 91 + 5), png_byte(255 - i)};
            alphas[i] = png_byte(i * 53);
        }
        png_set_PLTE(png, info, palette, 1 << v.bits);
        if (v.transparency) png_set_tRNS(png, info, alphas, 1 << v.bits, nullptr);
    } else if (v.transparency) {  // the first pixel's colour is transparent
        auto sample = [&](int i) {
            return v.bits == 16 ? png_uint_16((rows[0][2 * i] << 8) | rows[0][2 * i + 1])
                                : png_uint_16(rows[0][i]);
        };
        key.gray = sample(0);
        key.red = sample(0);
        key.green = sample(1);
        key.blue = sample(2);
        png_set_tRNS(png, info, nullptr, 0, &key);
    }
    text.compression = PNG_TEXT_COMPRESSION_NONE;
    text.key = const_cast<char*>("oiio:ColorSpace");
    text.text = const_cast<char*>(v.tag == ColourTag::TextSrgb ? "sRGB" : "Linear");
    switch (v.tag) {
        case ColourTag::None:
            break;
        case ColourTag::Srgb:
            png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
            break;
        case ColourTag::Gamma1:
            png_set_gAMA(png, info, 1.0);
            break;
        case ColourTag::Gamma22:
            png_set_gAMA(png, info, 1.0 / 2.2);
            break;
        case ColourTag::Gamma18:
            png_set_gAMA(png, info, 1.0 / 1.8);
            break;
        case ColourTag::SrgbTextLinear:
            png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
            png_set_text(png, info, &text, 1);
            break;
        case ColourTag::TextLinear:
        case ColourTag::TextSrgb:
            png_set_text(png, info, &text, 1);
            break;
    }
    png_write_info(png, info);
    png_write_image(png, rows);
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

void writeVariant(const fs::path& path, const PngVariant& v) {
    const size_t rowBytes = (size_t(kVariantWidth) * channelsOf(v.colourType) * v.bits + 7) / 8;
    std::vector<png_byte> data(rowBytes * kVariantHeight);
    std::uint32_t state = 99;
    for (png_byte& b : data) {
        state = state * 1664525u + 1013904223u;
        b = png_byte(state >> 24);
    }
    // Two pixels equal to the first, so a colour key hits more than one.
    const size_t pixelBytes = std::max<size_t>(1, size_t(channelsOf(v.colourType) * v.bits / 8));
    if (v.bits >= 8)
        for (size_t k = 0; k < pixelBytes; ++k) data[rowBytes + k] = data[k];
    std::vector<png_bytep> rows(kVariantHeight);
    for (int y = 0; y < kVariantHeight; ++y) rows[y] = data.data() + rowBytes * y;
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr) << path;
    const bool ok = writeWithLibpng(file, v, rows.data());
    std::fclose(file);
    ASSERT_TRUE(ok) << v.name;
}

// A Radiance file made here, independently of pbrlab's reader: the header, then every scanline
// run-length encoded one channel at a time (runs of 3 or more equal bytes as runs, the rest as
// literal stretches), or all pixels flat.
std::vector<char> radianceFile(int width, int height, const std::vector<unsigned char>& rgbe,
                               bool encodeRuns, const std::string& resolution = "",
                               const std::string& extraHeader = "") {
    std::string text =
        "#?RADIANCE\n" + extraHeader + "FORMAT=32-bit_rle_rgbe\n\n" +
        (resolution.empty() ? "-Y " + std::to_string(height) + " +X " + std::to_string(width)
                            : resolution) +
        "\n";
    std::vector<char> out(text.begin(), text.end());
    for (int y = 0; y < height; ++y) {
        const unsigned char* row = rgbe.data() + size_t(y) * width * 4;
        if (!encodeRuns) {
            out.insert(out.end(), row, row + size_t(width) * 4);
            continue;
        }
        out.insert(out.end(), {2, 2, char(width >> 8), char(width & 0xff)});
        for (int c = 0; c < 4; ++c) {
            auto at = [&](int x) { return row[size_t(x) * 4 + c]; };
            auto runAt = [&](int x) {
                int n = 1;
                while (x + n < width && n < 127 && at(x + n) == at(x)) ++n;
                return n;
            };
            for (int x = 0; x < width;) {
                if (runAt(x) >= 3) {
                    const int n = runAt(x);
                    out.push_back(char(128 + n));
                    out.push_back(char(at(x)));
                    x += n;
                    continue;
                }
                int n = 0;
                while (x + n < width && n < 128 && runAt(x + n) < 3) ++n;
                out.push_back(char(n));
                for (int k = 0; k < n; ++k) out.push_back(char(at(x + k)));
                x += n;
            }
        }
    }
    return out;
}

// RGBE pixels: a constant stretch in each row (runs), noise elsewhere, some zero exponents.
std::vector<unsigned char> rgbePixels(int width, int height) {
    std::vector<unsigned char> rgbe(size_t(width) * height * 4);
    std::uint32_t state = 5;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            unsigned char* p = &rgbe[(size_t(y) * width + x) * 4];
            for (int c = 0; c < 4; ++c) {
                state = state * 1664525u + 1013904223u;
                p[c] = (x < width / 2) ? (unsigned char)(40 * c + y + 1)
                                       : (unsigned char)(state >> 24);
            }
            p[0] |= 0x80;  // a normalised mantissa (and no scanline looks run-length marked)
            if (x >= width / 2) p[3] = (unsigned char)(110 + (p[3] & 31));
            if (x % 11 == 5) p[3] = 0;  // black
        }
    }
    return rgbe;
}

}  // namespace

TEST_F(ImageTest, PngReaderAgreesWithOpenImageIo) {
    constexpr int G = PNG_COLOR_TYPE_GRAY, GA = PNG_COLOR_TYPE_GRAY_ALPHA, RGB = PNG_COLOR_TYPE_RGB,
                  RGBA = PNG_COLOR_TYPE_RGB_ALPHA, P = PNG_COLOR_TYPE_PALETTE;
    const PngVariant variants[] = {
        {"gray1", G, 1},
        {"gray2", G, 2},
        {"gray4", G, 4},
        {"gray8", G, 8},
        {"gray16", G, 16},
        {"grayalpha8", GA, 8},
        {"grayalpha16", GA, 16},
        {"rgb8", RGB, 8},
        {"rgb16", RGB, 16},
        {"rgba8", RGBA, 8},
        {"rgba16", RGBA, 16},
        {"palette1", P, 1},
        {"palette2", P, 2},
        {"palette4", P, 4},
        {"palette8", P, 8},
        {"palette8-alpha", P, 8, true},
        {"palette2-alpha", P, 2, true},
        {"gray8-key", G, 8, true},
        {"gray16-key", G, 16, true},
        {"rgb8-key", RGB, 8, true},
        {"rgb16-key", RGB, 16, true},
        {"rgb8-interlaced", RGB, 8, false, true},
        {"gray16-interlaced", G, 16, false, true},
        {"rgb8-srgb", RGB, 8, false, false, ColourTag::Srgb},
        {"rgb8-gamma1", RGB, 8, false, false, ColourTag::Gamma1},
        {"rgb8-gamma2.2", RGB, 8, false, false, ColourTag::Gamma22},
        {"rgb8-gamma1.8", RGB, 8, false, false, ColourTag::Gamma18},
        {"rgb8-text-linear", RGB, 8, false, false, ColourTag::TextLinear},
        {"rgb8-text-srgb", RGB, 8, false, false, ColourTag::TextSrgb},
        {"rgb8-srgb-text-linear", RGB, 8, false, false, ColourTag::SrgbTextLinear},
        {"gray16-srgb", G, 16, false, false, ColourTag::Srgb},
        {"gray16-gamma1", G, 16, false, false, ColourTag::Gamma1},
        {"rgba16-gamma2.2", RGBA, 16, false, false, ColourTag::Gamma22},
    };
    for (const PngVariant& v : variants) {
        const fs::path file = dir_ / (std::string(v.name) + ".png");
        writeVariant(file, v);
        expectBothPathsAgree(file, v.name);
    }
    // What the tags mean (image.h): a gAMA of 2.0-2.6 is display encoding like sRGB; OIIO's
    // text chunk, when present, is the file's own statement and wins.
    auto srgb = [&](const char* name) {
        return pbrlab::readImage(dir_ / (std::string(name) + ".png")).sourceIsSrgb;
    };
    EXPECT_TRUE(srgb("rgb8-srgb"));
    EXPECT_TRUE(srgb("rgb8-gamma2.2"));
    EXPECT_FALSE(srgb("rgb8-gamma1.8"));
    EXPECT_FALSE(srgb("rgb8-gamma1"));
    EXPECT_FALSE(srgb("rgb8-text-linear"));
    EXPECT_FALSE(srgb("rgb8-srgb-text-linear"));
    EXPECT_TRUE(srgb("rgb8"));     // untagged 8-bit
    EXPECT_FALSE(srgb("gray16"));  // untagged 16-bit grey: data
    EXPECT_TRUE(srgb("rgb16"));    // untagged 16-bit colour
}

TEST_F(ImageTest, PngWritesReadTheSameThroughOpenImageIo) {
    // What pbrlab writes, OpenImageIO reads as written (and the other way round).
    for (int channels = 1; channels <= 4; ++channels) {
        for (FileDepth depth : {FileDepth::Uint8, FileDepth::Uint16}) {
            for (bool srgb : {false, true}) {
                const Image img = noiseImage(9, channels);
                const std::string what = std::to_string(channels) + " channels, " +
                                         pbrlab::fileDepthName(depth) + (srgb ? ", sRGB" : "");
                for (ImageCodecs writer : {ImageCodecs::Default, ImageCodecs::OpenImageIO}) {
                    const fs::path file = dir_ / "written.png";
                    pbrlab::writeImage(file, img, depth, srgb, writer);
                    const Image back = pbrlab::readImage(file, ImageCodecs::OpenImageIO);
                    EXPECT_EQ(back.sourceIsSrgb, srgb) << what;
                    EXPECT_EQ(back.sourceBitsPerChannel, depth == FileDepth::Uint8 ? 8 : 16);
                    const double step = depth == FileDepth::Uint8 ? 255.0 : 65535.0;
                    ASSERT_EQ(back.pixels.size(), img.pixels.size()) << what;
                    for (size_t i = 0; i < img.pixels.size(); ++i)
                        ASSERT_EQ(back.pixels[i], float(std::lround(img.pixels[i] * step) / step))
                            << what << " value " << i;
                    expectBothPathsAgree(file, what);
                }
            }
        }
    }
}

TEST_F(ImageTest, ExrWritesReadTheSameAsOpenImageIosOwn) {
    // EXR is written in-process (OpenEXRCore) and read by OpenImageIO: what it reads must be
    // what it reads from its own files, bit for bit, with the same channels and tags.
    const float specials[] = {0.0f, -2.5f, 1.0f / 3.0f, 1e-20f, 65504.0f, 3.4e38f, 1.0f + 1e-7f};
    for (int channels = 1; channels <= 4; ++channels) {
        for (bool srgb : {false, true}) {
            // 40 rows: more than one 16-line ZIP chunk, and a last chunk that is not full.
            Image img = makeImage(7, 40, channels);
            for (size_t i = 0; i < img.pixels.size(); ++i)
                img.pixels[i] = specials[i % 7] * (1.0f + float(i) * 0.01f);
            const std::string what =
                std::to_string(channels) + " channels" + (srgb ? ", sRGB" : "");
            pbrlab::writeImage(dir_ / "ours.exr", img, FileDepth::Float32, srgb,
                               ImageCodecs::Default);
            pbrlab::writeImage(dir_ / "theirs.exr", img, FileDepth::Float32, srgb,
                               ImageCodecs::OpenImageIO);
            const Image ours = pbrlab::readImage(dir_ / "ours.exr");
            expectSameImage(ours, pbrlab::readImage(dir_ / "theirs.exr"), what);
            ASSERT_EQ(ours.pixels.size(), img.pixels.size()) << what;
            for (size_t i = 0; i < img.pixels.size(); ++i)
                ASSERT_EQ(ours.pixels[i], img.pixels[i]) << what << " value " << i;
            EXPECT_FALSE(ours.sourceIsSrgb) << what;  // float data is linear
        }
    }
}

TEST_F(ImageTest, HdrReaderAgreesWithOpenImageIo) {
    struct Case {
        const char* name;
        int width, height;
        bool encodeRuns;
    };
    // 300 wide: runs longer than one code can hold (127) and literal stretches of 128; widths
    // under 8 are always flat; a flat first scanline makes the whole file flat.
    for (const Case& c : {Case{"rle", 64, 9, true}, Case{"rle-wide", 300, 4, true},
                          Case{"flat-narrow", 5, 6, false}, Case{"flat", 20, 3, false}}) {
        const fs::path file = dir_ / (std::string(c.name) + ".hdr");
        writeBytes(file,
                   radianceFile(c.width, c.height, rgbePixels(c.width, c.height), c.encodeRuns));
        expectBothPathsAgree(file, c.name);
        const Image image = pbrlab::readImage(file);
        EXPECT_EQ(image.width, c.width);
        EXPECT_EQ(image.channels, 3);
        EXPECT_FALSE(image.sourceIsSrgb);
    }
    // What OpenImageIO writes (the `environment` command's .hdr files).
    pbrlab::writeImage(dir_ / "oiio.hdr", noiseImage(40, 3), FileDepth::Float32);
    expectBothPathsAgree(dir_ / "oiio.hdr", "written by OpenImageIO");
    // Headers as Photoshop writes them (the shipped environments: GAMMA=1, PRIMARIES), and
    // other GAMMA values, whose colour-space names must be OpenImageIO's.
    for (const char* gamma : {"GAMMA=1", "GAMMA=2.2", "GAMMA=0.4545", "GAMMA=0.5", "GAMMA=x"}) {
        const std::string extra =
            "# Made with Adobe Photoshop\n" + std::string(gamma) + "\nPRIMARIES=0 0 0 0 0 0 0 0\n";
        writeBytes(dir_ / "gamma.hdr", radianceFile(12, 4, rgbePixels(12, 4), true, "", extra));
        expectBothPathsAgree(dir_ / "gamma.hdr", gamma);
    }
    // A variant the in-process reader hands to OpenImageIO: rows bottom to top.
    writeBytes(dir_ / "bottom-up.hdr", radianceFile(12, 4, rgbePixels(12, 4), false, "+Y 4 +X 12"));
    expectBothPathsAgree(dir_ / "bottom-up.hdr", "bottom-up");
}

TEST_F(ImageTest, TruncatedHdrIsAnError) {
    for (bool encodeRuns : {true, false}) {
        const auto bytes = radianceFile(64, 16, rgbePixels(64, 16), encodeRuns);
        for (size_t keep :
             {bytes.size() / 2, bytes.size() * 9 / 10, bytes.size() - 1, bytes.size() / 20}) {
            const fs::path file = dir_ / ("truncated-" + std::to_string(keep) + ".hdr");
            writeBytes(file, std::vector<char>(bytes.begin(), bytes.begin() + long(keep)));
            expectReadError(file, "truncated HDR");
        }
    }
}

TEST_F(ImageTest, CorruptHdrRunsAreErrors) {
    // stb_image loops forever on a run of length 0 or a truncated file; pbrlab's reader must stop.
    const auto good = radianceFile(64, 4, rgbePixels(64, 4), true);
    const std::string text(good.begin(), good.end());
    const size_t data = text.find("+X 64\n") + 6;  // the first scanline's 2, 2, 0, 64
    ASSERT_EQ(good[data], 2);
    auto corrupt = [&](size_t at, char value, const std::string& name) {
        auto bytes = good;
        bytes[at] = value;
        writeBytes(dir_ / name, bytes);
        expectReadError(dir_ / name, name);
    };
    corrupt(data + 4, 0, "zero-run.hdr");                // a literal stretch of 0 bytes
    corrupt(data + 4, char(128 + 100), "long-run.hdr");  // the first run is 32 long: 100 is not
    corrupt(data + 3, 63, "short-scanline.hdr");         // the scanline says 63 pixels, not 64
    // A header claiming far more pixels than the bytes that follow could hold.
    const std::string huge = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 10000 +X 10000\n";
    std::vector<char> bytes(huge.begin(), huge.end());
    bytes.resize(bytes.size() + 100, 2);
    writeBytes(dir_ / "huge.hdr", bytes);
    expectReadError(dir_ / "huge.hdr", "header claiming 10000 x 10000");
}

TEST_F(ImageTest, HotFormatsNeverOpenOpenImageIo) {
    if (pbrlab::openImageIoLoaded())
        GTEST_SKIP() << "an earlier test in this process opened it (ctest runs each test alone)";
    const Image img = noiseImage(16, 3);
    pbrlab::writeImage(dir_ / "a.png", img, FileDepth::Uint8, true);
    pbrlab::writeImage(dir_ / "b.png", img, FileDepth::Uint16);
    (void)pbrlab::readImage(dir_ / "a.png");
    (void)pbrlab::readImage(dir_ / "b.png");
    const auto bytes = readBytes(dir_ / "a.png");
    (void)pbrlab::decodeImage(std::vector<unsigned char>(bytes.begin(), bytes.end()), "x.png");
    // The shipped environments' header (Photoshop's).
    writeBytes(dir_ / "c.hdr", radianceFile(16, 4, rgbePixels(16, 4), true, "",
                                            "# Made with Adobe Photoshop\nGAMMA=1\n"
                                            "PRIMARIES=0 0 0 0 0 0 0 0\n"));
    (void)pbrlab::readImage(dir_ / "c.hdr");
    pbrlab::writeImage(dir_ / "d.exr", img, FileDepth::Float32);
    EXPECT_FALSE(pbrlab::openImageIoLoaded());
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

// Material maps get their mip levels on the CPU (assets/image_io.h): 2x2 means where a size is
// even, the exact covered area where it is odd, and every level keeps the image's mean, which
// a filter dropping the odd row or column would not.
TEST(Image, MipLevelsAverageTheAreaEachTexelCovers) {
    pbrlab::Image even;
    even.width = 4;
    even.height = 2;
    even.channels = 1;
    even.pixels = {0, 1, 2, 3, 4, 5, 6, 7};
    const pbrlab::Image half = pbrlab::halfSize(even);
    ASSERT_EQ(half.width, 2);
    ASSERT_EQ(half.height, 1);
    EXPECT_FLOAT_EQ(half.pixels[0], (0 + 1 + 4 + 5) / 4.0f);
    EXPECT_FLOAT_EQ(half.pixels[1], (2 + 3 + 6 + 7) / 4.0f);

    pbrlab::Image odd;
    odd.width = 5;
    odd.height = 3;
    odd.channels = 2;
    std::mt19937 random(7);
    std::uniform_real_distribution<float> value(0, 1);
    for (int i = 0; i < 5 * 3 * 2; ++i) odd.pixels.push_back(value(random));
    auto mean = [](const pbrlab::Image& image, int c) {
        double sum = 0;
        for (size_t i = size_t(c); i < image.pixels.size(); i += size_t(image.channels))
            sum += image.pixels[i];
        return sum / double(image.width * image.height);
    };
    pbrlab::Image level = odd;
    for (const auto& [w, h] : {std::pair{2, 1}, std::pair{1, 1}}) {
        level = pbrlab::halfSize(level);
        ASSERT_EQ(level.width, w);
        ASSERT_EQ(level.height, h);
        ASSERT_EQ(level.channels, 2);
        for (int c = 0; c < 2; ++c) EXPECT_NEAR(mean(level, c), mean(odd, c), 1e-6) << c;
    }
    // The left texel of 5 -> 2 covers source columns 0, 1 and half of 2.
    pbrlab::Image row;
    row.width = 5;
    row.height = 1;
    row.channels = 1;
    row.pixels = {1, 2, 3, 4, 5};
    EXPECT_FLOAT_EQ(pbrlab::halfSize(row).pixels[0], (1 + 2 + 0.5f * 3) / 2.5f);
}
