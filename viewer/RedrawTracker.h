// Which part of the image area a frame must draw, given what the window's back buffer still holds
// from an earlier frame (its buffer age: GLX_EXT_buffer_age / EGL_EXT_buffer_age; 1 for an
// offscreen target that is drawn over in place). Outside the surface, the image is the background,
// so between two frames that look alike (same size, panel and background) the pixels that differ lie
// where the surface is now, where it was in the older frame, and where something was drawn over the
// image then (ImGui's windows and text). Why bother: on compute GPUs every pixel written through the
// raster path is slow (H200: 0.15 ms for a 1080p window, 10% of a frame; docs/BENCHMARKS.md).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <deque>
#include <vector>

#include "PixelRect.h"

namespace fcc::render {

// What every background pixel of a frame depends on.
struct FrameLook {
  int width = 0, height = 0;  // the image (and window) in pixels
  int firstColumn = 0;        // columns left of it are under the opaque panel, drawn by ImGui
  glm::vec3 background{0.0f};
  bool operator==(const FrameLook& o) const {
    return width == o.width && height == o.height && firstColumn == o.firstColumn && background == o.background;
  }
  bool operator!=(const FrameLook& o) const { return !(*this == o); }
  PixelRect imageArea() const { return {firstColumn, 0, width, height}; }  // what the image covers
};

class RedrawTracker {
 public:
  // Frames remembered: an older back buffer is drawn whole.
  static constexpr int kHistory = 4;

  // What to draw of look.imageArea() for a frame that looks like `look`, into a back buffer holding
  // the frame drawn `bufferAge` frames ago (0: unknown): rectangles, which may overlap. The first is
  // where the surface was then: it is to be united with where the surface is now (on the GPU, see
  // Presenter.h). Each of the others is around something drawn over the image then (kept apart: the
  // panel's antialiased edge or a line of text would stretch one rectangle around the surface to
  // the image's full height or width). Unknown or different buffers get {look.imageArea()}.
  std::vector<PixelRect> regions(const FrameLook& look, int bufferAge) const;
  // True if the back buffer already shows the user interface `uiHash` stands for (a hash of ImGui's
  // draw data), drawn by a frame that looks like `look` with nothing over the image: then only the
  // panel's columns hold it, which the image never touches, and ImGui need not draw again.
  bool holdsUi(const FrameLook& look, int bufferAge, uint64_t uiHash) const;
  // Records the frame just drawn: its look, where its surface was, what was drawn over its image
  // (framebuffer pixels, rows from the top; clipped to the image) and the hash of its user interface.
  void drawn(const FrameLook& look, const PixelRect& surface, const std::vector<PixelRect>& overlays, uint64_t uiHash);
  // More overlay rectangles than this in a frame are drawn as their bounding box.
  static constexpr std::size_t kMaxOverlays = 8;

 private:
  struct Frame {
    FrameLook look;
    PixelRect surface;
    std::vector<PixelRect> overlays;  // inside look.imageArea()
    uint64_t uiHash = 0;
  };
  const Frame* held(const FrameLook& look, int bufferAge) const;  // null: unknown or another look
  std::deque<Frame> frames_;  // newest first
};

}  // namespace fcc::render
