#include "render/display_pass.h"

namespace pbrlab {

DisplayPass::DisplayPass(ProgramCache& programs, const std::filesystem::path& shaders)
    : programs_(programs), shaders_(shaders) {}

std::shared_ptr<Program> DisplayPass::program() {
    ProgramRecipe recipe;
    recipe.label = "display";
    recipe.vertex = {shaders_ / "fullscreen.vert"};
    recipe.fragment = {shaders_ / "color.glsl", shaders_ / "display.frag"};
    return programs_.get(recipe);
}

GLuint DisplayPass::run(GLuint value, int width, int height, const Display& display,
                        int components) {
    if (!target_ || target_->width() != width || target_->height() != height)
        target_ = std::make_unique<gl::RenderTarget>(width, height, 1, false);
    const std::shared_ptr<Program> program = this->program();
    target_->bind();
    gl::Disable(GL_DEPTH_TEST);
    program->use();
    gl::ActiveTexture(GL_TEXTURE0);
    gl::BindTexture(GL_TEXTURE_2D, value);
    program->set("uValue", 0);
    program->set("uMode", int(display.mode));
    program->set("uLo", float(display.lo));
    program->set("uHi", float(display.hi));
    program->set("uLogScale", display.logScale ? 1 : 0);
    program->set("uComponents", components);
    fullscreen_.draw();
    gl::BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl::checkError("display pass");
    return target_->colorTexture(0);
}

}  // namespace pbrlab
