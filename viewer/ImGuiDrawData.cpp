#include "ImGuiDrawData.h"

#include <cmath>
#include <functional>
#include <string_view>

namespace fcc::render {

// Each command draws inside its clip rectangle and the bounding box of its vertices (antialiased
// edges are vertices too; a pixel is drawn when its centre is covered).
std::vector<PixelRect> overlaysOf(const ImDrawData& drawData, const PixelRect& imageArea) {
  const ImVec2 origin = drawData.DisplayPos, scale = drawData.FramebufferScale;
  std::vector<PixelRect> overlays;
  for (int n = 0; n < drawData.CmdListsCount; ++n) {
    const ImDrawList& list = *drawData.CmdLists[n];
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      if (cmd.UserCallback || cmd.ElemCount == 0) continue;
      const PixelRect clip{int(std::floor((cmd.ClipRect.x - origin.x) * scale.x)),
                           int(std::floor((cmd.ClipRect.y - origin.y) * scale.y)),
                           int(std::ceil((cmd.ClipRect.z - origin.x) * scale.x)),
                           int(std::ceil((cmd.ClipRect.w - origin.y) * scale.y))};
      // The panel's own commands stay left of the image: no need to look at their vertices.
      if (intersected(clip, imageArea).empty()) continue;
      ImVec2 lo(cmd.ClipRect.z, cmd.ClipRect.w), hi(cmd.ClipRect.x, cmd.ClipRect.y);
      for (unsigned i = cmd.IdxOffset; i < cmd.IdxOffset + cmd.ElemCount; ++i) {
        const ImVec2 p = list.VtxBuffer[int(cmd.VtxOffset + list.IdxBuffer[int(i)])].pos;
        lo = ImVec2(std::min(lo.x, p.x), std::min(lo.y, p.y));
        hi = ImVec2(std::max(hi.x, p.x), std::max(hi.y, p.y));
      }
      const PixelRect drawn{int(std::floor((lo.x - origin.x) * scale.x)), int(std::floor((lo.y - origin.y) * scale.y)),
                            int(std::ceil((hi.x - origin.x) * scale.x)), int(std::ceil((hi.y - origin.y) * scale.y))};
      const PixelRect r = intersected(intersected(clip, drawn), imageArea);
      if (r.empty()) continue;
      // Consecutive commands of a window usually overlap: one rectangle for them.
      if (!overlays.empty() && !intersected(overlays.back(), r).empty()) overlays.back() = united(overlays.back(), r);
      else overlays.push_back(r);
    }
  }
  return overlays;
}

uint64_t hashOf(const ImDrawData& drawData) {
  uint64_t h = 0;
  const auto mix = [&h](const void* data, std::size_t bytes) {
    const uint64_t v = std::hash<std::string_view>{}(std::string_view(static_cast<const char*>(data), bytes));
    h ^= v + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
  };
  const float frame[6] = {drawData.DisplayPos.x, drawData.DisplayPos.y, drawData.DisplaySize.x, drawData.DisplaySize.y,
                          drawData.FramebufferScale.x, drawData.FramebufferScale.y};
  mix(frame, sizeof frame);
  for (int n = 0; n < drawData.CmdListsCount; ++n) {
    const ImDrawList& list = *drawData.CmdLists[n];
    mix(list.VtxBuffer.Data, std::size_t(list.VtxBuffer.Size) * sizeof(ImDrawVert));
    mix(list.IdxBuffer.Data, std::size_t(list.IdxBuffer.Size) * sizeof(ImDrawIdx));
    for (const ImDrawCmd& cmd : list.CmdBuffer) {
      const float clip[4] = {cmd.ClipRect.x, cmd.ClipRect.y, cmd.ClipRect.z, cmd.ClipRect.w};
      const uint64_t counts[5] = {uint64_t(reinterpret_cast<uintptr_t>(cmd.TextureId)), cmd.VtxOffset, cmd.IdxOffset,
                                  cmd.ElemCount, uint64_t(cmd.UserCallback != nullptr)};
      mix(clip, sizeof clip);
      mix(counts, sizeof counts);
    }
  }
  return h;
}

}  // namespace fcc::render
