// Draws the raycaster's colour image into the current framebuffer (the viewer's window, or an
// offscreen target in `fccvdb bench view`): over a background colour, sRGB-encoded exactly as
// `fccvdb render` writes PNGs, one texel per pixel.
#pragma once

#include <glm/glm.hpp>

#include "GlProgram.h"

namespace fcc::render {

class Presenter {
 public:
  Presenter();  // needs a current OpenGL 4.5 context
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // Fills the viewport (x, y, width, height; GL's lower-left origin) with `image`, which must be
  // width x height.
  void draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, int x, int y, int width, int height);

 private:
  GlProgram program_;
  GLuint vertexArray_ = 0;  // empty: the core profile draws nothing without one bound
};

}  // namespace fcc::render
