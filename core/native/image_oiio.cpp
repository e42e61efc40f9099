// libpbrlab_oiio.so: image files through OpenImageIO, for the formats pbrlab does not read and
// write in-process (image_codecs.h). Only this file includes OpenImageIO; the library is
// opened on first use. Nothing here throws across the boundary: reasons come back as strings.
#include "native/image_oiio.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>

namespace pbrlab {
namespace {

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

int bitsFor(OIIO::TypeDesc format) {
    if (format == OIIO::TypeDesc::UINT8) return 8;
    if (format == OIIO::TypeDesc::UINT16) return 16;
    return 32;
}

template <typename T>
void toFloat(const std::vector<T>& in, std::vector<float>& out) {
    constexpr float scale = float(std::numeric_limits<T>::max());
    out.resize(in.size());
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = float(in[i]) / scale;
}

std::string decode(const std::string& name, const std::vector<unsigned char>* memory,
                   DecodedImage& out) try {
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
    auto in = OIIO::ImageInput::open(name, &config);
    if (!in) return "not a readable image file (" + oiioReason(OIIO::geterror()) + ")";

    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
        return "zero size (" + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
               ", " + std::to_string(spec.nchannels) + " channels)";
    }
    if (spec.deep) return "deep images are not supported";
    if (spec.depth > 1) return "volume images (depth > 1) are not supported";
    const std::size_t count = std::size_t(spec.width) * std::size_t(spec.height);
    if (count > kMaxImageValues / std::size_t(spec.nchannels)) {
        return "too large (" + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
               " x " + std::to_string(spec.nchannels) + ")";
    }

    Image& image = out.image;
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
        return "truncated or corrupt pixel data (" + reason + ")";
    }
    image.sourceBitsPerChannel = uniform ? bitsFor(spec.format) : 32;
    out.formatName = lower(in->format_name());
    out.colourSpace = spec.get_string_attribute("oiio:ColorSpace");
    in->close();
    return {};
} catch (const std::exception& e) {
    return std::string("OpenImageIO failed (") + e.what() + ")";
}

std::string write(const std::string& file, const std::string& temp, const Image& image,
                  FileDepth depth, const void* codes, bool markSrgb) try {
    const OIIO::TypeDesc format = depth == FileDepth::Uint8    ? OIIO::TypeDesc::UINT8
                                  : depth == FileDepth::Uint16 ? OIIO::TypeDesc::UINT16
                                                               : OIIO::TypeDesc::FLOAT;
    // The writer is chosen by the final name's extension; the pixels go to `temp`.
    auto out = OIIO::ImageOutput::create(file);
    if (!out) {
        const std::size_t dot = file.find_last_of('.');
        const std::string extension = dot == std::string::npos ? "" : file.substr(dot);
        return "no image writer for the extension '" + extension + "' (" +
               oiioReason(OIIO::geterror()) + ")";
    }
    // Formats known not to hold the depth are refused before a file is created (OIIO would
    // silently convert); for other formats the spec OIIO settles on is checked after open.
    const std::string formatName = out->format_name();
    const bool depthKnownBad =
        (formatName == "png" && depth == FileDepth::Float32) ||
        (formatName == "jpeg" && depth != FileDepth::Uint8) ||
        ((formatName == "openexr" || formatName == "hdr") && depth != FileDepth::Float32);
    if (depthKnownBad) {
        return "the " + formatName + " format cannot store " + fileDepthName(depth) + " data";
    }

    OIIO::ImageSpec spec(image.width, image.height, image.channels, format);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // store colour as given, never un-premultiply
    if (markSrgb) {
        spec.attribute("oiio:ColorSpace", "sRGB");
    } else if (depth != FileDepth::Float32) {
        spec.attribute("oiio:ColorSpace", "Linear");  // PNG: a gAMA 1.0 chunk says "data"
    }
    if (!out->open(temp, spec))
        return "cannot create the file (" + oiioReason(out->geterror()) + ")";
    const OIIO::ImageSpec& actual = out->spec();
    if (actual.format != format || actual.nchannels != image.channels) {
        out->close();
        out->geterror();
        return "the " + formatName + " format cannot store " + std::to_string(image.channels) +
               " channels of " + fileDepthName(depth) + " data";
    }
    const void* data = depth == FileDepth::Float32 ? image.pixels.data() : codes;
    bool ok = out->write_image(format, data);
    ok = out->close() && ok;
    if (!ok) return "writing failed (" + oiioReason(out->geterror()) + ")";
    return {};
} catch (const std::exception& e) {
    return std::string("OpenImageIO failed (") + e.what() + ")";
}

}  // namespace
}  // namespace pbrlab

extern "C" __attribute__((visibility("default"))) const pbrlab::OiioInterface*
pbrlab_oiio_interface() {
    static const pbrlab::OiioInterface table{pbrlab::OiioInterface::kVersion, &pbrlab::decode,
                                             &pbrlab::write};
    return &table;
}
