// What the viewer needs to know of a frame's Dear ImGui draw data to draw only what changed
// (RedrawTracker.h): where it covers the image, and whether it is the same as an earlier frame's.
#pragma once

#include <imgui.h>

#include <cstdint>
#include <vector>

#include "PixelRect.h"

namespace fcc::render {

// The rectangles of `imageArea` (framebuffer pixels, rows from the top) that the draw data draws
// into, conservatively; overlapping consecutive commands give one rectangle. ImGui's coordinates are
// window units from the top left, scaled by drawData.FramebufferScale.
std::vector<PixelRect> overlaysOf(const ImDrawData& drawData, const PixelRect& imageArea);

// A hash of everything ImGui's OpenGL backend draws from (display, vertices, indices, commands):
// equal draw data, equal hash; so equal hashes stand for equal pixels.
uint64_t hashOf(const ImDrawData& drawData);

}  // namespace fcc::render
