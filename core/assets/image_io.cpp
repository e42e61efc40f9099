#include "assets/image_io.h"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <string_view>
#include <system_error>

#include "assets/image_codecs.h"
#include "util/error.h"

#ifdef _WIN32
#include <process.h>
#define PBRLAB_GETPID _getpid
#else
#include <unistd.h>
#define PBRLAB_GETPID getpid
#endif

namespace pbrlab {

Image flipRows(Image image) {
    const size_t row = size_t(image.width) * size_t(image.channels);
    float* pixels = image.pixels.data();
    for (int top = 0, bottom = image.height - 1; top < bottom; ++top, --bottom)
        std::swap_ranges(pixels + size_t(top) * row, pixels + size_t(top + 1) * row,
                         pixels + size_t(bottom) * row);
    return image;
}

Image halfSize(const Image& image) {
    // Each axis: the destination texel i covers [i, i + 1) * from / to of the source, and each
    // source texel counts by the length of its overlap (a box filter over the exact area).
    struct Tap {
        int source;
        float weight;
    };
    auto taps = [](int from, int to) {
        std::vector<std::vector<Tap>> all(static_cast<size_t>(to));
        const double scale = double(from) / double(to);
        for (int i = 0; i < to; ++i) {
            const double begin = i * scale, end = (i + 1) * scale;
            for (int s = int(begin); s < from && s < end; ++s) {
                const double overlap = std::min(end, double(s + 1)) - std::max(begin, double(s));
                if (overlap > 0) all[size_t(i)].push_back({s, float(overlap / scale)});
            }
        }
        return all;
    };
    const int channels = image.channels;
    Image half;
    half.width = std::max(1, image.width / 2);
    half.height = std::max(1, image.height / 2);
    half.channels = channels;
    half.sourceBitsPerChannel = image.sourceBitsPerChannel;
    half.sourceIsSrgb = image.sourceIsSrgb;
    const auto across = taps(image.width, half.width), down = taps(image.height, half.height);
    // Rows first (full height, half width), then columns.
    std::vector<float> rows(size_t(half.width) * size_t(image.height) * size_t(channels), 0.0f);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < half.width; ++x)
            for (const Tap& t : across[size_t(x)])
                for (int c = 0; c < channels; ++c)
                    rows[(size_t(y) * size_t(half.width) + size_t(x)) * size_t(channels) +
                         size_t(c)] +=
                        t.weight *
                        image.pixels[(size_t(y) * size_t(image.width) + size_t(t.source)) *
                                         size_t(channels) +
                                     size_t(c)];
    half.pixels.assign(size_t(half.width) * size_t(half.height) * size_t(channels), 0.0f);
    for (int y = 0; y < half.height; ++y)
        for (const Tap& t : down[size_t(y)])
            for (size_t i = 0; i < size_t(half.width) * size_t(channels); ++i)
                half.pixels[size_t(y) * size_t(half.width) * size_t(channels) + i] +=
                    t.weight * rows[size_t(t.source) * size_t(half.width) * size_t(channels) + i];
    return half;
}

namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& path) {
    return "'" + path.string() + "'";
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

}  // namespace

std::string pngColourSpaceName(const char* text, bool srgbChunk, double fileGamma) {
    if (text) return text;
    if (srgbChunk) return "sRGB";
    if (fileGamma > 0.0) {
        const float g = std::round(100.0f * float(1.0 / fileGamma)) / 100.0f;
        if (g == 1.0f) return "linear";
        char name[32];
        std::snprintf(name, sizeof name, "Gamma%.2g", double(g));
        return name;
    }
    return "sRGB";
}

