// assets/image_codecs.h in the browser: PNG read with stb_image and written with
// stb_image_write (libstb-dev's headers); EXR and every format OpenImageIO reads on the
// desktop are refused with a reason naming the file. The page ships only what the project
// generates (scenes, environments from assets/, PNG textures).
#include <cstring>

#include "assets/image_codecs.h"
#include "util/error.h"

#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb_image.h>
#include <stb_image_write.h>

namespace pbrlab {

namespace {

std::uint32_t bigEndian(const unsigned char* p) {
    return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) |
           std::uint32_t(p[3]);
}

// The colour chunks before the pixel data (stb reads none): sRGB, gAMA, and the
// "oiio:ColorSpace" text, named by the rules libpng's path uses (pngColourSpaceName).
std::string colourSpaceOfChunks(const unsigned char* bytes, std::size_t size) {
    bool srgb = false;
    double gamma = 0;
    std::string text;
    bool hasText = false;
    for (std::size_t pos = 8; pos + 12 <= size;) {
        const std::uint32_t length = bigEndian(bytes + pos);
        const std::string type(reinterpret_cast<const char*>(bytes + pos + 4), 4);
        const unsigned char* data = bytes + pos + 8;
        if (length > size - pos - 12 || type == "IDAT") break;
        if (type == "sRGB") srgb = true;
        if (type == "gAMA" && length == 4) gamma = bigEndian(data) / 100000.0;
        const char key[] = "oiio:ColorSpace";
        if (type == "tEXt" && length > sizeof key && std::memcmp(data, key, sizeof key) == 0) {
            text.assign(reinterpret_cast<const char*>(data) + sizeof key, length - sizeof key);
            hasText = true;
        }
        pos += 12 + length;
    }
    return pngColourSpaceName(hasText ? text.c_str() : nullptr, srgb, gamma);
}

}  // namespace

std::string decodePng(const unsigned char* bytes, std::size_t size, DecodedImage& out) {
    int w = 0, h = 0, channels = 0;
    const bool sixteen = stbi_is_16_bit_from_memory(bytes, int(size));
    void* data =
        sixteen
            ? static_cast<void*>(stbi_load_16_from_memory(bytes, int(size), &w, &h, &channels, 0))
            : static_cast<void*>(stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 0));
    if (!data) return std::string("not a readable PNG file (") + stbi_failure_reason() + ")";
    Image& image = out.image;
    image.width = w;
    image.height = h;
    image.channels = channels;
    image.sourceBitsPerChannel = sixteen ? 16 : 8;
    const std::size_t count = std::size_t(w) * std::size_t(h) * std::size_t(channels);
    image.pixels.resize(count);
    for (std::size_t i = 0; i < count; ++i)
        image.pixels[i] = sixteen ? float(static_cast<const std::uint16_t*>(data)[i]) / 65535.0f
                                  : float(static_cast<const std::uint8_t*>(data)[i]) / 255.0f;
    stbi_image_free(data);
    out.formatName = "png";
    out.colourSpace = colourSpaceOfChunks(bytes, size);
    return {};
}

std::string encodePng(const Image& image, FileDepth depth, const void* codes, bool,
                      std::vector<unsigned char>& file) {
    if (depth != FileDepth::Uint8) return "the page writes only 8-bit PNG files";
    auto append = [](void* context, void* data, int size) {
        auto& bytes = *static_cast<std::vector<unsigned char>*>(context);
        const auto* first = static_cast<const unsigned char*>(data);
        bytes.insert(bytes.end(), first, first + size);
    };
    if (!stbi_write_png_to_func(append, &file, image.width, image.height, image.channels, codes,
                                image.width * image.channels))
        return "stb_image_write could not encode it";
    return {};
}

std::string writeExr(const std::filesystem::path&, const Image&) {
    return "the page writes no OpenEXR files";
}

std::string decodeOtherFormat(const std::string& what, const std::string&,
                              const std::vector<unsigned char>*, DecodedImage&) {
    throw Error(what + ": the page reads only PNG and Radiance HDR images");
}

std::string writeOtherFormat(const std::string& what, const std::string&, const std::string&,
                             const Image&, FileDepth, const void*, bool) {
    throw Error(what + ": the page writes only PNG images");
}

bool openImageIoLoaded() {
    return false;
}

}  // namespace pbrlab
