#include "pbrlab/image.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string_view>
#include <system_error>

#include "pbrlab/error.h"

#ifdef _WIN32
#include <process.h>
#define PBRLAB_GETPID _getpid
#else
#include <unistd.h>
#define PBRLAB_GETPID getpid
#endif

namespace pbrlab {

Image flipRows(const Image& image) {
    Image flipped = image;
    const size_t row = size_t(image.width) * size_t(image.channels);
    for (int y = 0; y < image.height; ++y)
        std::copy_n(image.pixels.data() + size_t(image.height - 1 - y) * row, row,
                    flipped.pixels.data() + size_t(y) * row);
    return flipped;
}

namespace {

namespace fs = std::filesystem;

// Largest image we agree to hold (floats): 2^30 values = 4 GiB. A corrupt header claiming more
// is reported instead of ending in std::bad_alloc.
constexpr std::size_t kMaxValues = std::size_t(1) << 30;

std::string quoted(const fs::path& path) {
    return "'" + path.string() + "'";
}

// OIIO keeps an error string per thread (and per ImageInput/ImageOutput); take it, so nothing is
// left pending, and never return an empty reason.
std::string oiioReason(const std::string& text) {
    std::string s;
    for (char c : text) {
        if (c == '\n')
            s += "; ";
        else
            s += c;
    }
    while (!s.empty() && (s.back() == ' ' || s.back() == ';')) s.pop_back();
    return s.empty() ? std::string("no further detail from OpenImageIO") : s;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

// What the PNG chunk structure says, beyond what OIIO reports.
struct PngScan {
    // A chunk before the pixel data says how to interpret the values: sRGB, gAMA, iCCP, or
    // OIIO's own "oiio:ColorSpace" text. Needed because OIIO's PNG reader reports "sRGB" both
    // for an sRGB chunk and for a file without any colour information.
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

std::vector<unsigned char> readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<unsigned char>(std::istreambuf_iterator<char>(in),
                                      std::istreambuf_iterator<char>());
}

// Whether OIIO's colour-space name means display-encoded (sRGB-like) values.
bool colourSpaceIsSrgb(const std::string& name) {
    const std::string s = lower(name);
    if (s.rfind("srgb", 0) == 0) return true;  // "sRGB", "srgb_texture", "sRGB - Texture"
    if (s.rfind("gammacorrected", 0) == 0) {   // "GammaCorrected2.2" from a PNG gAMA chunk
        const double gamma = std::atof(s.c_str() + std::string_view("gammacorrected").size());
        return gamma >= 2.0 && gamma <= 2.6;
    }
    return false;  // "Linear", "lin_srgb", "scene_linear", "ACEScg", ...
}

int bitsFor(OIIO::TypeDesc format) {
    if (format == OIIO::TypeDesc::UINT8) return 8;
    if (format == OIIO::TypeDesc::UINT16) return 16;
    return 32;
}

std::string depthName(FileDepth depth) {
    switch (depth) {
        case FileDepth::Uint8:
            return "8-bit";
        case FileDepth::Uint16:
            return "16-bit";
        case FileDepth::Float32:
            return "32-bit float";
    }
    return "?";
}

template <typename T>
void toFloat(const std::vector<T>& in, std::vector<float>& out) {
    constexpr float scale = float(std::numeric_limits<T>::max());
    out.resize(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = float(in[i]) / scale;
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

// Decodes from the file `path`, or from `memory` when given (then `path` only names it and
// picks the format by its extension).
Image decode(const fs::path& path, const std::string& what,
             const std::vector<unsigned char>* memory) {
    // Keep straight alpha as stored: OIIO would otherwise premultiply PNG/TGA colour by alpha.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::Filesystem::IOMemReader> reader;
    if (memory) {
        // OIIO 2.4's readers take the proxy from this attribute (open()'s own proxy
        // argument is ignored by the PNG reader).
        reader = std::make_unique<OIIO::Filesystem::IOMemReader>(memory->data(), memory->size());
        void* proxy = reader.get();
        config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    }
    auto in = OIIO::ImageInput::open(path.string(), &config);
    if (!in) {
        throw Error(what + "not a readable image file (" + oiioReason(OIIO::geterror()) + ")");
    }

    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
        throw Error(what + "zero size (" + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + ", " + std::to_string(spec.nchannels) +
                    " channels)");
    }
    if (spec.deep) throw Error(what + "deep images are not supported");
    if (spec.depth > 1) throw Error(what + "volume images (depth > 1) are not supported");
    const std::size_t count = std::size_t(spec.width) * std::size_t(spec.height);
    if (count > kMaxValues / std::size_t(spec.nchannels)) {
        throw Error(what + "too large (" + std::to_string(spec.width) + " x " +
                    std::to_string(spec.height) + " x " + std::to_string(spec.nchannels) + ")");
    }

    const bool isPng = lower(in->format_name()) == "png";
    PngScan png;
    if (isPng) {
        if (memory) {
            png = scanPng(memory->data(), memory->size());
        } else {
            const std::vector<unsigned char> bytes = readBytes(path);
            png = scanPng(bytes.data(), bytes.size());
        }
    }
    if (!png.problem.empty()) throw Error(what + png.problem);

    Image image;
    image.width = spec.width;
    image.height = spec.height;
    image.channels = spec.nchannels;
    const std::size_t values = count * std::size_t(spec.nchannels);

    // Integer data is read in its own depth and scaled here, so 16-bit keeps every code value.
    const bool uniform = spec.channelformats.empty();
    const OIIO::TypeDesc format = uniform ? spec.format : OIIO::TypeDesc(OIIO::TypeDesc::FLOAT);
    bool ok = false;
    if (format == OIIO::TypeDesc::UINT8) {
        std::vector<std::uint8_t> raw(values);
        ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, raw.data());
        if (ok) toFloat(raw, image.pixels);
    } else if (format == OIIO::TypeDesc::UINT16) {
        std::vector<std::uint16_t> raw(values);
        ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT16, raw.data());
        if (ok) toFloat(raw, image.pixels);
    } else {
        image.pixels.resize(values);
        ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data());
    }
    if (!ok || in->has_error()) {
        const std::string reason = oiioReason(in->geterror());
        in->close();
        OIIO::geterror();  // drop anything left at the global level
        throw Error(what + "truncated or corrupt pixel data (" + reason + ")");
    }
    image.sourceBitsPerChannel = uniform ? bitsFor(spec.format) : 32;

