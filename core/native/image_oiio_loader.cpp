// assets/image_codecs.h's other formats on the desktop: libpbrlab_oiio.so, the one place pbrlab
// calls OpenImageIO, opened with dlopen on the first file that needs it (image_codecs.h says
// why it is not linked).
#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "assets/image_codecs.h"
#include "native/image_oiio.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

struct OiioLibrary {
    const OiioInterface* table = nullptr;
    std::string problem;  // why it could not be opened
};

std::atomic<bool> oiioOpened{false};

OiioLibrary openOiioLibrary() {
    // $PBRLAB_OIIO_LIBRARY when set; otherwise beside the executable (where the build puts it)
    // or in <prefix>/lib/pbrlab (where an install copies it), then the dynamic linker's own search
    // (the test and benchmark programs in build/tests carry build/ in their RUNPATH).
    std::vector<std::string> candidates;
    if (const char* named = std::getenv("PBRLAB_OIIO_LIBRARY"); named && *named) {
        candidates.push_back(named);
    } else {
        std::error_code ec;
        const fs::path exeDir = fs::read_symlink("/proc/self/exe", ec).parent_path();
        // Beside the executable (the build tree), or in <prefix>/lib/pbrlab (cmake --install).
        for (const fs::path& place : {exeDir, exeDir.parent_path() / "lib" / "pbrlab"})
            if (!ec && fs::exists(place / "libpbrlab_oiio.so", ec))
                candidates.push_back((place / "libpbrlab_oiio.so").string());
        candidates.push_back("libpbrlab_oiio.so");
    }
    std::string failures;
    for (const std::string& candidate : candidates) {
        void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) {
            failures += std::string(failures.empty() ? "" : "; ") + dlerror();
            continue;
        }
        auto get =
            reinterpret_cast<const OiioInterface* (*)()>(dlsym(handle, "pbrlab_oiio_interface"));
        const OiioInterface* table = get ? get() : nullptr;
        if (table && table->version == OiioInterface::kVersion) {
            oiioOpened = true;
            return {table, {}};  // stays loaded: OpenImageIO's threads outlive any one call
        }
        failures += std::string(failures.empty() ? "" : "; ") + candidate +
                    ": not the OpenImageIO library of this pbrlab build";
        dlclose(handle);
    }
    return {nullptr,
            "this format needs OpenImageIO, which pbrlab loads from its library "
            "libpbrlab_oiio.so (built beside the pbrlab executable, installed in lib/pbrlab; "
            "PBRLAB_OIIO_LIBRARY may name another path), and it could not be loaded (" +
                failures + ")"};
}

// The library's functions, opened on the first call. Throws naming `what` if it cannot be.
const OiioInterface& oiio(const std::string& what) {
    static const OiioLibrary library = openOiioLibrary();
    if (!library.table) throw Error(what + library.problem);
    return *library.table;
}

}  // namespace

std::string decodeOtherFormat(const std::string& what, const std::string& name,
                              const std::vector<unsigned char>* memory, DecodedImage& out) {
    return oiio(what).decode(name, memory, out);
}

std::string writeOtherFormat(const std::string& what, const std::string& file,
                             const std::string& temp, const Image& image, FileDepth depth,
                             const void* codes, bool markSrgb) {
    return oiio(what).write(file, temp, image, depth, codes, markSrgb);
}

bool openImageIoLoaded() {
    return oiioOpened;
}

}  // namespace pbrlab
