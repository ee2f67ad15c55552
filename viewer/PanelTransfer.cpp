// DVR's transfer-function editor in the panel (docs/VIEWER.md, "Transfer function"): the opacity
// control points over the histogram (click to add, drag to move, right-click or Delete to remove),
// the shape of the segment after the last grabbed point (ParaView's midpoint and sharpness), the
// colour map, and the function saved to or loaded from a file (ParaView colour-map JSON, the
// reader of --tf). The edits go to a TransferFunctionEditor (viewer/TransferFunctionEditor.h); the
// session rebuilds the GPU's table from it (ViewerSession::applyTransfer).
#define GLFW_INCLUDE_NONE  // key codes only
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "OutputNames.h"
#include "ViewerSession.h"
#include "io/TransferFunctionFile.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {

ImRectF lastRect() {
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  return {lo.x, lo.y, hi.x, hi.y};
}

}  // namespace

// Over the histogram's frame (layout_.histogram), an invisible button takes the mouse (drawHistogram
// submits it: hoveredItem, active): the value axis is the histogram's, [axisMin, axisMax] from x0 to
// x1, the opacity 0 at yLo and 1 at yHi.
void ViewerSession::editOpacityPoints(float x0, float x1, float yLo, float yHi, float axisMin, float axisMax,
                                     bool hoveredItem, bool active) {
  layout_.opacityPoints.clear();
  if (!(x1 > x0) || !(yLo > yHi) || !(axisMax > axisMin)) return;
  const ImRectF frame = layout_.histogram;

  const ImGuiIO& io = ImGui::GetIO();
  const double valuePerPixel = double(axisMax - axisMin) / double(x1 - x0);
  const double pixelsPerOpacity = double(yLo - yHi);
  // Positions past the axis give values past it: the editor clamps them into its range.
  const double mouseValue = axisMin + double(io.MousePos.x - x0) * valuePerPixel;
  const double mouseAlpha = double(yLo - io.MousePos.y) / pixelsPerOpacity;
  const float scale = ImGui::GetIO().FontGlobalScale;
  const float radius = std::max(4.0f, 8.0f * scale);
  const int hovered = hoveredItem ? editor_->pick(mouseValue, mouseAlpha, 1.0 / valuePerPixel, pixelsPerOpacity, radius) : -1;
  if (dragPoint_ >= int(editor_->points().size())) dragPoint_ = -1;

  if (hoveredItem && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
    // A point under the mouse is grabbed; elsewhere a new one is made there and grabbed.
    dragPoint_ = hovered >= 0 ? hovered : editor_->insert(mouseValue, mouseAlpha);
    shapePoint_ = dragPoint_;
  } else if (active && dragPoint_ >= 0 && ImGui::IsMouseDown(ImGuiMouseButton_Left) &&
             (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
    editor_->move(dragPoint_, mouseValue, mouseAlpha);  // clamped between its neighbours: it stays dragPoint_
  }
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) dragPoint_ = -1;
  const int target = dragPoint_ >= 0 ? dragPoint_ : hovered;
  if ((hovered >= 0 && ImGui::IsMouseClicked(ImGuiMouseButton_Right)) ||
      (target >= 0 && !io.WantTextInput && ImGui::IsKeyPressed(GLFW_KEY_DELETE, false))) {
    editor_->remove(ImGui::IsMouseClicked(ImGuiMouseButton_Right) ? hovered : target);  // never the last point
    dragPoint_ = shapePoint_ = -1;
  }

  // The points as handles: a light disc in a dark ring, the one under the mouse or held larger.
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  for (std::size_t k = 0; k < editor_->points().size(); ++k) {
    const OpacityPoint& p = editor_->points()[k];
    const float x = x0 + float((p.x - axisMin) / valuePerPixel), y = yLo - float(p.alpha * pixelsPerOpacity);
    layout_.opacityPoints.push_back({x - radius, y - radius, x + radius, y + radius});
    if (x < frame.x0 || x > frame.x1) continue;  // outside the axis: not drawn (still in the editor)
    const bool hot = int(k) == target;
    const float r = (hot ? 0.75f : 0.55f) * radius;
    draw.AddCircleFilled(ImVec2(x, y), r + 1.5f * std::max(scale, 0.5f), IM_COL32(20, 20, 20, 255));
    draw.AddCircleFilled(ImVec2(x, y), r, hot ? IM_COL32(255, 210, 90, 255) : IM_COL32(240, 240, 240, 255));
  }
}