    // How to interpret the values: the file's own tag if it has one; otherwise integer 8-bit
    // data is display-encoded (sRGB) as PNG and JPEG files in the wild are, 16-bit grayscale is
    // data (height, roughness, ...), 16-bit colour is sRGB, and float data is linear.
    const std::string colourSpace = spec.get_string_attribute("oiio:ColorSpace");
    const bool tagged = isPng ? png.colourTagged : !colourSpace.empty();
    in->close();
    if (tagged) {
        image.sourceIsSrgb = colourSpaceIsSrgb(colourSpace);
    } else if (image.sourceBitsPerChannel == 8) {
        image.sourceIsSrgb = true;
    } else if (image.sourceBitsPerChannel == 16) {
        image.sourceIsSrgb = image.channels >= 3;
    } else {
        image.sourceIsSrgb = false;
    }
    return image;
}

}  // namespace

Image readImage(const fs::path& path) {
    const std::string what = "cannot read image " + quoted(path) + ": ";
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw Error(what + "file not found");
    if (fs::is_directory(status)) throw Error(what + "it is a directory, not a file");
    const auto fileSize = fs::file_size(path, ec);
    if (!ec && fileSize == 0) throw Error(what + "the file is empty (0 bytes)");
    return decode(path, what, nullptr);
}

