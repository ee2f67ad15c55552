#include "Presenter.h"

#include "embedded_shaders.h"

namespace fcc::render {

Presenter::Presenter() {
  program_ = GlProgram::compute(embedded::shaders("shaders/present.comp"), "shaders/present.comp");
  backgroundLocation_ = program_.uniformLocation("uBackground");
  regionMinLocation_ = program_.uniformLocation("uRegionMin");
  regionMaxLocation_ = program_.uniformLocation("uRegionMax");
  group_ = program_.localSize();
  glCreateFramebuffers(1, &readFramebuffer_);
  checkGl("creating the presenter's framebuffer");
}

Presenter::~Presenter() {
  if (readFramebuffer_) glDeleteFramebuffers(1, &readFramebuffer_);
}

void Presenter::draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, const PixelRect& region) {
  const int width = image.width(), height = image.height();
  if (width <= 0 || height <= 0) return;
  if (display_.width() != width || display_.height() != height) {
    display_ = GlTexture2D(GL_RGBA8, width, height);
    glNamedFramebufferTexture(readFramebuffer_, GL_COLOR_ATTACHMENT0, display_.id(), 0);
    if (glCheckNamedFramebufferStatus(readFramebuffer_, GL_READ_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("presenter: the display image's framebuffer is incomplete");
  }
  const PixelRect r = intersected(region, PixelRect{0, 0, width, height});
  if (r.empty()) return;
  // The framebuffer's rows count from the bottom.
  const glm::ivec2 lo(r.x0, height - r.y1), hi(r.x1, height - r.y0);
  glProgramUniform3fv(program_.id(), backgroundLocation_, 1, &backgroundLinear.x);
  glProgramUniform2i(program_.id(), regionMinLocation_, lo.x, lo.y);
  glProgramUniform2i(program_.id(), regionMaxLocation_, hi.x, hi.y);
  image.bindImage(0, GL_READ_ONLY);
  display_.bindImage(1, GL_WRITE_ONLY);
  program_.use();
  glDispatchCompute(GLuint((hi.x - lo.x + group_[0] - 1) / group_[0]), GLuint((hi.y - lo.y + group_[1] - 1) / group_[1]), 1);
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);

  GLint drawFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
  glBlitNamedFramebuffer(readFramebuffer_, GLuint(drawFramebuffer), lo.x, lo.y, hi.x, hi.y, lo.x, lo.y, hi.x, hi.y,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
  checkGl("drawing the rendered image");
}

}  // namespace fcc::render