namespace {

// What the PNG chunk structure says, beyond what the decoders report.
struct PngScan {
    // A chunk before the pixel data says how to interpret the values: sRGB, gAMA, iCCP, or
    // OIIO's own "oiio:ColorSpace" text. Needed because both PNG paths report "sRGB" (OIIO's
    // name) for an sRGB chunk and for a file without any colour information.
    bool colourTagged = false;
    // Empty when the chunks run intact up to IEND. libpng stops reading after the pixel data,
    // so a file cut after its last IDAT chunk would otherwise pass as complete.
    std::string problem;
};

PngScan scanPng(const unsigned char* bytes, std::size_t size) {
    PngScan scan;
    const unsigned char pngSig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size < 8 || !std::equal(bytes, bytes + 8, pngSig)) {
        scan.problem = "not a PNG signature";
        return scan;
    }
    bool beforeData = true;
    std::size_t pos = 8;
    while (pos + 12 <= size) {
        const unsigned char* head = bytes + pos;
        const std::uint32_t length = (std::uint32_t(head[0]) << 24) |
                                     (std::uint32_t(head[1]) << 16) |
                                     (std::uint32_t(head[2]) << 8) | std::uint32_t(head[3]);
        const std::string type(reinterpret_cast<const char*>(head + 4), 4);
        const std::uintmax_t next = std::uintmax_t(pos) + 12 + std::uintmax_t(length);
        if (length > 0x7fffffffu || next > size) {
            scan.problem = "truncated: the file ends inside its " + type + " chunk";
            return scan;
        }
        if (type == "IEND") return scan;
        if (type == "IDAT") beforeData = false;
        if (beforeData && (type == "sRGB" || type == "gAMA" || type == "iCCP"))
            scan.colourTagged = true;
        if (beforeData && (type == "tEXt" || type == "iTXt" || type == "zTXt")) {
            const std::string key = "oiio:ColorSpace";
            const std::size_t n = std::min<std::size_t>(length, key.size() + 1);
            if (std::string(reinterpret_cast<const char*>(head + 8), n) == key + '\0')
                scan.colourTagged = true;
        }
        pos = std::size_t(next);
    }
    scan.problem = "truncated: the file ends before its IEND chunk";
    return scan;
}

// Whether OIIO's colour-space name means display-encoded (sRGB-like) values.
bool colourSpaceIsSrgb(const std::string& name) {
    const std::string s = lower(name);
    if (s.rfind("srgb", 0) == 0) return true;  // "sRGB", "srgb_texture", "sRGB - Texture"
    // A PNG gAMA chunk: "Gamma2.2" (OpenImageIO 2.4), "GammaCorrected2.2" (earlier versions).
    for (const std::string_view prefix : {"gammacorrected", "gamma"}) {
        if (s.rfind(prefix, 0) == 0) {
            const double gamma = std::atof(s.c_str() + prefix.size());
            return gamma >= 2.0 && gamma <= 2.6;
        }
    }
    return false;  // "Linear", "lin_srgb", "scene_linear", "ACEScg", ...
}

// ---------------------------------------------------------------- reading

// The whole file, or its first `limit` bytes.
std::vector<unsigned char> readBytes(const fs::path& path,
                                     std::size_t limit = std::numeric_limits<std::size_t>::max()) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    const std::streamoff size = in.tellg();
    if (!in || size < 0) return {};
    std::vector<unsigned char> bytes(std::min(std::size_t(size), limit));
    in.seekg(0);
    in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
    bytes.resize(std::size_t(in.gcount()));
    return bytes;
}

bool isPngSignature(const std::vector<unsigned char>& head) {
    const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    return head.size() >= 8 && std::equal(signature, signature + 8, head.begin());
}

bool isRadianceSignature(const std::vector<unsigned char>& head) {
    return head.size() >= 2 && head[0] == '#' && head[1] == '?';
}

// pbrlab's rules for what the values mean: the file's own tag if it has one; otherwise integer
// 8-bit data is display-encoded (sRGB) as PNG and JPEG files in the wild are, 16-bit grayscale
// is data (height, roughness, ...), 16-bit colour is sRGB, and float data is linear.
Image interpret(DecodedImage decoded, const PngScan* png) {
    Image image = std::move(decoded.image);
    const bool tagged = png ? png->colourTagged : !decoded.colourSpace.empty();
    if (tagged) {
        image.sourceIsSrgb = colourSpaceIsSrgb(decoded.colourSpace);
    } else if (image.sourceBitsPerChannel == 8) {
        image.sourceIsSrgb = true;
    } else if (image.sourceBitsPerChannel == 16) {
        image.sourceIsSrgb = image.channels >= 3;
    } else {
        image.sourceIsSrgb = false;
    }
    return image;
}

