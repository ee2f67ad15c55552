// DVR's colour points in the panel (docs/VIEWER.md, "Transfer function"): under the histogram a bar
// in the function's colours on the histogram's value axis with a marker at each colour point (click
// to add one or grab it, drag to move, right-click to remove), and below the opacity segment's
// sliders the chosen point's colour and a button that removes it (ImGui's colour field: sRGB as shown, the function keeps it
// linear). The edits go to the TransferFunctionEditor, as the opacity points' do.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "Srgb.h"
#include "ViewerSession.h"

namespace fcc::render {
namespace {

ImU32 shownColour(const glm::dvec3& linear) {
  const glm::vec3 c = srgbFromLinear(glm::clamp(glm::vec3(linear), 0.0f, 1.0f));
  return ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1.0f));
}

}  // namespace

// The bar spans the histogram's frame; its value axis is the histogram's, [axisMin, axisMax] from x0
// to x1 (the frame less its padding).
void ViewerSession::editColorPoints(float x0, float x1, float axisMin, float axisMax) {
  const float scale = ImGui::GetIO().FontGlobalScale;
  const ImRectF frame = layout_.histogram;
  ImGui::InvisibleButton("##colour points", ImVec2(std::max(1.0f, frame.x1 - frame.x0), 12.0f * scale),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
  const bool hoveredItem = ImGui::IsItemHovered(), active = ImGui::IsItemActive();
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  layout_.colorBar = {lo.x, lo.y, hi.x, hi.y};
  layout_.colorPoints.clear();
  if (!(x1 > x0) || !(axisMax > axisMin)) return;
  const int count = int(editor_->colors().size());
  if (dragColor_ >= count) dragColor_ = -1;  // another colour map chosen meanwhile
  if (selectedColor_ >= count) selectedColor_ = -1;

  const ImGuiIO& io = ImGui::GetIO();
  const double valuePerPixel = double(axisMax - axisMin) / double(x1 - x0);
  const double mouseValue = axisMin + double(io.MousePos.x - x0) * valuePerPixel;  // the editor clamps it
  const float radius = std::max(4.0f, 6.0f * scale);
  const int hovered = hoveredItem ? editor_->pickColor(mouseValue, 1.0 / valuePerPixel, radius) : -1;
  if (hoveredItem && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    // A marker under the mouse is grabbed; elsewhere a new point is made there (in the colour the
    // function has there: nothing changes until it is moved or recoloured) and grabbed.
    dragColor_ = hovered >= 0 ? hovered : editor_->insertColor(mouseValue);
    selectedColor_ = dragColor_;
  } else if (active && dragColor_ >= 0 && ImGui::IsMouseDown(ImGuiMouseButton_Left) && io.MouseDelta.x != 0.0f) {
    editor_->moveColor(dragColor_, mouseValue);  // clamped between its neighbours: it keeps its index
  }
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) dragColor_ = -1;
  if (hovered >= 0 && ImGui::IsMouseClicked(ImGuiMouseButton_Right) && editor_->removeColor(hovered))
    dragColor_ = selectedColor_ = -1;  // never the last point
  if (hoveredItem && !active) {
    const glm::vec3 c = srgbFromLinear(glm::clamp(glm::vec3(editor_->function("").color(mouseValue)), 0.0f, 1.0f));
    ImGui::SetTooltip("colour at %.5g: %d, %d, %d (sRGB)\nclick: add a colour point; drag: move; right-click: remove",
                      std::clamp(mouseValue, double(axisMin), double(axisMax)), int(std::lround(255.0f * c.r)),
                      int(std::lround(255.0f * c.g)), int(std::lround(255.0f * c.b)));
  }

  // The colours as shown, one column a pixel, then the markers: a swatch of the point's colour in a
  // dark frame, the one under the mouse, held or chosen in a light frame.
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  const TransferFunction function = editor_->function("");
  const float barLo = lo.y + 0.25f * (hi.y - lo.y), barHi = hi.y;
  for (float x = std::floor(x0); x < x1; x += 1.0f) {
    const double v = axisMin + double(x + 0.5f - x0) * valuePerPixel;
    draw.AddRectFilled(ImVec2(std::max(x, x0), barLo), ImVec2(std::min(x + 1.0f, x1), barHi), shownColour(function.color(v)));
  }
  const int target = dragColor_ >= 0 ? dragColor_ : hovered;
  const float half = 0.5f * radius;
  for (std::size_t k = 0; k < editor_->colors().size(); ++k) {
    const ColorPoint& p = editor_->colors()[k];
    const float x = x0 + float((p.x - axisMin) / valuePerPixel);
    layout_.colorPoints.push_back({x - radius, lo.y, x + radius, hi.y});
    if (x < frame.x0 || x > frame.x1) continue;  // outside the axis: not drawn (still in the editor)
    const bool hot = int(k) == target || int(k) == selectedColor_;
    draw.AddRectFilled(ImVec2(x - half - 1.5f, lo.y), ImVec2(x + half + 1.5f, hi.y),
                       hot ? IM_COL32(255, 210, 90, 255) : IM_COL32(20, 20, 20, 255));
    draw.AddRectFilled(ImVec2(x - half, lo.y + 1.5f), ImVec2(x + half, hi.y - 1.5f), shownColour(p.rgb));
  }
}

// The chosen colour point's colour, as shown (sRGB); a component typed or dragged is written back
// linear, the others stay exactly what they were (a round trip through sRGB, or ImGui's 8 bits, would
// move them).
void ViewerSession::drawColorPointEdit() {
  if (selectedColor_ < 0 || selectedColor_ >= int(editor_->colors().size())) return;
  const ColorPoint& p = editor_->colors()[std::size_t(selectedColor_)];
  ImGui::TextDisabled("colour point at %.5g", p.x);
  const glm::vec3 shown = srgbFromLinear(glm::vec3(p.rgb));
  float edited[3] = {shown.r, shown.g, shown.b};
  const bool changed = ImGui::ColorEdit3("point colour", edited, ImGuiColorEditFlags_DisplayRGB);
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  layout_.colorPointEdit = {lo.x, lo.y, hi.x, hi.y};
  if (changed) {
    const double keep = std::numeric_limits<double>::quiet_NaN();
    glm::dvec3 rgb(keep);
    // ImGui's fields hand back every component in 8 bits after an edit of one: such a component is
    // the one shown, untouched.
    const auto untouched = [&](int c) {
      return edited[c] == shown[c] || edited[c] == float(std::lround(255.0f * shown[c])) / 255.0f;
    };
    for (int c = 0; c < 3; ++c)
      if (!untouched(c)) rgb[c] = double(linearFromSrgb(std::clamp(edited[c], 0.0f, 1.0f)));
    editor_->setColor(selectedColor_, rgb);
  }
  if (ImGui::SmallButton("remove colour point") && editor_->removeColor(selectedColor_)) dragColor_ = selectedColor_ = -1;
  const ImVec2 blo = ImGui::GetItemRectMin(), bhi = ImGui::GetItemRectMax();
  layout_.colorPointRemove = {blo.x, blo.y, bhi.x, bhi.y};
}

}  // namespace fcc::render
