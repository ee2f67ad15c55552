#include "Presenter.h"

#include "embedded_shaders.h"

namespace fcc::render {

Presenter::Presenter() {
  program_ = GlProgram::graphics(embedded::shaders("shaders/present.vert"), embedded::shaders("shaders/present.frag"),
                                 "shaders/present.{vert,frag}");
  glCreateVertexArrays(1, &vertexArray_);
  checkGl("creating the presenter's vertex array");
}

Presenter::~Presenter() {
  if (vertexArray_) glDeleteVertexArrays(1, &vertexArray_);
}

void Presenter::draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, int x, int y, int width,
                     int height) {
  if (image.width() != width || image.height() != height)
    throw GlError("presenter: the image is " + std::to_string(image.width()) + "x" + std::to_string(image.height()) +
                  ", the viewport " + std::to_string(width) + "x" + std::to_string(height));
  glViewport(x, y, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  const GLuint p = program_.id();
  glProgramUniform3fv(p, program_.uniformLocation("uBackground"), 1, &backgroundLinear.x);
  glProgramUniform2i(p, program_.uniformLocation("uOrigin"), x, y);
  glBindTextureUnit(0, image.id());
  program_.use();
  glBindVertexArray(vertexArray_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  checkGl("drawing the rendered image");
}

}  // namespace fcc::render
