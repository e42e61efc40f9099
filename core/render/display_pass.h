// The display mapping (render/display.h) as a GPU pass: a float value texture becomes the
// picture a person sees, in a texture, with no read-back. The GUI draws with it while the
// input moves (the CPU mapping is what files and reports use; a test holds the two together).
#pragma once

#include "gl/objects.h"
#include "pbrlab/module.h"
#include "shader/program.h"

namespace pbrlab {

class DisplayPass {
public:
    DisplayPass(ProgramCache& programs, const std::filesystem::path& shaders);
    // Maps `value` (width x height RGBA32F, GL rows bottom-up, as a render target holds it)
    // into the pass's own RGBA8 texture, row 0 = the top of the picture.
    GLuint run(GLuint value, int width, int height, const Display& display, int components);
    GLuint texture() const { return target_ ? target_->colorTexture(0) : 0; }
    // Compiles the pass's program ahead of the first run (a page compiles in tens of ms: not
    // within the first frame of the first drag).
    void prepare() { program(); }

private:
    std::shared_ptr<Program> program();

    ProgramCache& programs_;
    std::filesystem::path shaders_;
    gl::FullscreenTriangle fullscreen_;
    std::unique_ptr<gl::RenderTarget> target_;
};

}  // namespace pbrlab
