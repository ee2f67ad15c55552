// The viewer's drawing over the image (the streaming line, notices, the axis indicator without the
// panel) and the axis indicator itself.
#include "ViewerOverlays.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <numeric>
#include <utility>

#include "AxisIndicator.h"
#include "ViewerSession.h"

namespace fcc::render {

void drawAxes(ImDrawList& drawList, ImVec2 centre, float radius, const Camera& camera) {
  const std::array<glm::dvec3, 3> axes = worldAxesInView(camera);
  static const ImU32 kColours[3] = {IM_COL32(230, 70, 60, 255), IM_COL32(90, 200, 80, 255), IM_COL32(80, 140, 255, 255)};
  static const char* const kNames[3] = {"x", "y", "z"};
  std::array<int, 3> order;
  std::iota(order.begin(), order.end(), 0);
  // Painter's order: the axis pointing away from the viewer first.
  std::sort(order.begin(), order.end(), [&](int a, int b) { return axes[std::size_t(a)].z < axes[std::size_t(b)].z; });
  for (int k : order) {
    const glm::dvec3& a = axes[std::size_t(k)];
    const ImVec2 tip(centre.x + radius * float(a.x), centre.y - radius * float(a.y));  // image y grows down
    drawList.AddLine(centre, tip, kColours[k], 2.0f);
    drawList.AddText(ImVec2(tip.x - 3.0f, tip.y - 7.0f), kColours[k], kNames[k]);
  }
}

std::string ViewerSession::statusLine() const {
  if (settled()) return {};
  char text[96];
  if (stats_.streaming > 0)
    std::snprintf(text, sizeof text, "streaming %zu bricks (%zu at the isovalue not loaded)", stats_.streaming,
                  stats_.missing);
  else
    std::snprintf(text, sizeof text, "refining (%u bricks requested)", stats_.requested);
  return text;
}

void ViewerSession::drawStreamingLine(int windowHeight) {
  if (shownStatusLine_.empty()) return;
  const ImVec2 at(panelWidth() + 10.0f, float(windowHeight) - ImGui::GetFontSize() - 10.0f);
  ImGui::GetForegroundDrawList()->AddText(at, IM_COL32(255, 255, 255, 220), shownStatusLine_.c_str());
}

void ViewerSession::drawNotice() {
  if (notice_.empty()) return;
  const ImVec2 at(panelWidth() + 10.0f, 10.0f);
  const ImVec2 size = ImGui::CalcTextSize(notice_.c_str());
  ImDrawList& list = *ImGui::GetForegroundDrawList();
  // A dark box under the text: readable over any surface colour.
  list.AddRectFilled(ImVec2(at.x - 4.0f, at.y - 2.0f), ImVec2(at.x + size.x + 4.0f, at.y + size.y + 2.0f),
                     IM_COL32(0, 0, 0, 180));
  list.AddText(at, IM_COL32(255, 255, 255, 255), notice_.c_str());
}

void ViewerSession::drawOpenField() {
  if (!openField_.shown) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0.5f * (panelWidth() + display.x), 0.3f * display.y), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(0.5f * (display.x - panelWidth()), 0.0f));
  ImGui::Begin("Open a file", &openField_.shown, ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings);
  ImGui::TextUnformatted("any file `fccvdb view` takes (or drop one on the window)");
  if (std::exchange(openField_.focus, false)) ImGui::SetKeyboardFocusHere();
  ImGui::SetNextItemWidth(-1.0f);
  const bool entered = ImGui::InputText("##path", openField_.path, sizeof openField_.path, ImGuiInputTextFlags_EnterReturnsTrue);
  // Esc closes the field (and, the field having the keys this frame, does not quit the viewer).
  const bool cancelled = ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape), false);
  if ((entered || ImGui::Button("open")) && openField_.path[0] != '\0') {
    openRequest_ = OpenRequest{std::string(openField_.path), {}};
    openField_.shown = false;
  }
  if (cancelled) openField_.shown = false;
  ImGui::End();
}

void ViewerSession::drawAxisIndicator(int windowHeight) {
  if (settings_.showPanel) return;  // the panel's Camera section holds it (ViewerPanel.cpp)
  const float side = kAxisIndicatorSide * ImGui::GetIO().FontGlobalScale;
  drawAxes(*ImGui::GetForegroundDrawList(), ImVec2(0.5f * side + 8.0f, float(windowHeight) - 0.5f * side - 8.0f),
           0.4f * side, camera_);
}

}  // namespace fcc::render
