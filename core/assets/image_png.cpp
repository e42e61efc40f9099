// PNG through libpng, the library OpenImageIO's own PNG plugin is built on: the same
// expansions (palette to RGB, 1/2/4-bit grey to 8 bits, tRNS to alpha) give the same values,
// straight alpha as stored, 16-bit data kept 16-bit.
//
// libpng reports errors by longjmp to the last setjmp. The functions that call setjmp below hold
// nothing that needs a destructor, so the jump skips no C++ clean-up; buffers live in callers.
#include <png.h>

#include <bit>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "assets/image_codecs.h"

namespace pbrlab {
namespace {

struct PngState {
    const unsigned char* data = nullptr;  // reading: the encoded file
    std::size_t size = 0, position = 0;
    std::vector<unsigned char>* file = nullptr;  // writing: the encoded file
    std::string error;
};

[[noreturn]] void onError(png_structp png, png_const_charp message) {
    static_cast<PngState*>(png_get_error_ptr(png))->error = message;
    png_longjmp(png, 1);
}

// libpng's warnings (a damaged ancillary chunk it skips, an odd ICC profile) change nothing
// pbrlab reads; OpenImageIO dropped them too.
void onWarning(png_structp, png_const_charp) {}

void readBytes(png_structp png, png_bytep out, png_size_t count) {
    auto* state = static_cast<PngState*>(png_get_io_ptr(png));
    if (count > state->size - state->position) png_error(png, "truncated: the file ends early");
    std::memcpy(out, state->data + state->position, count);
    state->position += count;
}

void writeBytes(png_structp png, png_bytep in, png_size_t count) {
    auto* state = static_cast<PngState*>(png_get_io_ptr(png));
    state->file->insert(state->file->end(), in, in + count);
}

void flushNothing(png_structp) {}

// Owns libpng's structures (png_destroy_* takes null pointers).
struct PngRead {
    png_structp png = nullptr;
    png_infop info = nullptr;
    ~PngRead() { png_destroy_read_struct(&png, &info, nullptr); }
};
struct PngWrite {
    png_structp png = nullptr;
    png_infop info = nullptr;
    ~PngWrite() { png_destroy_write_struct(&png, &info); }
};

// What the header says, after the expansions.
struct PngHeader {
    png_uint_32 width = 0, height = 0;
    int channels = 0, bits = 0;
    std::size_t rowBytes = 0;
    bool srgbChunk = false;
    double fileGamma = 0.0;                 // gAMA, 0 when absent
    const char* colourSpaceText = nullptr;  // an "oiio:ColorSpace" text chunk, owned by libpng
};

bool readHeader(PngRead& r, PngHeader& h) {
    if (setjmp(png_jmpbuf(r.png))) return false;
    png_read_info(r.png, r.info);
    png_set_expand(r.png);
    png_set_interlace_handling(r.png);  // Adam7 files come out as whole rows
    if constexpr (std::endian::native == std::endian::little) png_set_swap(r.png);
    png_read_update_info(r.png, r.info);
    h.width = png_get_image_width(r.png, r.info);
    h.height = png_get_image_height(r.png, r.info);
    h.channels = png_get_channels(r.png, r.info);
    h.bits = png_get_bit_depth(r.png, r.info);
    h.rowBytes = png_get_rowbytes(r.png, r.info);
    int intent = 0;
    h.srgbChunk = png_get_sRGB(r.png, r.info, &intent) != 0;
    if (!png_get_gAMA(r.png, r.info, &h.fileGamma)) h.fileGamma = 0.0;
    png_textp text = nullptr;
    const int texts = png_get_text(r.png, r.info, &text, nullptr);
    for (int i = 0; i < texts; ++i)
        if (std::strcmp(text[i].key, "oiio:ColorSpace") == 0) h.colourSpaceText = text[i].text;
    return true;
}

bool readPixels(PngRead& r, png_bytepp rows) {
    if (setjmp(png_jmpbuf(r.png))) return false;
    png_read_image(r.png, rows);
    png_read_end(r.png, nullptr);  // through IEND: a file cut after its pixel data is an error
    return true;
}

std::string colourSpaceName(const PngHeader& h) {
    return pngColourSpaceName(h.colourSpaceText, h.srgbChunk, h.fileGamma);
}

template <typename T>
void toFloat(const std::vector<unsigned char>& raw, std::vector<float>& out) {
    constexpr float scale = float(std::numeric_limits<T>::max());
    const std::size_t n = raw.size() / sizeof(T);
    out.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        T v;
        std::memcpy(&v, raw.data() + i * sizeof(T), sizeof(T));
        out[i] = float(v) / scale;
    }
}

bool encode(PngWrite& w, const PngHeader& h, bool markSrgb, png_bytepp rows) {
    if (setjmp(png_jmpbuf(w.png))) return false;
    const int colourType = h.channels == 1   ? PNG_COLOR_TYPE_GRAY
                           : h.channels == 2 ? PNG_COLOR_TYPE_GRAY_ALPHA
                           : h.channels == 3 ? PNG_COLOR_TYPE_RGB
                                             : PNG_COLOR_TYPE_RGB_ALPHA;
    png_set_IHDR(w.png, w.info, h.width, h.height, h.bits, colourType, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    // Display-encoded values carry an sRGB chunk (with the gAMA and cHRM it implies, for
    // readers that know only those); data carries gAMA 1.0, which readers take as linear.
    if (markSrgb)
        png_set_sRGB_gAMA_and_cHRM(w.png, w.info, PNG_sRGB_INTENT_PERCEPTUAL);
    else
        png_set_gAMA(w.png, w.info, 1.0);
    png_write_info(w.png, w.info);
    if constexpr (std::endian::native == std::endian::little)
        if (h.bits == 16) png_set_swap(w.png);
    png_write_image(w.png, rows);
    png_write_end(w.png, nullptr);
    return true;
}

}  // namespace

std::string decodePng(const unsigned char* bytes, std::size_t size, DecodedImage& out) {
    PngState state;
    state.data = bytes;
    state.size = size;
    PngRead r;
    r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, onError, onWarning);
    if (r.png) r.info = png_create_info_struct(r.png);
    if (!r.png || !r.info) return "libpng could not start (out of memory)";
    png_set_read_fn(r.png, &state, readBytes);

