// A rectangle of pixels, [x0, x1) x [y0, y1), with rows counted from the top as in the raycaster's
// images (OpenGL's framebuffers count from the bottom: the Presenter flips).
#pragma once

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

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

// Pixels inside at least one of `rects` (overlaps counted once): for statistics and tests.
inline long long coveredArea(const std::vector<PixelRect>& rects) {
  // Sweep the distinct column boundaries; in each strip, merge the rows the rectangles cover.
  std::vector<int> xs;
  for (const PixelRect& r : rects)
    if (!r.empty()) xs.insert(xs.end(), {r.x0, r.x1});
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  long long area = 0;
  for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
    std::vector<std::pair<int, int>> spans;
    for (const PixelRect& r : rects)
      if (!r.empty() && r.x0 <= xs[i] && r.x1 >= xs[i + 1]) spans.emplace_back(r.y0, r.y1);
    std::sort(spans.begin(), spans.end());
    int covered = 0, end = std::numeric_limits<int>::min();
    for (const auto& [y0, y1] : spans) {
      if (y1 <= end) continue;
      covered += y1 - std::max(y0, end);
      end = y1;
    }
    area += (long long)(xs[i + 1] - xs[i]) * covered;
  }
  return area;
}

}  // namespace fcc::render