// Decodes the file `path`, or `memory` when given (then `path` only names it and picks the
// format by its extension, for OpenImageIO). The first bytes pick the codec.
Image decode(const fs::path& path, const std::string& what,
             const std::vector<unsigned char>* memory, ImageCodecs codecs) {
    std::vector<unsigned char> fileBytes;
    if (!memory) fileBytes = readBytes(path, 8);
    const std::vector<unsigned char>& head = memory ? *memory : fileBytes;
    const bool pngSignature = isPngSignature(head);
    const bool inProcess =
        codecs == ImageCodecs::Default && (pngSignature || isRadianceSignature(head));
    if (!memory && (inProcess || pngSignature)) fileBytes = readBytes(path);
    const std::vector<unsigned char>& bytes = memory ? *memory : fileBytes;

    DecodedImage decoded;
    std::string problem;
    RadianceHeader radiance;
    if (inProcess && pngSignature) {
        const PngScan png = scanPng(bytes.data(), bytes.size());
        if (!png.problem.empty()) throw Error(what + png.problem);
        problem = decodePng(bytes.data(), bytes.size(), decoded);
        if (problem.empty()) return interpret(std::move(decoded), &png);
    } else if (inProcess && readRadianceHeader(bytes.data(), bytes.size(), radiance)) {
        problem = decodeRadiance(bytes.data(), bytes.size(), radiance, decoded);
        if (problem.empty()) return interpret(std::move(decoded), nullptr);
    } else {
        problem = decodeOtherFormat(what, path.string(), memory, decoded);
        if (problem.empty()) {
            if (decoded.formatName != "png") return interpret(std::move(decoded), nullptr);
            const PngScan png = scanPng(bytes.data(), bytes.size());
            if (png.problem.empty()) return interpret(std::move(decoded), &png);
            problem = png.problem;
        }
    }
    throw Error(what + problem);
}

template <typename T>
std::vector<T> toCodes(const std::vector<float>& in) {
    constexpr double maxCode = double(std::numeric_limits<T>::max());
    std::vector<T> out(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) {
        float v = in[i];
        if (!(v > 0.0f)) v = 0.0f;  // also NaN
        if (v > 1.0f) v = 1.0f;
        out[i] = T(std::lround(double(v) * maxCode));
    }
    return out;
}

// Empty on success, otherwise why not.
std::string writeBytes(const fs::path& file, const std::vector<unsigned char>& bytes) {
    std::FILE* out = std::fopen(file.c_str(), "wb");
    if (!out) return "cannot create the file (" + std::string(std::strerror(errno)) + ")";
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), out) == bytes.size();
    const int error = errno;
    if (std::fclose(out) != 0 || !written)
        return "writing failed (" + std::string(std::strerror(written ? errno : error)) + ")";
    return {};
}

}  // namespace

Image readImage(const fs::path& path, ImageCodecs codecs) {
    const std::string what = "cannot read image " + quoted(path) + ": ";
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw Error(what + "file not found");
    if (fs::is_directory(status)) throw Error(what + "it is a directory, not a file");
    const auto fileSize = fs::file_size(path, ec);
    if (!ec && fileSize == 0) throw Error(what + "the file is empty (0 bytes)");
    return decode(path, what, nullptr, codecs);
}

Image readImage(const fs::path& path) {
    return readImage(path, ImageCodecs::Default);
}

Image decodeImage(const std::vector<unsigned char>& bytes, const std::string& name,
                  ImageCodecs codecs) {
    const std::string what = "cannot decode image " + name + ": ";
    if (bytes.empty()) throw Error(what + "no data (0 bytes)");
    return decode(name, what, &bytes, codecs);
}

