#include "RedrawTracker.h"

namespace fcc::render {

PixelRect RedrawTracker::region(const FrameLook& look, const PixelRect& surface, int bufferAge) const {
  const PixelRect all = look.imageArea();
  if (bufferAge <= 0 || bufferAge > int(frames_.size())) return all;
  const Frame& held = frames_[std::size_t(bufferAge - 1)];
  if (held.look != look) return all;
  return intersected(united(united(held.surface, held.overlay), surface), all);
}

void RedrawTracker::drawn(const FrameLook& look, const PixelRect& surface) {
  frames_.push_front(Frame{look, surface, look.imageArea()});
  if (frames_.size() > std::size_t(kHistory)) frames_.pop_back();
}

void RedrawTracker::overlaid(const PixelRect& overlay) {
  if (!frames_.empty()) frames_.front().overlay = overlay;
}

}  // namespace fcc::render