    PngHeader h;
    if (!readHeader(r, h)) return "not a readable PNG file (" + state.error + ")";
    const std::size_t count = std::size_t(h.width) * std::size_t(h.height);
    if (count > kMaxImageValues / std::size_t(h.channels)) {
        return "too large (" + std::to_string(h.width) + " x " + std::to_string(h.height) + " x " +
               std::to_string(h.channels) + ")";
    }
    std::vector<unsigned char> raw(h.rowBytes * h.height);
    std::vector<png_bytep> rows(h.height);
    for (png_uint_32 y = 0; y < h.height; ++y) rows[y] = raw.data() + h.rowBytes * y;
    if (!readPixels(r, rows.data())) return "truncated or corrupt pixel data (" + state.error + ")";

    Image& image = out.image;
    image.width = int(h.width);
    image.height = int(h.height);
    image.channels = h.channels;
    image.sourceBitsPerChannel = h.bits;
    if (h.bits == 16)
        toFloat<std::uint16_t>(raw, image.pixels);
    else
        toFloat<std::uint8_t>(raw, image.pixels);
    out.formatName = "png";
    out.colourSpace = colourSpaceName(h);
    return {};
}

std::string encodePng(const Image& image, FileDepth depth, const void* codes, bool markSrgb,
                      std::vector<unsigned char>& file) {
    if (depth == FileDepth::Float32) return "the png format cannot store 32-bit float data";
    if (image.channels > 4) {
        return "the png format cannot store " + std::to_string(image.channels) + " channels of " +
               fileDepthName(depth) + " data";
    }
    PngState state;
    state.file = &file;
    PngWrite w;
    w.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, onError, onWarning);
    if (w.png) w.info = png_create_info_struct(w.png);
    if (!w.png || !w.info) return "libpng could not start (out of memory)";
    png_set_write_fn(w.png, &state, writeBytes, flushNothing);

    PngHeader h;
    h.width = png_uint_32(image.width);
    h.height = png_uint_32(image.height);
    h.channels = image.channels;
    h.bits = depth == FileDepth::Uint16 ? 16 : 8;
    h.rowBytes = std::size_t(image.width) * std::size_t(image.channels) * std::size_t(h.bits / 8);
    std::vector<png_bytep> rows(h.height);
    auto* base = static_cast<unsigned char*>(const_cast<void*>(codes));
    for (png_uint_32 y = 0; y < h.height; ++y) rows[y] = base + h.rowBytes * y;
    if (!encode(w, h, markSrgb, rows.data())) return "encoding failed (" + state.error + ")";
    return {};
}

}  // namespace pbrlab
