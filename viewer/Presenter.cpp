#include "Presenter.h"

#include <algorithm>

#include "embedded_shaders.h"

namespace fcc::render {

Presenter::Presenter() {
  program_ = GlProgram::compute(embedded::shaders("shaders/present.comp"), "shaders/present.comp");
  backgroundLocation_ = program_.uniformLocation("uBackground");
  columnOffsetLocation_ = program_.uniformLocation("uColumnOffset");
  group_ = program_.localSize();
  glCreateFramebuffers(1, &readFramebuffer_);
  checkGl("creating the presenter's framebuffer");
}

Presenter::~Presenter() {
  if (readFramebuffer_) glDeleteFramebuffers(1, &readFramebuffer_);
}

void Presenter::draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, int firstColumn) {
  const int width = image.width(), height = image.height();
  if (width <= 0 || height <= 0) return;
  firstColumn = std::clamp(firstColumn, 0, width);
  if (display_.width() != width || display_.height() != height) {
    display_ = GlTexture2D(GL_RGBA8, width, height);
    glNamedFramebufferTexture(readFramebuffer_, GL_COLOR_ATTACHMENT0, display_.id(), 0);
    if (glCheckNamedFramebufferStatus(readFramebuffer_, GL_READ_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("presenter: the display image's framebuffer is incomplete");
  }
  if (firstColumn == width) return;
  const int columnOffset = firstColumn / group_[0] * group_[0];
  glProgramUniform3fv(program_.id(), backgroundLocation_, 1, &backgroundLinear.x);
  glProgramUniform1i(program_.id(), columnOffsetLocation_, columnOffset);
  image.bindImage(0, GL_READ_ONLY);
  display_.bindImage(1, GL_WRITE_ONLY);
  program_.use();
  glDispatchCompute(GLuint((width - columnOffset + group_[0] - 1) / group_[0]), GLuint((height + group_[1] - 1) / group_[1]),
                    1);
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);

  GLint drawFramebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
  glBlitNamedFramebuffer(readFramebuffer_, GLuint(drawFramebuffer), firstColumn, 0, width, height, firstColumn, 0, width,
                         height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  checkGl("drawing the rendered image");
}

}  // namespace fcc::render
