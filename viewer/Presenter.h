// Draws the raycaster's colour image into the current draw framebuffer (the viewer's window, or an
// offscreen target in `fccvdb bench view`): over a background colour, sRGB-encoded exactly as
// `fccvdb render` writes PNGs, one texel per pixel, and only inside given rectangles: compute GPUs
// (H100/H200) write pixels through their few raster units slowly, so the viewer draws only what
// changed (RedrawTracker.h). One draw call, whose first rectangle can grow on the GPU to the surface
// rectangle a raycasting pass left there: drawing need not wait for the pass's results on the CPU.
#pragma once

#include <glm/glm.hpp>

#include <vector>

#include "GlProgram.h"
#include "PixelRect.h"

namespace fcc::render {

class Presenter {
 public:
  // Rectangles one draw() takes; more are drawn as their bounding box.
  static constexpr std::size_t kMaxRects = 16;  // FCC_MAX_PRESENT_RECTS in shaders/present.vert

  Presenter();  // needs a current OpenGL 4.5 context
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // Draws the pixels of `image` inside `regions` and inside `clip` (rows from the top, as the
  // image's) into the bound draw framebuffer's lower-left image.width() x image.height() pixels,
  // leaving the others as they are. With `passResults` (Raycaster::passResults()), regions[0] is first
  // united with the surface rectangle held there. Changes the viewport, program and vertex array;
  // turns off blending, depth and stencil tests, scissoring and face culling.
  void draw(const GlTexture2D& image, const glm::vec3& backgroundLinear, const std::vector<PixelRect>& regions,
            const PixelRect& clip, const GlBuffer* passResults = nullptr);
  // All of `image`.
  void draw(const GlTexture2D& image, const glm::vec3& backgroundLinear) {
    const PixelRect all{0, 0, image.width(), image.height()};
    draw(image, backgroundLinear, {all}, all);
  }

 private:
  GlProgram program_;
  // Looked up once.
  GLint rectsLocation_ = -1, uniteSurfaceLocation_ = -1, clipLocation_ = -1, sizeLocation_ = -1,
        backgroundLocation_ = -1;
  GLuint vertexArray_ = 0;  // empty: the vertex shader makes its corners
  GlBuffer noSurface_;      // bound when no pass results are given (the shader's block must be backed)
};

}  // namespace fcc::render
