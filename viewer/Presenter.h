// Draws the raycaster's colour image into the current draw framebuffer (the viewer's window, or an
// offscreen target in `fccvdb bench view`): over a background colour, sRGB-encoded exactly as
// `fccvdb render` writes PNGs, one texel per pixel. A compute pass encodes it into an RGBA8 image
// that is then blitted: compute GPUs (H100/H200) run fragment work slowly (docs/BENCHMARKS.md).
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <vector>

#include "GlProgram.h"
#include "PixelRect.h"

namespace fcc::render {

class Presenter {
 public:
  Presenter();  // needs a current OpenGL 4.5 context
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // Draws the pixels of `image` inside `region` (rows from the top, as the image's) into the bound
  // draw framebuffer's lower-left image.width() x image.height() pixels, leaving the others as they
  // are: fewer pixels through the raster path, which is slow on compute GPUs. The viewer leaves out
  // the columns under its opaque panel and what its back buffer already shows (RedrawTracker.h).
  void draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, const PixelRect& region);
  // Each region in turn (where they overlap, pixels are drawn twice, the same each time).
  void draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, const std::vector<PixelRect>& regions) {
    for (const PixelRect& r : regions) draw(image, backgroundLinear, r);
  }
  // All of `image`.
  void draw(const GlTexture2D& image, const glm::vec3& backgroundLinear) {
    draw(image, backgroundLinear, PixelRect{0, 0, image.width(), image.height()});
  }

 private:
  GlProgram program_;
  GLint backgroundLocation_ = -1, regionMinLocation_ = -1, regionMaxLocation_ = -1;  // looked up once
  std::array<GLint, 3> group_{};                               // the compute shader's work group
  GlTexture2D display_;     // RGBA8, the encoded image
  GLuint readFramebuffer_ = 0;  // wraps display_ as the blit's source
};

}  // namespace fcc::render
