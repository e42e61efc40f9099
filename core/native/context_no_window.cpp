// The headless grader's window context: it has none (no GLFW, no display libraries in the
// grader bundle). Every headless command renders through OSMesa (context_osmesa.cpp).
#include "gl/context.h"
#include "util/error.h"

namespace pbrlab {

std::unique_ptr<GlContext> createWindowContext(int, int, const std::string&) {
    throw Error(
        "this pbrlab is the headless grader: it opens no window (the GUI is in the "
        "desktop build)");
}

}  // namespace pbrlab
