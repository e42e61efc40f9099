// Image files: PNG (read and written, libpng), Radiance HDR (read, pbrlab's own reader) and EXR
// (written, OpenEXRCore) are handled in-process; everything else through OpenImageIO, loaded on
// first use from libpbrlab_oiio.so (core/assets/image_codecs.h says why). Errors are thrown as
// pbrlab::Error naming the file and what is wrong.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "pbrlab/image.h"

namespace pbrlab {

// The same picture with its rows in the other order (GL textures and read-back run bottom-up).
// Takes the image by value: pass std::move(image) to flip without a copy.
Image flipRows(Image image);

// The next mip level of an image: half its size (rounded down, at least 1) as GL sizes levels,
// each texel the mean of the source area it covers (2x2 texels where the size is even;
// fractions of the texels at the seams where it is odd, so the level keeps the image's mean).
Image halfSize(const Image& image);

// Reads any file OpenImageIO knows (PNG and Radiance HDR are told by their first bytes, other
// formats by OpenImageIO, which tries the extension's format first). Values are the stored code
// values scaled to [0, 1] for integer formats (16-bit stays 16-bit precise: no detour through 8
// bits) and unchanged for float formats; no colour conversion is applied (sourceIsSrgb says how
// to interpret them).
Image readImage(const std::filesystem::path& path);

// The same from an encoded file held in memory (an image embedded in a glTF binary). `name`
// names it in errors and, for OpenImageIO's formats, picks one by its extension (e.g.
// "model.glb#image2.jpg").
Image decodeImage(const std::vector<unsigned char>& bytes, const std::string& name);

// Where a material map's pixels come from, read only when a program samples the map: an image
// file, or an encoded image held in memory (embedded in a glTF file).
struct TextureSource {
    std::string key;             // unique, for caches and logs: the file, or "MODEL#image N"
    std::filesystem::path file;  // the image file; empty when `encoded` holds the image
    std::shared_ptr<const std::vector<unsigned char>> encoded;
    std::string extension = ".png";  // of the encoded image (picks the decoder)
    // How uv outside [0, 1] wraps. glTF's default is repeat (a file's sampler may say
    // otherwise); the scene's sphere maps clamp along v, so the poles do not bleed together.
    enum class Wrap { Repeat, Clamp, Mirror };
    Wrap wrapU = Wrap::Repeat, wrapV = Wrap::Clamp;
    bool empty() const { return key.empty(); }
};

// Reads or decodes the source. Throws pbrlab::Error naming the key.
Image readTexture(const TextureSource& source);

enum class FileDepth { Uint8, Uint16, Float32 };

// Writes the pixels as they are. Integer depths clamp to [0, 1] and round to nearest; the
// caller applies any display encoding first. Writes to a temporary file and renames it, so a
// failed write never leaves a half-written file behind.
void writeImage(const std::filesystem::path& path, const Image& image, FileDepth depth,
                bool markSrgb = false);

// The depth a file extension implies: .exr/.hdr -> Float32, otherwise Uint8.
FileDepth defaultDepthFor(const std::filesystem::path& path);

}  // namespace pbrlab