Image decodeImage(const std::vector<unsigned char>& bytes, const std::string& name) {
    return decodeImage(bytes, name, ImageCodecs::Default);
}

Image readTexture(const TextureSource& source) {
    if (source.encoded) return decodeImage(*source.encoded, source.key + source.extension);
    if (source.file.empty()) throw Error("texture " + source.key + ": no file and no data");
    return readImage(source.file);
}

FileDepth defaultDepthFor(const fs::path& path) {
    const std::string ext = lower(path.extension().string());
    return (ext == ".exr" || ext == ".hdr") ? FileDepth::Float32 : FileDepth::Uint8;
}

void writeImage(const fs::path& path, const Image& image, FileDepth depth, bool markSrgb,
                ImageCodecs codecs) {
    const std::string what = "cannot write image " + quoted(path) + ": ";
    if (image.width <= 0 || image.height <= 0 || image.channels <= 0) {
        throw Error(what + "the image has zero size (" + std::to_string(image.width) + " x " +
                    std::to_string(image.height) + ", " + std::to_string(image.channels) +
                    " channels)");
    }
    const std::size_t values =
        std::size_t(image.width) * std::size_t(image.height) * std::size_t(image.channels);
    if (image.pixels.size() != values) {
        throw Error(what + "the pixel buffer holds " + std::to_string(image.pixels.size()) +
                    " values, expected " + std::to_string(values));
    }
    const std::string extension = lower(path.extension().string());
    const bool png = codecs == ImageCodecs::Default && extension == ".png";
    const bool exr = codecs == ImageCodecs::Default && extension == ".exr" && image.channels <= 4;
    if (png && depth == FileDepth::Float32)  // refused before anything is made
        throw Error(what + "the png format cannot store 32-bit float data");
    if (exr && depth != FileDepth::Float32)
        throw Error(what + "the openexr format cannot store " + fileDepthName(depth) + " data");
    const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (std::error_code ec; !fs::is_directory(parent, ec)) {
        throw Error(what + "the directory '" + parent.string() + "' does not exist");
    }

    // Code values are made before any file exists (clamped, NaN as 0, rounded to nearest).
    std::vector<std::uint8_t> codes8;
    std::vector<std::uint16_t> codes16;
    const void* codes = nullptr;
    if (depth == FileDepth::Uint8) {
        codes8 = toCodes<std::uint8_t>(image.pixels);
        codes = codes8.data();
    } else if (depth == FileDepth::Uint16) {
        codes16 = toCodes<std::uint16_t>(image.pixels);
        codes = codes16.data();
    }

    // The pixels go to a temporary file beside the final one (same file system, so the rename
    // below is atomic): a failed write never leaves a half-written file behind.
    static std::atomic<unsigned> counter{0};
    const fs::path temp =
        path.parent_path() / ("." + path.filename().string() + ".tmp" +
                              std::to_string(PBRLAB_GETPID()) + "-" + std::to_string(counter++));
    auto discard = [&temp] {
        std::error_code ignored;
        fs::remove(temp, ignored);
    };
    std::string problem;
    if (png) {
        std::vector<unsigned char> file;
        problem = encodePng(image, depth, codes, markSrgb, file);
        if (problem.empty()) problem = writeBytes(temp, file);
    } else if (exr) {
        problem = writeExr(temp, image);
    } else {
        problem =
            writeOtherFormat(what, path.string(), temp.string(), image, depth, codes, markSrgb);
    }
    if (!problem.empty()) {
        discard();
        throw Error(what + problem);
    }

    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) {
        discard();
        throw Error(what + "cannot move the finished file into place (" + ec.message() + ")");
    }
}

void writeImage(const fs::path& path, const Image& image, FileDepth depth, bool markSrgb) {
    writeImage(path, image, depth, markSrgb, ImageCodecs::Default);
}

}  // namespace pbrlab
