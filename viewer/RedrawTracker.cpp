#include "RedrawTracker.h"

namespace fcc::render {

std::vector<PixelRect> RedrawTracker::regions(const FrameLook& look, int bufferAge) const {
  const PixelRect all = look.imageArea();
  if (bufferAge <= 0 || bufferAge > int(frames_.size())) return {all};
  const Frame& held = frames_[std::size_t(bufferAge - 1)];
  if (held.look != look) return {all};
  std::vector<PixelRect> out{intersected(held.surface, all)};
  for (const PixelRect& overlay : held.overlays)
    if (united(out[0], overlay) != out[0]) out.push_back(overlay);
  return out;
}

void RedrawTracker::drawn(const FrameLook& look, const PixelRect& surface) {
  frames_.push_front(Frame{look, surface, {look.imageArea()}});
  if (frames_.size() > std::size_t(kHistory)) frames_.pop_back();
}

void RedrawTracker::overlaid(const std::vector<PixelRect>& overlays) {
  if (frames_.empty()) return;
  const PixelRect all = frames_.front().look.imageArea();
  std::vector<PixelRect>& kept = frames_.front().overlays;
  kept.clear();
  PixelRect bounds;
  for (const PixelRect& r : overlays) {
    const PixelRect inside = intersected(r, all);
    if (inside.empty()) continue;
    kept.push_back(inside);
    bounds = united(bounds, inside);
  }
  if (kept.size() > kMaxOverlays) kept = {bounds};
}

}  // namespace fcc::render
