// The panel's Surfaces section (the drawing half of ViewerSession, kept apart from ViewerPanel.cpp):
// up to kMaxIsosurfaces isosurfaces, each with its value (label and slider), colour and opacity; a
// radio button selects the one the isovalue keys and a click on the histogram move; surfaces are
// added (at the middle of the surface range, the next default colour, half opaque) and removed.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "Srgb.h"
#include "ViewerSession.h"

namespace fcc::render {
namespace {

ImRectF itemRect() {
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  return {lo.x, lo.y, hi.x, hi.y};
}

}  // namespace

void ViewerSession::drawSurfacesSection() {
  layout_.addSurface = layout_.removeLastSurface = {};
  if (!ImGui::CollapsingHeader("Isosurface", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const int count = 1 + int(settings_.moreSurfaces.size());
  settings_.selectedSurface = std::clamp(settings_.selectedSurface, 0, count - 1);
  int remove = -1;
  for (int k = 0; k < count; ++k) {
    float& iso = k == 0 ? settings_.iso : settings_.moreSurfaces[std::size_t(k - 1)].iso;
    glm::vec3& color = k == 0 ? settings_.surfaceColor : settings_.moreSurfaces[std::size_t(k - 1)].color;
    float& opacity = k == 0 ? settings_.surfaceOpacity : settings_.moreSurfaces[std::size_t(k - 1)].opacity;
    ImGui::PushID(k);
    if (count > 1) {
      // Which surface the keys move; the value follows on the same line.
      ImGui::RadioButton("##selected", &settings_.selectedSurface, k);
      ImGui::SameLine();
    }
    // The value above the slider, not in it: the slider's handle would cover it wherever it stands.
    if (count > 1) ImGui::Text("surface %d: isovalue %.6g", k + 1, double(iso));
    else ImGui::Text("isovalue %.6g", double(iso));
    if (k == 0) layout_.isoLabel = itemRect();
    ImGui::SetNextItemWidth(-1.0f);
    // Instant: the bounds do not depend on the isovalue, only which bricks are needed does. No text
    // in the slider (an empty format), so no rounding to one either; ctrl + click still types a value.
    if (ImGui::SliderFloat("##iso", &iso, summary_.valueMin, summary_.valueMax, "", ImGuiSliderFlags_NoRoundToFormat))
      settings_.selectedSurface = k;
    if (k == 0) layout_.isoSlider = itemRect();
    // The colour as drawn on screen (sRGB); converted back only on an edit (the defaults stay exact).
    glm::vec3 srgb = srgbFromLinear(color);
    if (ImGui::ColorEdit3("colour", &srgb.x, ImGuiColorEditFlags_Float)) color = linearFromSrgb(srgb);
    ImGui::SliderFloat("opacity", &opacity, 0.0f, 1.0f, "%.2f", ImGuiSliderFlags_AlwaysClamp);
    if (count > 1) {
      if (ImGui::SmallButton("remove")) remove = k;
      if (k == count - 1) layout_.removeLastSurface = itemRect();
    }
    ImGui::PopID();
  }
  if (count < kMaxIsosurfaces) {
    if (ImGui::Button("add surface")) {
      Isosurface added;
      added.iso = 0.5f * (summary_.valueMin + summary_.valueMax);
      added.color = defaultSurfaceColor(count);
      added.opacity = 0.5f;  // translucent: a new surface does not hide the others
      settings_.moreSurfaces.push_back(added);
      settings_.selectedSurface = count;
    }
    layout_.addSurface = itemRect();
  }
  if (remove >= 0) {
    std::vector<Isosurface> all = surfacesOfSettings();
    all.erase(all.begin() + remove);
    settings_.iso = all[0].iso;
    settings_.surfaceColor = all[0].color;
    settings_.surfaceOpacity = all[0].opacity;
    settings_.moreSurfaces.assign(all.begin() + 1, all.end());
    settings_.selectedSurface = std::min(settings_.selectedSurface, int(all.size()) - 1);
  }
  drawHistogram();  // marks every isovalue
}

}  // namespace fcc::render
