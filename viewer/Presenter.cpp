#include "Presenter.h"

#include "embedded_shaders.h"

namespace fcc::render {

Presenter::Presenter() {
  program_ = GlProgram::compute(embedded::shaders("shaders/present.comp"), "shaders/present.comp");
  glCreateFramebuffers(1, &readFramebuffer_);
  checkGl("creating the presenter's framebuffer");
}

Presenter::~Presenter() {
  if (readFramebuffer_) glDeleteFramebuffers(1, &readFramebuffer_);
}

void Presenter::draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, int x, int y, int width,
                     int height) {
  if (image.width() != width || image.height() != height)
    throw GlError("presenter: the image is " + std::to_string(image.width()) + "x" + std::to_string(image.height()) +
                  ", the viewport " + std::to_string(width) + "x" + std::to_string(height));
  if (display_.width() != width || display_.height() != height) {
    display_ = GlTexture2D(GL_RGBA8, width, height);
    glNamedFramebufferTexture(readFramebuffer_, GL_COLOR_ATTACHMENT0, display_.id(), 0);
    if (glCheckNamedFramebufferStatus(readFramebuffer_, GL_READ_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("presenter: the display image's framebuffer is incomplete");
  }
  glProgramUniform3fv(program_.id(), program_.uniformLocation("uBackground"), 1, &backgroundLinear.x);
  image.bindImage(0, GL_READ_ONLY);
  display_.bindImage(1, GL_WRITE_ONLY);
  program_.use();
  const std::array<GLint, 3> group = program_.localSize();
  glDispatchCompute(GLuint((width + group[0] - 1) / group[0]), GLuint((height + group[1] - 1) / group[1]), 1);
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);

  GLint drawFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
  glBlitNamedFramebuffer(readFramebuffer_, GLuint(drawFramebuffer), 0, 0, width, height, x, y, x + width, y + height,
                         GL_COLOR_BUFFER_BIT, GL_NEAREST);
  checkGl("drawing the rendered image");
}

}  // namespace fcc::render
