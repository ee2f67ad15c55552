#include "RedrawTracker.h"

namespace fcc::render {

const RedrawTracker::Frame* RedrawTracker::held(const FrameLook& look, int bufferAge) const {
  if (bufferAge <= 0 || bufferAge > int(frames_.size())) return nullptr;
  const Frame& frame = frames_[std::size_t(bufferAge - 1)];
  return frame.look == look ? &frame : nullptr;
}

std::vector<PixelRect> RedrawTracker::regions(const FrameLook& look, int bufferAge) const {
  const PixelRect all = look.imageArea();
  const Frame* frame = held(look, bufferAge);
  if (!frame) return {all};
  std::vector<PixelRect> out{intersected(frame->surface, all)};
  for (const PixelRect& overlay : frame->overlays)
    if (united(out[0], overlay) != out[0]) out.push_back(overlay);
  return out;
}

bool RedrawTracker::holdsUi(const FrameLook& look, int bufferAge, uint64_t uiHash) const {
  const Frame* frame = held(look, bufferAge);
  return frame && frame->overlays.empty() && frame->uiHash == uiHash;
}

void RedrawTracker::drawn(const FrameLook& look, const PixelRect& surface, const std::vector<PixelRect>& overlays,
                          uint64_t uiHash) {
  const PixelRect all = look.imageArea();
  Frame frame{look, intersected(surface, all), {}, uiHash};
  PixelRect bounds;
  for (const PixelRect& r : overlays) {
    const PixelRect inside = intersected(r, all);
    if (inside.empty()) continue;
    frame.overlays.push_back(inside);
    bounds = united(bounds, inside);
  }
  if (frame.overlays.size() > kMaxOverlays) frame.overlays = {bounds};
  frames_.push_front(std::move(frame));
  if (frames_.size() > std::size_t(kHistory)) frames_.pop_back();
}

}  // namespace fcc::render
