// What the viewer draws with ImGui's draw lists rather than as widgets: the axis indicator.
#pragma once

#include <imgui.h>

#include "Camera.h"

namespace fcc::render {

// Side of the axis indicator's square, in window units before the font scale.
inline constexpr float kAxisIndicatorSide = 56.0f;

// World x (red), y (green) and z (blue) as seen by `camera`, from `centre`, `radius` long when in the
// image plane; the axis nearest the viewer drawn last, each labelled at its tip.
void drawAxes(ImDrawList& drawList, ImVec2 centre, float radius, const Camera& camera);

}  // namespace fcc::render
