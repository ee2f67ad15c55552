// Draws the raycaster's colour image into the current draw framebuffer (the viewer's window, or an
// offscreen target in `fccvdb bench view`): over a background colour, sRGB-encoded exactly as
// `fccvdb render` writes PNGs, one texel per pixel. A compute pass encodes it into an RGBA8 image
// that is then blitted: compute GPUs (H100/H200) run fragment work slowly (docs/BENCHMARKS.md).
#pragma once

#include <glm/glm.hpp>

#include <array>

#include "GlProgram.h"

namespace fcc::render {

class Presenter {
 public:
  Presenter();  // needs a current OpenGL 4.5 context
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // Fills the bound draw framebuffer's lower-left image.width() x image.height() pixels with `image`,
  // except the first `firstColumn` columns (covered by the opaque panel, which is drawn there next):
  // fewer pixels through the raster path, which is slow on compute GPUs.
  void draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, int firstColumn = 0);

 private:
  GlProgram program_;
  GLint backgroundLocation_ = -1, columnOffsetLocation_ = -1;  // looked up once
  std::array<GLint, 3> group_{};                               // the compute shader's work group
  GlTexture2D display_;     // RGBA8, the encoded image
  GLuint readFramebuffer_ = 0;  // wraps display_ as the blit's source
};

}  // namespace fcc::render
