// A rectangle of pixels, [x0, x1) x [y0, y1), with rows counted from the top as in the raycaster's
// images (OpenGL's framebuffers count from the bottom: the Presenter flips).
#pragma once

#include <algorithm>

namespace fcc::render {

struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool empty() const { return x1 <= x0 || y1 <= y0; }
  long long area() const { return empty() ? 0 : (long long)(x1 - x0) * (y1 - y0); }
  bool operator==(const PixelRect& o) const { return x0 == o.x0 && y0 == o.y0 && x1 == o.x1 && y1 == o.y1; }
  bool operator!=(const PixelRect& o) const { return !(*this == o); }
};

// The smallest rectangle holding both (an empty one adds nothing).
inline PixelRect united(const PixelRect& a, const PixelRect& b) {
  if (a.empty()) return b;
  if (b.empty()) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

// What both hold; empty (all zero) if nothing.
inline PixelRect intersected(const PixelRect& a, const PixelRect& b) {
  const PixelRect r{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
  return r.empty() ? PixelRect{} : r;
}

}  // namespace fcc::render