Image decodeImage(const std::vector<unsigned char>& bytes, const std::string& name) {
    const std::string what = "cannot decode image " + name + ": ";
    if (bytes.empty()) throw Error(what + "no data (0 bytes)");
    return decode(name, what, &bytes);
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

void writeImage(const fs::path& path, const Image& image, FileDepth depth, bool markSrgb) {
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

    const OIIO::TypeDesc format = depth == FileDepth::Uint8    ? OIIO::TypeDesc::UINT8
                                  : depth == FileDepth::Uint16 ? OIIO::TypeDesc::UINT16
                                                               : OIIO::TypeDesc::FLOAT;
    // The writer is chosen by the final name's extension; the pixels go to a temporary file
    // beside it (same file system, so the rename below is atomic).
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) {
        throw Error(what + "no image writer for the extension '" + path.extension().string() +
                    "' (" + oiioReason(OIIO::geterror()) + ")");
    }
    // Formats known not to hold the depth are refused before a file is created (OIIO would
    // silently convert); for other formats the spec OIIO settles on is checked after open.
    const std::string formatName = out->format_name();
    const bool depthKnownBad =
        (formatName == "png" && depth == FileDepth::Float32) ||
        (formatName == "jpeg" && depth != FileDepth::Uint8) ||
        ((formatName == "openexr" || formatName == "hdr") && depth != FileDepth::Float32);
    if (depthKnownBad) {
        throw Error(what + "the " + formatName + " format cannot store " + depthName(depth) +
                    " data");
    }
    const fs::path parent = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    if (std::error_code ec; !fs::is_directory(parent, ec)) {
        throw Error(what + "the directory '" + parent.string() + "' does not exist");
    }

    // Code values are made before any file exists (clamped, NaN as 0, rounded to nearest).
    std::vector<std::uint8_t> codes8;
    std::vector<std::uint16_t> codes16;
    const void* data = image.pixels.data();
    if (depth == FileDepth::Uint8) {
        codes8 = toCodes<std::uint8_t>(image.pixels);
        data = codes8.data();
    } else if (depth == FileDepth::Uint16) {
        codes16 = toCodes<std::uint16_t>(image.pixels);
        data = codes16.data();
    }

    static std::atomic<unsigned> counter{0};
    const fs::path temp =
        path.parent_path() / ("." + path.filename().string() + ".tmp" +
                              std::to_string(PBRLAB_GETPID()) + "-" + std::to_string(counter++));
    auto discard = [&temp] {
        std::error_code ignored;
        fs::remove(temp, ignored);
    };

    OIIO::ImageSpec spec(image.width, image.height, image.channels, format);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // store colour as given, never un-premultiply
    if (markSrgb) {
        spec.attribute("oiio:ColorSpace", "sRGB");
    } else if (depth != FileDepth::Float32) {
        spec.attribute("oiio:ColorSpace", "Linear");  // PNG: a gAMA 1.0 chunk says "data"
    }
    if (!out->open(temp.string(), spec)) {
        const std::string reason = oiioReason(out->geterror());
        discard();
        throw Error(what + "cannot create the file (" + reason + ")");
    }
    const OIIO::ImageSpec& actual = out->spec();
    if (actual.format != format || actual.nchannels != image.channels) {
        out->close();
        out->geterror();
        discard();
        throw Error(what + "the " + formatName + " format cannot store " +
                    std::to_string(image.channels) + " channels of " + depthName(depth) + " data");
    }

    bool ok = out->write_image(format, data);
    ok = out->close() && ok;
    if (!ok) {
        const std::string reason = oiioReason(out->geterror());
        discard();
        throw Error(what + "writing failed (" + reason + ")");
    }
    out.reset();

    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) {
        discard();
        throw Error(what + "cannot move the finished file into place (" + ec.message() + ")");
    }
}

}  // namespace pbrlab
