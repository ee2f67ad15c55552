// The panel's histogram under the isovalue slider: log counts, a value axis, a tooltip naming the
// bin under the mouse, and a click that sets the isovalue there.
#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <vector>

#include "HistogramAxis.h"
#include "Srgb.h"
#include "ViewerSession.h"

namespace fcc::render {

void ViewerSession::drawHistogram() {
  const std::vector<float>& h = summary_.histogram;
  layout_.histogram = {};
  if (h.empty()) return;
  const HistogramAxis axis{summary_.histogramMin, summary_.histogramMax, int(h.size())};
  // Logarithmic counts: a large background bin would flatten everything else.
  std::vector<float> logCounts(h.size());
  std::transform(h.begin(), h.end(), logCounts.begin(), [](float c) { return std::log1p(c); });
  const char* what = summary_.histogramOfSamples ? "samples" : "coefficients";
  char title[64];
  std::snprintf(title, sizeof title, "%s (log count)", what);
  const float scale = ImGui::GetIO().FontGlobalScale;
  const ImVec2 plotSize(ImGui::GetContentRegionAvail().x, 56.0f * scale);
  // DVR: the editor's invisible button over the plot's frame (viewer/PanelTransfer.cpp) takes the
  // mouse; submitted first, so that ImGui gives it the hover, not the plot drawn at the same place.
  bool editorHovered = false, editorActive = false;
  if (dvr_) {
    const ImVec2 start = ImGui::GetCursorScreenPos();
    ImGui::InvisibleButton("##opacity points", plotSize, ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight);
    editorHovered = ImGui::IsItemHovered();
    editorActive = ImGui::IsItemActive();
    ImGui::SetCursorScreenPos(start);
  }
  ImGui::PlotHistogram("##histogram", logCounts.data(), int(logCounts.size()), 0, title, 0.0f, FLT_MAX, plotSize);
  const ImVec2 outerLo = ImGui::GetItemRectMin(), outerHi = ImGui::GetItemRectMax();
  layout_.histogram = {outerLo.x, outerLo.y, outerHi.x, outerHi.y};
  // The bars span the frame less its padding, as ImGui lays them out and picks the hovered one.
  const ImVec2 pad = ImGui::GetStyle().FramePadding;
  const float x0 = outerLo.x + pad.x, x1 = outerHi.x - pad.x;
  const auto positionOfMouse = [&] { return x1 > x0 ? (ImGui::GetIO().MousePos.x - x0) / (x1 - x0) : 0.5f; };
  const bool plotHovered = dvr_ ? editorHovered && !editorActive : ImGui::IsItemHovered();
  if (plotHovered) {
    // Replaces ImGui's own tooltip (the bin's index and log count).
    const int bin = axis.binAt(positionOfMouse());
    char tip[256];
    const double v = axis.valueAt(positionOfMouse());
    if (dvr_)
      std::snprintf(tip, sizeof tip,
                    "%.5g .. %.5g: %.0f %s\nopacity at %.5g: %.3g\nclick: add a point; drag: move; right-click, Delete: remove",
                    axis.binLow(bin), axis.binHigh(bin), double(h[std::size_t(bin)]), what, v, dvr_->function.opacity(v));
    else
      std::snprintf(tip, sizeof tip, "%.5g .. %.5g: %.0f %s\nclick: isovalue %.5g", axis.binLow(bin), axis.binHigh(bin),
                    double(h[std::size_t(bin)]), what, v);
    ImGui::SetTooltip("%s", tip);
    layout_.histogramTooltip = tip;
  }
  if (dvr_) {
    drawOpacityCurve(x0, x1, outerHi.y - pad.y, outerLo.y + pad.y);
    editOpacityPoints(x0, x1, outerHi.y - pad.y, outerLo.y + pad.y, axis.min, axis.max, editorHovered,
                      editorActive);  // viewer/PanelTransfer.cpp
  } else if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) {
    // Where a surface can be: the samples' range may reach past the spline's.
    // The selected surface's isovalue (the Surfaces section selects it).
    selectedIso() = std::clamp(axis.valueAt(positionOfMouse()), summary_.valueMin, summary_.valueMax);
  }
  // Every isovalue's place in the histogram: a line in its surface's colour over a dark outline (a
  // light colour shows on the bars too), the selected one wider.
  if (!dvr_) {
    const std::vector<Isosurface> surfaces = surfacesOfSettings();
    for (std::size_t k = 0; k < surfaces.size(); ++k) {
      const float x = x0 + axis.positionOf(surfaces[k].iso) * (x1 - x0);
      const bool selected = int(k) == settings_.selectedSurface;
      const glm::vec3 c = srgbFromLinear(glm::clamp(surfaces[k].color, 0.0f, 1.0f));
      ImDrawList& draw = *ImGui::GetWindowDrawList();
      draw.AddLine(ImVec2(x, outerLo.y), ImVec2(x, outerHi.y), IM_COL32(20, 20, 20, 255), selected ? 4.0f : 3.0f);
      draw.AddLine(ImVec2(x, outerLo.y), ImVec2(x, outerHi.y),
                   IM_COL32(int(255.0f * c.r), int(255.0f * c.g), int(255.0f * c.b), 255), selected ? 2.5f : 1.5f);
    }
  }
  // DVR: the colour points on a bar of the function's colours, right under the plot and on its axis.
  if (dvr_) editColorPoints(x0, x1, axis.min, axis.max);  // viewer/PanelColorPoints.cpp
  // The value axis: the first bin's low end under the left edge, the last bin's high end under the right.
  char low[32], high[32];
  std::snprintf(low, sizeof low, "%.4g", double(axis.min));
  std::snprintf(high, sizeof high, "%.4g", double(axis.max));
  ImGui::TextDisabled("%s", low);
  ImGui::SameLine(std::max(0.0f, outerHi.x - ImGui::GetWindowPos().x - ImGui::CalcTextSize(high).x));
  ImGui::TextDisabled("%s", high);
}

// DVR: the transfer function's opacity over the histogram's value axis (0 at yLo, 1 at yHi), one
// segment per pixel column, each in the function's colour there (as shown: sRGB) over a light outline
// so that dark colours show on the panel.
void ViewerSession::drawOpacityCurve(float x0, float x1, float yLo, float yHi) {
  const HistogramAxis axis{summary_.histogramMin, summary_.histogramMax, std::max(1, int(summary_.histogram.size()))};
  const int n = std::max(2, int(x1 - x0));
  std::vector<ImVec2> points(std::size_t(n) + 1);
  std::vector<ImU32> colours(points.size());
  for (int i = 0; i <= n; ++i) {
    const float t = float(i) / float(n);
    const double v = axis.valueAt(t);
    points[std::size_t(i)] = ImVec2(x0 + t * (x1 - x0), yLo + float(dvr_->function.opacity(v)) * (yHi - yLo));
    const glm::vec3 c = srgbFromLinear(glm::vec3(dvr_->function.color(v)));
    colours[std::size_t(i)] = ImGui::ColorConvertFloat4ToU32(ImVec4(c.x, c.y, c.z, 1.0f));
  }
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  const float scale = ImGui::GetIO().FontGlobalScale;
  draw.AddPolyline(points.data(), int(points.size()), IM_COL32(230, 230, 230, 255), ImDrawFlags_None, 3.5f * scale);
  for (int i = 0; i < n; ++i)
    draw.AddLine(points[std::size_t(i)], points[std::size_t(i) + 1], colours[std::size_t(i)], 1.5f * scale);
}

}  // namespace fcc::render
