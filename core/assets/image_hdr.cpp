// Radiance RGBE (.hdr), the format of the environments: a text header, a resolution line, then
// scanlines of 4-byte pixels (three mantissas sharing one exponent), usually run-length encoded
// one channel at a time. Read here rather than by stb_image from Debian's libstb, which loops
// forever on a truncated file, or by OpenImageIO, which costs 0.3-0.5 s to load. Variants this
// reader does not take (other orientations, XYZE) go to OpenImageIO.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "assets/image_codecs.h"

namespace pbrlab {
namespace {

// A resolution axis: "-Y 512" says 512 rows from top to bottom, "+X 1024" 1024 pixels from left
// to right.
bool readAxis(std::string_view& line, std::string_view axis, int& count) {
    if (line.substr(0, axis.size()) != axis) return false;
    line.remove_prefix(axis.size());
    long long value = 0;
    std::size_t digits = 0;
    while (digits < line.size() && line[digits] >= '0' && line[digits] <= '9' && digits < 10)
        value = value * 10 + (line[digits++] - '0');
    if (digits == 0 || value <= 0 || value > 0x7fffffff) return false;
    count = int(value);
    line.remove_prefix(digits);
    return true;
}

// 2^(e - 136) for each exponent byte e (the mantissas are 8-bit fractions), 0 for e = 0 (black).
// Every entry and every mantissa times it is exact in float (down to 2^-135, a subnormal).
struct ExponentScales {
    float scale[256];
    ExponentScales() {
        scale[0] = 0.0f;
        for (int e = 1; e < 256; ++e) scale[e] = std::ldexp(1.0f, e - (128 + 8));
    }
};
const ExponentScales kScales;

void toFloat(const unsigned char* rgbe, float* rgb) {
    const float scale = kScales.scale[rgbe[3]];
    for (int c = 0; c < 3; ++c) rgb[c] = float(rgbe[c]) * scale;
}

}  // namespace

bool readRadianceHeader(const unsigned char* bytes, std::size_t size, RadianceHeader& out) {
    const std::string_view text(reinterpret_cast<const char*>(bytes), size);
    if (text.substr(0, 2) != "#?") return false;
    bool rgbe = false, usableGamma = true;
    double gamma = 0.0;
    std::size_t pos = 0;
    for (;;) {  // header lines up to an empty one
        const std::size_t end = text.find('\n', pos);
        if (end == std::string_view::npos || end > 65536) return false;
        const std::string_view line = text.substr(pos, end - pos);
        pos = end + 1;
        if (line.empty()) break;
        if (line.substr(0, 7) == "FORMAT=") rgbe = line.substr(7) == "32-bit_rle_rgbe";
        if (line.substr(0, 6) == "GAMMA=") {
            const std::string value(line.substr(6));
            char* end = nullptr;
            gamma = std::strtod(value.c_str(), &end);
            usableGamma = end != value.c_str() && gamma > 0.0 && std::isfinite(gamma);
        }
    }
    const std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) return false;
    std::string_view resolution = text.substr(pos, end - pos);
    const bool topDown = readAxis(resolution, "-Y ", out.height) &&
                         readAxis(resolution, " +X ", out.width) && resolution.empty();
    out.dataStart = end + 1;
    out.standard = rgbe && usableGamma && topDown;
    // The name OpenImageIO 2.4 gives (it rounds 1 / GAMMA to hundredths); no GAMMA: linear.
    out.colourSpace = "linear";
    if (gamma > 0.0) {
        const float g = std::round(100.0f * float(1.0 / gamma)) / 100.0f;
        if (g != 1.0f) {
            char name[32];
            std::snprintf(name, sizeof name, "Gamma%.2g", double(g));
            out.colourSpace = name;
        }
    }
    return out.standard;
}

std::string decodeRadiance(const unsigned char* bytes, std::size_t size,
                           const RadianceHeader& header, DecodedImage& out) {
    const int width = header.width, height = header.height;
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    if (pixels > kMaxImageValues / 3) {
        return "too large (" + std::to_string(width) + " x " + std::to_string(height) + " x 3)";
    }
    // Radiance's own reader (and OpenImageIO's) encode runs only for widths 8..32767; once a
    // scanline is not run-length encoded, the rest of the file is flat pixels.
    bool flat = width < 8 || width > 0x7fff;
    // The fewest bytes the pixels could take (a run covers at most 127 pixels of one channel
    // in 2 bytes): a header claiming more than the file can hold is refused before allocating.
    const std::size_t leastPerRow =
        flat ? 4 * std::size_t(width) : 4 + 4 * 2 * ((std::size_t(width) + 126) / 127);
    const std::size_t available = size - header.dataStart;
    if (available / leastPerRow < std::size_t(height)) {
        return "truncated: " + std::to_string(width) + " x " + std::to_string(height) +
               " pixels need at least " + std::to_string(leastPerRow * std::size_t(height)) +
               " bytes, the file has " + std::to_string(available);
    }

    Image& image = out.image;
    image.width = width;
    image.height = height;
    image.channels = 3;
    image.sourceBitsPerChannel = 32;
    image.pixels.resize(pixels * 3);
    std::vector<unsigned char> row(std::size_t(width) * 4);
    std::size_t pos = header.dataStart;
    auto truncated = [&](int y) {
        return "truncated: the file ends in scanline " + std::to_string(y) + " of " +
               std::to_string(height);
    };
    for (int y = 0; y < height; ++y) {
        float* rgb = image.pixels.data() + std::size_t(y) * std::size_t(width) * 3;
        if (!flat) {
            if (size - pos < 4) return truncated(y);
            const unsigned char* mark = bytes + pos;
            flat = !(mark[0] == 2 && mark[1] == 2 && (mark[2] & 0x80) == 0);
        }
        if (flat) {
            const std::size_t need = std::size_t(width) * 4;
            if (size - pos < need) return truncated(y);
            for (int x = 0; x < width; ++x) toFloat(bytes + pos + std::size_t(x) * 4, rgb + x * 3);
            pos += need;
            continue;
        }
        const int length = (int(bytes[pos + 2]) << 8) | int(bytes[pos + 3]);
        if (length != width) {
            return "corrupt pixel data: scanline " + std::to_string(y) + " says it holds " +
                   std::to_string(length) + " pixels, the image is " + std::to_string(width) +
                   " wide";
        }
        pos += 4;
        for (int c = 0; c < 4; ++c) {
            for (int x = 0; x < width;) {
                if (pos >= size) return truncated(y);
                const int code = bytes[pos++];
                const bool run = code > 128;
                const int count = run ? code - 128 : code;
                if (count == 0 || count > width - x) {
                    return "corrupt pixel data: a run of " + std::to_string(count) +
                           " in scanline " + std::to_string(y) + " at pixel " + std::to_string(x) +
                           " of " + std::to_string(width);
                }
                if (size - pos < std::size_t(run ? 1 : count)) return truncated(y);
                for (int k = 0; k < count; ++k, ++x)
                    row[std::size_t(x) * 4 + std::size_t(c)] =
                        bytes[run ? pos : pos + std::size_t(k)];
                pos += run ? 1 : std::size_t(count);
            }
        }
        for (int x = 0; x < width; ++x) toFloat(row.data() + std::size_t(x) * 4, rgb + x * 3);
    }
    out.formatName = "hdr";
    out.colourSpace = header.colourSpace;
    return {};
}

}  // namespace pbrlab
