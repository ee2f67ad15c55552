#include "Presenter.h"

#include <cstdint>

#include "Raycaster.h"
#include "embedded_shaders.h"

namespace fcc::render {
namespace {
// A PassResults block (shaders/present.vert) without a surface: last column before the first.
constexpr int32_t kNoSurface[5] = {0, 0, 0, -1, -1};
static_assert(sizeof kNoSurface == Raycaster::kPassResultsHeaderBytes, "present.vert reads a pass's results header");
}  // namespace

Presenter::Presenter() : noSurface_(sizeof kNoSurface, kNoSurface) {
  program_ = GlProgram::graphics(embedded::shaders("shaders/present.vert"), embedded::shaders("shaders/present.frag"),
                                 "shaders/present.vert + present.frag");
  rectsLocation_ = program_.uniformLocation("uRects");
  uniteSurfaceLocation_ = program_.uniformLocation("uUniteSurface");
  clipLocation_ = program_.uniformLocation("uClip");
  sizeLocation_ = program_.uniformLocation("uSize");
  backgroundLocation_ = program_.uniformLocation("uBackground");
  glCreateVertexArrays(1, &vertexArray_);
  checkGl("creating the presenter");
}

Presenter::~Presenter() {
  if (vertexArray_) glDeleteVertexArrays(1, &vertexArray_);
}

void Presenter::draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, const std::vector<PixelRect>& regions,
                     const PixelRect& clip, const GlBuffer* passResults) {
  const int width = image.width(), height = image.height();
  if (width <= 0 || height <= 0 || regions.empty()) return;
  std::vector<glm::ivec4> rects;
  for (const PixelRect& r : regions) rects.emplace_back(r.x0, r.y0, r.x1, r.y1);
  if (rects.size() > kMaxRects) {
    PixelRect bounds;
    for (std::size_t i = 1; i < regions.size(); ++i) bounds = united(bounds, regions[i]);
    rects.resize(2);
    rects[1] = glm::ivec4(bounds.x0, bounds.y0, bounds.x1, bounds.y1);
  }
  const GLuint p = program_.id();
  glProgramUniform4iv(p, rectsLocation_, GLsizei(rects.size()), &rects[0].x);
  glProgramUniform1i(p, uniteSurfaceLocation_, passResults ? 1 : 0);
  glProgramUniform4i(p, clipLocation_, clip.x0, clip.y0, clip.x1, clip.y1);
  glProgramUniform2i(p, sizeLocation_, width, height);
  glProgramUniform3fv(p, backgroundLocation_, 1, &backgroundLinear.x);
  const GlBuffer& results = passResults ? *passResults : noSurface_;
  glBindBufferRange(GL_UNIFORM_BUFFER, 0, results.id(), 0, GLsizeiptr(sizeof kNoSurface));
  image.bindImage(0, GL_READ_ONLY);

  glViewport(0, 0, width, height);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  program_.use();
  glBindVertexArray(vertexArray_);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, GLsizei(rects.size()));
  glBindVertexArray(0);
  checkGl("drawing the rendered image");
}

}  // namespace fcc::render
