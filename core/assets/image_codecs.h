// The codecs behind assets/image_io.h. PNG (every render, texture and glTF image) goes through
// libpng, Radiance HDR (the environments) through a reader of pbrlab's own, and EXR writing
// (precomputed maps, --out x.exr) through OpenEXRCore, all in this process; every other format,
// and reading EXR, goes to OpenImageIO, which lives in libpbrlab_oiio.so and is opened on first
// use, so that no command pays OpenImageIO's start-up (its ~260 shared libraries and their
// initialisers: 0.3-0.5 s, and its first use as much again) unless a file needs it.
// docs/architecture.md ("Start-up") has the measurements behind the choice.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "assets/image_io.h"

namespace pbrlab {

// What a decoder found, before pbrlab's rules for untagged files (assets/image_io.cpp) are applied.
struct DecodedImage {
    Image image;              // pixels scaled as image.h says; sourceBitsPerChannel set
    std::string formatName;   // "png", "hdr", "openexr", ... (OpenImageIO's names)
    std::string colourSpace;  // the file's colour-space tag, in OpenImageIO's names ("sRGB",
                              // "Linear", "GammaCorrected2.2", ...); empty when it has none
};

// Which code reads and writes: Default picks per format as above; OpenImageIO sends every
// format there (tests compare the two paths, benchmarks time them).
enum class ImageCodecs { Default, OpenImageIO };

Image readImage(const std::filesystem::path& path, ImageCodecs codecs);
Image decodeImage(const std::vector<unsigned char>& bytes, const std::string& name,
                  ImageCodecs codecs);
void writeImage(const std::filesystem::path& path, const Image& image, FileDepth depth,
                bool markSrgb, ImageCodecs codecs);

// The codec of every other format: the platform's (core/native/image_oiio_loader.cpp opens
// OpenImageIO on the desktop). Decodes the file `name`, or the encoded bytes at `memory` when
// not null (then `name`'s extension picks the format); writes `image` (its pixels, or `codes`
// for integer depths as in encodePng) to the file `temp` in the format `file`'s extension
// names. Each returns an empty string on success, otherwise the reason; each throws
// pbrlab::Error starting with `what` when the platform has no such codec.
std::string decodeOtherFormat(const std::string& what, const std::string& name,
                              const std::vector<unsigned char>* memory, DecodedImage& out);
std::string writeOtherFormat(const std::string& what, const std::string& file,
                             const std::string& temp, const Image& image, FileDepth depth,
                             const void* codes, bool markSrgb);
// Whether this process has opened libpbrlab_oiio.so (and so OpenImageIO).
bool openImageIoLoaded();

// Largest image pbrlab agrees to hold (floats): 2^30 values = 4 GiB. A corrupt header claiming
// more is reported instead of ending in std::bad_alloc.
constexpr std::size_t kMaxImageValues = std::size_t(1) << 30;

inline const char* fileDepthName(FileDepth depth) {
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

// The in-process codecs. Each returns an empty string on success, otherwise what is wrong
// (without the file's name, which the caller puts in front).
std::string decodePng(const unsigned char* bytes, std::size_t size, DecodedImage& out);
// `codes` holds width * height * channels values of the depth's type (uint8_t or uint16_t).
std::string encodePng(const Image& image, FileDepth depth, const void* codes, bool markSrgb,
                      std::vector<unsigned char>& file);

// The colour-space name OpenImageIO 2.4 gives a PNG file's chunks, so one set of rules
// (assets/image_io.cpp) interprets both PNG paths: its "oiio:ColorSpace" text chunk first
// (null: none), then sRGB, then gAMA (`fileGamma`, 0 when absent; rounded to hundredths, as
// OpenImageIO does), else OpenImageIO's PNG default "sRGB" (image_io.cpp's chunk scan tells an
// untagged file from a tagged one).
std::string pngColourSpaceName(const char* text, bool srgbChunk, double fileGamma);

// 32-bit float OpenEXR (1 to 4 channels), straight to `file`.
std::string writeExr(const std::filesystem::path& file, const Image& image);

// A Radiance file's header: `standard` when it is the variant decodeRadiance takes (RGBE
// pixels, rows top to bottom); other variants go to OpenImageIO.
struct RadianceHeader {
    bool standard = false;
    int width = 0, height = 0;
    std::size_t dataStart = 0;  // offset of the first scanline
    std::string colourSpace;    // from the GAMMA line, in OpenImageIO's names
};
// Whether the file starts with a header of that variant.
bool readRadianceHeader(const unsigned char* bytes, std::size_t size, RadianceHeader& out);
std::string decodeRadiance(const unsigned char* bytes, std::size_t size,
                           const RadianceHeader& header, DecodedImage& out);

}  // namespace pbrlab
