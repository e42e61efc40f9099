// The interface of libpbrlab_oiio.so, the one place pbrlab calls OpenImageIO. assets/image_io.cpp
// opens the library with dlopen on the first file that needs it and calls through this table; both
// sides are built together, the version guards against a stale library from another build.
#pragma once

#include <string>
#include <vector>

#include "assets/image_codecs.h"

namespace pbrlab {

struct OiioInterface {
    static constexpr int kVersion = 1;
    int version = kVersion;
    // Decodes the file `name`, or the encoded bytes at `memory` when not null (then `name`'s
    // extension picks the format). Returns an empty string on success, otherwise the reason;
    // never throws.
    std::string (*decode)(const std::string& name, const std::vector<unsigned char>* memory,
                          DecodedImage& out) = nullptr;
    // Writes `image` (its pixels, or `codes` for integer depths as in encodePng) to the file
    // `temp`, in the format that `file`'s extension names. Same return as decode.
    std::string (*write)(const std::string& file, const std::string& temp, const Image& image,
                         FileDepth depth, const void* codes, bool markSrgb) = nullptr;
};

}  // namespace pbrlab

// The library's one exported symbol.
extern "C" const pbrlab::OiioInterface* pbrlab_oiio_interface();