// Below the histogram, once a point was grabbed: the shape of the segment from it to the next point,
// ParaView's midpoint (where the opacity is halfway) and sharpness (0 a line, 1 a step there).
void ViewerSession::drawSegmentShape() {
  const int count = int(editor_->points().size());
  if (shapePoint_ < 0 || shapePoint_ + 1 >= count) return;  // no point chosen, or the last: no segment after it
  const OpacityPoint& p = editor_->points()[std::size_t(shapePoint_)];
  ImGui::TextDisabled("segment from %.5g to %.5g", p.x, editor_->points()[std::size_t(shapePoint_) + 1].x);
  float midpoint = float(p.midpoint), sharpness = float(p.sharpness);
  const bool midpointMoved = ImGui::SliderFloat("midpoint", &midpoint, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
  layout_.segmentMidpointSlider = lastRect();
  const bool sharpnessMoved = ImGui::SliderFloat("sharpness", &sharpness, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_AlwaysClamp);
  layout_.segmentSharpnessSlider = lastRect();
  if (midpointMoved || sharpnessMoved)
    editor_->setShape(shapePoint_, midpointMoved ? double(midpoint) : p.midpoint, sharpnessMoved ? double(sharpness) : p.sharpness);
}

// Below the histogram: the colour map, and the function to or from a file.
void ViewerSession::drawTransferFiles() {
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);
  if (ImGui::BeginCombo("colour map", editor_->colorMapName().c_str())) {
    for (const auto& [name, colors] : colorMaps_)
      if (ImGui::Selectable(name.c_str(), name == editor_->colorMapName())) {
        editor_->setColors(colors, name);
        dragColor_ = selectedColor_ = -1;  // the points are the new map's
      }
    ImGui::EndCombo();
  }
  layout_.colorMapCombo = lastRect();
  // What --tf takes: a ParaView .json (FILE.json:NAME for one of its maps), a text file, a preset.
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::InputTextWithHint("##transfer file", "file.json[:map], text file or preset", transferPath_,
                           sizeof transferPath_);
  layout_.transferPathField = lastRect();
  if (ImGui::Button("load")) {
    try {
      loadTransferFunction(transferPath_);
    } catch (const std::exception& e) {
      notify(e.what());  // a bad file is a notice, not the end of the session
    }
  }
  layout_.transferLoad = lastRect();
  ImGui::SameLine();
  if (ImGui::Button("save as ParaView JSON")) {
    try {
      saveTransferFunction();
    } catch (const std::exception& e) {
      notify(e.what());
    }
  }
  layout_.transferSave = lastRect();
  // Every edit above (points, shapes, colours, the colour map) can be undone: ctrl + Z, ctrl + Y.
  ImGui::BeginDisabled(!editor_->canUndo());
  if (ImGui::Button("undo")) undoTransferEdit(false);
  ImGui::EndDisabled();
  layout_.transferUndo = lastRect();
  ImGui::SameLine();
  ImGui::BeginDisabled(!editor_->canRedo());
  if (ImGui::Button("redo")) undoTransferEdit(true);
  ImGui::EndDisabled();
  layout_.transferRedo = lastRect();
}

void ViewerSession::undoTransferEdit(bool redo) {
  if (!(redo ? editor_->redo() : editor_->undo())) {
    notify(redo ? "nothing to redo" : "nothing to undo in the transfer function");
    return;
  }
  dragPoint_ = shapePoint_ = dragColor_ = selectedColor_ = -1;  // the indices were the other state's
}

TransferFunction ViewerSession::baseFunction(const std::string& name) const {
  // What --tf named (a file's function, kept), one loaded from the panel, else a preset fitted to
  // the source as `render` fits it.
  if (name == initialDvr_->spec) return initialDvr_->function;
  for (const auto& [spec, function] : loadedFunctions_)
    if (spec == name) return function;
  return fitTransferFunction(transferFunctionPreset(name), source());
}

void ViewerSession::addColorMapsOf(const std::string& spec) {
  const io::TransferFunctionSpec file = io::splitTransferFunctionSpec(spec);
  const std::string ext = std::filesystem::path(file.path).extension().string();
  if (isTransferFunctionPreset(spec) || (ext != ".json" && ext != ".JSON" && ext != ".Json")) return;
  for (const TransferFunction& map : io::readParaViewColorMaps(file.path)) {
    const auto same = [&](const auto& entry) { return entry.first == map.name(); };
    colorMaps_.erase(std::remove_if(colorMaps_.begin(), colorMaps_.end(), same), colorMaps_.end());
    colorMaps_.emplace_back(map.name(), map.colors());
  }
}

void ViewerSession::loadTransferFunction(const std::string& spec) {
  if (!dvr_) throw ValueError("a transfer function applies in DVR mode only (view --mode dvr)");
  if (spec.empty()) throw ValueError("load: type a transfer function file (or a preset) into the field first");
  const TransferFunction function = fitTransferFunction(io::transferFunctionFromSpec(spec), source());
  addColorMapsOf(spec);
  const auto same = [&](const auto& entry) { return entry.first == spec; };
  loadedFunctions_.erase(std::remove_if(loadedFunctions_.begin(), loadedFunctions_.end(), same), loadedFunctions_.end());
  if (spec != initialDvr_->spec) loadedFunctions_.emplace_back(spec, function);
  else initialDvr_->function = function;  // --tf's file read again
  settings_.transferFunction = spec;
  reloadBase_ = true;  // even when it is the spec in use: the file may have changed
  notify("transfer function loaded from " + spec);
}

std::string ViewerSession::saveTransferFunction() {
  if (!dvr_) throw ValueError("a transfer function applies in DVR mode only (view --mode dvr)");
  const std::string stem = uniqueTimestampedStem(outputDirectory_, "fccvdb-tf", {".json"});
  const std::string path = stem + ".json";
  io::writeParaViewColorMap(path, dvr_->function, std::filesystem::path(stem).filename().string(), /*overwrite=*/false);
  const std::string line = "transfer function saved to " + path + " (use it with --mode dvr --tf)";
  if (report_) report_(line);
  notify(line);
  return path;
}

}  // namespace fcc::render
