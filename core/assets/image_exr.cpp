// Writing OpenEXR through OpenEXRCore, the C core of Debian's OpenEXR 3: one library on zlib
// that loads in about a millisecond, where OpenImageIO's first use costs about half a second
// (docs/architecture.md, "Start-up"). The file is what OpenImageIO wrote: 32-bit float
// scanlines, ZIP compression, channels named Y / R,G / R,G,B / R,G,B,A, no colour tag (float
// data is linear; OpenImageIO dropped an sRGB mark on float EXR too). Reading EXR stays
// with OpenImageIO (tiles, half floats, layers, deep data: the whole format).
#include <OpenEXR/openexr.h>

#include <cstring>

#include "assets/image_codecs.h"

namespace pbrlab {
namespace {

struct ExrState {
    std::string error;  // the library's own message for the first failure
};

void onExrError(exr_const_context_t context, exr_result_t code, const char* message) {
    void* data = nullptr;
    if (exr_get_user_data(context, &data) != EXR_ERR_SUCCESS || !data) return;
    auto* state = static_cast<ExrState*>(data);
    if (state->error.empty())
        state->error = message && *message ? message : exr_get_default_error_message(code);
}

// Closes the context (and, after a failure, deletes the half-written file) on every path.
struct ExrContext {
    exr_context_t context = nullptr;
    exr_encode_pipeline_t encoder = EXR_ENCODE_PIPELINE_INITIALIZER;
    bool encoderStarted = false;
    ~ExrContext() {
        if (encoderStarted) exr_encoding_destroy(context, &encoder);
        if (context) exr_finish(&context);
    }
};

const char* channelName(int channels, int c) {
    if (channels == 1) return "Y";
    static const char* const kNames[] = {"R", "G", "B", "A"};
    return kNames[c];
}

}  // namespace

std::string writeExr(const std::filesystem::path& file, const Image& image) {
    if (image.channels > 4)
        return "the in-process EXR writer takes 1 to 4 channels, not " +
               std::to_string(image.channels);
    ExrState state;
    exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
    init.error_handler_fn = onExrError;
    init.user_data = &state;
    ExrContext exr;
    auto failed = [&](exr_result_t result, const char* step) {
        const std::string reason =
            state.error.empty() ? exr_get_default_error_message(result) : state.error;
        return std::string("writing failed (OpenEXR, ") + step + ": " + reason + ")";
    };
    exr_result_t r = exr_start_write(&exr.context, file.c_str(), EXR_WRITE_FILE_DIRECTLY, &init);
    if (r != EXR_ERR_SUCCESS) {
        exr.context = nullptr;
        return "cannot create the file (OpenEXR: " +
               (state.error.empty() ? std::string(exr_get_default_error_message(r)) : state.error) +
               ")";
    }
    int part = 0;
    r = exr_add_part(exr.context, "", EXR_STORAGE_SCANLINE, &part);
    if (r == EXR_ERR_SUCCESS)
        r = exr_initialize_required_attr_simple(exr.context, part, image.width, image.height,
                                                EXR_COMPRESSION_ZIP);
    for (int c = 0; c < image.channels && r == EXR_ERR_SUCCESS; ++c)
        r = exr_add_channel(exr.context, part, channelName(image.channels, c), EXR_PIXEL_FLOAT,
                            EXR_PERCEPTUALLY_LINEAR, 1, 1);
    if (r == EXR_ERR_SUCCESS) r = exr_write_header(exr.context);
    int32_t linesPerChunk = 1;
    if (r == EXR_ERR_SUCCESS) r = exr_get_scanlines_per_chunk(exr.context, part, &linesPerChunk);
    if (r != EXR_ERR_SUCCESS) return failed(r, "header");

    const std::size_t pixelBytes = std::size_t(image.channels) * sizeof(float);
    const std::size_t rowBytes = std::size_t(image.width) * pixelBytes;
    const auto* base = reinterpret_cast<const unsigned char*>(image.pixels.data());
    for (int y = 0; y < image.height; y += linesPerChunk) {
        exr_chunk_info_t chunk{};
        r = exr_write_scanline_chunk_info(exr.context, part, y, &chunk);
        if (r == EXR_ERR_SUCCESS) {
            r = exr.encoderStarted
                    ? exr_encoding_update(exr.context, part, &chunk, &exr.encoder)
                    : exr_encoding_initialize(exr.context, part, &chunk, &exr.encoder);
            exr.encoderStarted = exr.encoderStarted || r == EXR_ERR_SUCCESS;
        }
        if (r != EXR_ERR_SUCCESS) return failed(r, "scanlines");
        // The library keeps channels sorted by name; each finds its place in our pixels.
        for (int k = 0; k < exr.encoder.channel_count; ++k) {
            exr_coding_channel_info_t& channel = exr.encoder.channels[k];
            int c = 0;
            while (c < image.channels &&
                   std::strcmp(channel.channel_name, channelName(image.channels, c)) != 0)
                ++c;
            channel.encode_from_ptr =
                base + std::size_t(chunk.start_y) * rowBytes + std::size_t(c) * sizeof(float);
            channel.user_pixel_stride = int32_t(pixelBytes);
            channel.user_line_stride = int32_t(rowBytes);
            channel.user_bytes_per_element = sizeof(float);
            channel.user_data_type = EXR_PIXEL_FLOAT;
        }
        if (!exr.encoder.convert_and_pack_fn)  // chosen once, on the first chunk
            r = exr_encoding_choose_default_routines(exr.context, part, &exr.encoder);
        if (r == EXR_ERR_SUCCESS) r = exr_encoding_run(exr.context, part, &exr.encoder);
        if (r != EXR_ERR_SUCCESS) return failed(r, "scanlines");
    }
    exr_encoding_destroy(exr.context, &exr.encoder);
    exr.encoderStarted = false;
    r = exr_finish(&exr.context);
    exr.context = nullptr;
    if (r != EXR_ERR_SUCCESS) return failed(r, "closing");
    return {};
}

}  // namespace pbrlab
