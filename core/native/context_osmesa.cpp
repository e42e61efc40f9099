// OSMesa backend. libOSMesa is opened with dlopen rather than linked, so that a machine
// without it gets a clear message instead of a loader failure, and so its GL symbols never
// mix with libGL's in the GUI build.
#include <dlfcn.h>

#include <vector>

#include "gl/context.h"
#include "gl/gl.h"
#include "util/error.h"

namespace pbrlab {
namespace {

// From GL/osmesa.h (not included: it drags in GL/gl.h, which clashes with glcorearb.h).
constexpr int kOsmesaFormat = 0x22, kOsmesaDepthBits = 0x30, kOsmesaStencilBits = 0x31,
              kOsmesaAccumBits = 0x32, kOsmesaProfile = 0x33, kOsmesaCoreProfile = 0x34,
              kOsmesaMajor = 0x36, kOsmesaMinor = 0x37;
using OSMesaContext = struct osmesa_context*;
using CreateContextAttribsFn = OSMesaContext (*)(const int*, OSMesaContext);
using MakeCurrentFn = unsigned char (*)(OSMesaContext, void*, unsigned, int, int);
using DestroyContextFn = void (*)(OSMesaContext);
using GetProcAddressFn = void* (*)(const char*);

GetProcAddressFn osmesaGetProcAddress = nullptr;

void* openLibrary() {
    void* library = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    return library ? library : dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
}

void* getProc(const char* name) {
    return osmesaGetProcAddress(name);
}

class OsMesaContext final : public GlContext {
public:
    OsMesaContext() {
        library_ = openLibrary();
        if (!library_)
            throw Error(std::string("headless OpenGL unavailable: cannot load libOSMesa (") +
                        dlerror() + "); install the Debian package libosmesa6");
        auto create =
            reinterpret_cast<CreateContextAttribsFn>(dlsym(library_, "OSMesaCreateContextAttribs"));
        makeCurrent_ = reinterpret_cast<MakeCurrentFn>(dlsym(library_, "OSMesaMakeCurrent"));
        destroy_ = reinterpret_cast<DestroyContextFn>(dlsym(library_, "OSMesaDestroyContext"));
        osmesaGetProcAddress =
            reinterpret_cast<GetProcAddressFn>(dlsym(library_, "OSMesaGetProcAddress"));
        if (!create || !makeCurrent_ || !destroy_ || !osmesaGetProcAddress)
            throw Error("headless OpenGL unavailable: libOSMesa lacks OSMesaCreateContextAttribs");
        const int attribs[] = {kOsmesaFormat,
                               0x1908 /* GL_RGBA */,
                               kOsmesaDepthBits,
                               24,
                               kOsmesaStencilBits,
                               0,
                               kOsmesaAccumBits,
                               0,
                               kOsmesaProfile,
                               kOsmesaCoreProfile,
                               kOsmesaMajor,
                               4,
                               kOsmesaMinor,
                               5,
                               0};
        context_ = create(attribs, nullptr);
        if (!context_)
            throw Error("headless OpenGL unavailable: OSMesa could not create a 4.5 core context");
        // All rendering goes to framebuffer objects; the default buffer only has to exist.
        buffer_.resize(4 * 4 * 4);
        if (!makeCurrent_(context_, buffer_.data(), GL_UNSIGNED_BYTE, 4, 4))
            throw Error("headless OpenGL unavailable: OSMesaMakeCurrent failed");
        gl::loadFunctions(getProc);
    }
    ~OsMesaContext() override {
        if (context_) destroy_(context_);
        // The library stays loaded: llvmpipe threads may outlive the context briefly.
    }
    std::string description() const override {
        return std::string("OSMesa: ") + reinterpret_cast<const char*>(gl::GetString(GL_VERSION)) +
               ", " + reinterpret_cast<const char*>(gl::GetString(GL_RENDERER));
    }

private:
    void* library_ = nullptr;
    OSMesaContext context_ = nullptr;
    MakeCurrentFn makeCurrent_ = nullptr;
    DestroyContextFn destroy_ = nullptr;
    std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<GlContext> createHeadlessContext() {
    return std::make_unique<OsMesaContext>();
}

void preloadHeadlessLibrary() {
    openLibrary();  // stays loaded; when missing, createHeadlessContext says so
}

}  // namespace pbrlab
