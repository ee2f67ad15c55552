// The viewer's ImGui panel, help window and streaming line (the drawing half of ViewerSession).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cfloat>
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>

#include "Srgb.h"
#include "ViewerOverlays.h"
#include "ViewerSession.h"

namespace fcc::render {
namespace {


std::string mib(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", bytes / double(1 << 20));
  return text;
}

std::string count(uint64_t n) {
  char text[32];
  if (n >= 10'000'000) std::snprintf(text, sizeof text, "%.1f M", double(n) / 1e6);
  else if (n >= 10'000) std::snprintf(text, sizeof text, "%.1f k", double(n) / 1e3);
  else std::snprintf(text, sizeof text, "%llu", (unsigned long long)n);
  return text;
}

// A label and a value in two columns.
void row(const char* label, const std::string& value) {
  ImGui::TextUnformatted(label);
  ImGui::SameLine(ImGui::GetFontSize() * 8.0f);
  ImGui::TextUnformatted(value.c_str());
}

void usageBar(const char* label, double used, double budget) {
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, "%s / %s", mib(used).c_str(), mib(budget).c_str());
  ImGui::TextUnformatted(label);
  ImGui::SameLine(ImGui::GetFontSize() * 8.0f);
  ImGui::ProgressBar(budget > 0.0 ? float(std::min(used / budget, 1.0)) : 0.0f, ImVec2(-1.0f, 0.0f), overlay);
}

ImRectF lastItemRect() {
  const ImVec2 lo = ImGui::GetItemRectMin(), hi = ImGui::GetItemRectMax();
  return {lo.x, lo.y, hi.x, hi.y};
}

// A colour's fields and swatch (sRGB, 0..1), then its label; `swatch` gets where the swatch is.
bool colourEdit(const char* label, glm::vec3& srgb, ImRectF* swatch = nullptr) {
  ImGui::PushID(label);
  const bool changed = ImGui::ColorEdit3("##colour", &srgb.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_NoLabel);
  // Without its label the widget ends with the swatch, a square of the frame's height.
  const ImRectF all = lastItemRect();
  if (swatch) *swatch = {all.x1 - ImGui::GetFrameHeight(), all.y0, all.x1, all.y0 + ImGui::GetFrameHeight()};
  ImGui::SameLine(0.0f, ImGui::GetStyle().ItemInnerSpacing.x);
  ImGui::TextUnformatted(label);
  ImGui::PopID();
  return changed;
}

}  // namespace

void ViewerSession::drawLightSliders() {
  // Light direction in camera space as azimuth (from the view axis towards the right) and elevation;
  // written back only when moved, so the default light stays bit-exact.
  const glm::vec3 l = glm::normalize(settings_.lightInCamera);
  float azimuth = glm::degrees(std::atan2(l.x, l.z)), elevation = glm::degrees(std::asin(std::clamp(l.y, -1.0f, 1.0f)));
  bool lightMoved = ImGui::SliderFloat("light azimuth", &azimuth, -180.0f, 180.0f, "%.0f deg");
  layout_.lightAzimuthSlider = lastItemRect();
  lightMoved |= ImGui::SliderFloat("light elevation", &elevation, -89.0f, 89.0f, "%.0f deg");
  layout_.lightElevationSlider = lastItemRect();
  if (lightMoved) settings_.lightInCamera = lightInCameraFromAngles(azimuth, elevation);
}

void ViewerSession::drawPanel(int windowHeight) {
  if (!settings_.showPanel) return;
  ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
  ImGui::SetNextWindowSize(ImVec2(panelWidth_, float(windowHeight)));
  // Opaque: the raycaster casts no rays under it (ViewerSession::frame). No border: it would reach a
  // pixel or two into the image, and then the panel would count as drawn over the image every frame.
  ImGui::SetNextWindowBgAlpha(1.0f);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
  ImGui::Begin("fccvdb", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  ImGui::PopStyleVar();
  ImGui::PushItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);  // room for the labels

  layout_.isoLabel = layout_.isoSlider = layout_.transferCombo = layout_.densitySlider = {};
  layout_.unitDistanceSlider = layout_.stopOpacitySlider = layout_.shadingCheckbox = {};
  layout_.specularSlider = layout_.specularPowerSlider = {};
  layout_.lightButtons = {};
  layout_.lightAzimuthSlider = layout_.lightElevationSlider = {};
  layout_.colorMapCombo = layout_.transferPathField = layout_.transferLoad = layout_.transferSave = {};
  layout_.transferUndo = layout_.transferRedo = {};
  layout_.opacityPoints.clear();
  layout_.colorBar = layout_.colorPointEdit = layout_.colorPointRemove = {};
  layout_.colorPoints.clear();
  layout_.segmentMidpointSlider = layout_.segmentSharpnessSlider = {};
  if (dvr()) {
    drawTransferSection();
  } else {
    drawSurfacesSection();  // viewer/PanelSurfaces.cpp: the surfaces, their values, colours and opacities
  }
  if (!dvr() && ImGui::CollapsingHeader("Shading", ImGuiTreeNodeFlags_DefaultOpen)) {
    drawLightSliders();
    // The renderer's colours are linear; the swatches and fields show them as drawn on screen (sRGB),
    // and an edit is converted back (only then: the defaults stay bit-exact). The surfaces' colours
    // are in their section.
    glm::vec3 background = srgbFromLinear(settings_.background);
    if (colourEdit("background", background, &layout_.backgroundSwatch))
      settings_.background = linearFromSrgb(background);
  } else if (dvr() && ImGui::CollapsingHeader("Background", ImGuiTreeNodeFlags_DefaultOpen)) {
    // The colour the volume is composited over (DVR's light is under Renderer, with its shading).
    glm::vec3 background = srgbFromLinear(settings_.background);
    if (colourEdit("background", background, &layout_.backgroundSwatch))
      settings_.background = linearFromSrgb(background);
  }
  layout_.reconstructionCombo = {};
  layout_.reconstructionItems.clear();
  if (ImGui::CollapsingHeader("Renderer", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Checkbox("empty-space skipping", &settings_.skipEmpty);
    if (!dvr()) ImGui::Checkbox("finite-difference normals", &settings_.finiteDifferenceNormals);
    if (dvr()) {
      ImGui::Checkbox("gradient shading", &settings_.dvrShading.on);
      layout_.shadingCheckbox = lastItemRect();
      if (settings_.dvrShading.on) {  // the highlight: K |cos|^P (docs/DVR.md)
        ImGui::SliderFloat("specular", &settings_.dvrShading.specular, 0.0f, 1.0f, "%.3f", ImGuiSliderFlags_NoRoundToFormat);
        layout_.specularSlider = lastItemRect();
        ImGui::SliderFloat("specular power", &settings_.dvrShading.specularPower, 1.0f, 200.0f, "%.3g",
                           ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_NoRoundToFormat);
        layout_.specularPowerSlider = lastItemRect();
        // The light: the headlight (along each ray), one fixed to the camera (the isosurface's, with
        // its sliders) or the light kit (viewer/DvrLight.h).
        for (DvrLight light : {DvrLight::Headlight, DvrLight::Directional, DvrLight::Kit}) {
          if (light != DvrLight::Headlight) ImGui::SameLine();
          DvrLight& chosen = settings_.dvrShading.light;
          if (ImGui::RadioButton(dvrLightName(light).c_str(), chosen == light)) chosen = light;
          layout_.lightButtons[std::size_t(light)] = lastItemRect();
        }
        if (settings_.dvrShading.light == DvrLight::Directional) drawLightSliders();
      }
    }
    row("mode", dvr() ? "direct volume rendering" : "isosurface");
    drawReconstructionChoice();
    row("brick layout", brickLayoutName(*raycaster_.options().layout));
  }
  drawCameraSection();
  drawClipSection();
  drawCursorSection();
  if (ImGui::CollapsingHeader("Dataset", ImGuiTreeNodeFlags_DefaultOpen)) {
    row("file", summary_.file);
    if (!summary_.grid.empty()) row("grid", summary_.grid);
    std::string lattice(latticeName(source().reconstruction().lattice));
    std::transform(lattice.begin(), lattice.end(), lattice.begin(), [](unsigned char c) { return char(std::toupper(c)); });
    row("lattice", lattice + ", " + std::string(source().reconstruction().name));  // the reconstruction
    if (summary_.samples > 0) row("samples", count(summary_.samples));
    row("bricks", count(summary_.bricks));
    row("memory", mib(double(summary_.bytes)) + " decoded");
    // Two ranges, named as `fccvdb info` names them: the samples' (the data) and the spline's (the
    // isovalues with a surface: the slider's range; for DVR, the values the transfer function meets).
    char range[64];
    if (summary_.hasDataRange) {
      std::snprintf(range, sizeof range, "%.4g .. %.4g", double(summary_.dataMin), double(summary_.dataMax));
      row("data range", range);
    }
    std::snprintf(range, sizeof range, "%.4g .. %.4g", double(summary_.valueMin), double(summary_.valueMax));
    row(dvr() ? "value range" : "surface range", range);
    const io::Damage damage = source().damage();
    if (damage.count > 0) {
      // Damaged bricks (FCC) or leaves (Cartesian) are never trusted: they show as holes; the panel
      // says so, and which.
      ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 140, 90, 255));
      ImGui::TextWrapped("%s shown as holes. First: %s", io::damagedCountText(damage).c_str(), damage.first.c_str());
      ImGui::PopStyleColor();
    }
  }
  if (ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) {
    char frame[64];
    std::snprintf(frame, sizeof frame, "%.2f ms (%.0f fps)", stats_.frameMs, stats_.fps);
    row("frame", frame);
    // Bricks "at the isovalue" are all those whose bounds hold it, in the whole dataset; rays load only
    // those they reach, so a complete image leaves the hidden and off-screen ones unloaded.
    row("resident", count(stats_.resident) + " bricks");
    // In DVR mode: the bricks the transfer function gives an opacity somewhere.
    row(dvr() ? "needed" : "at isovalue", count(stats_.needed) + " bricks");
    row("not loaded", count(stats_.missing) + (stats_.complete ? " (no ray reaches them)" : " (streaming or unreached)"));
    row("requested", count(stats_.requested) + " (last pass)");
    row("streaming", count(stats_.streaming) + " bricks");
    if (raycaster_.levelCount() > 1) {
      // The level mix: bricks drawn per pyramid level (coarse ones stand in while finer ones stream),
      // the share of the surface's final pixels drawn at full resolution, and the bias in effect.
      std::string mix;
      for (std::size_t k = 0; k < stats_.levels.bricksPerLevel.size(); ++k)
        mix += (k ? "  L" : "L") + std::to_string(k) + " " + count(stats_.levels.bricksPerLevel[k]);
      row("levels", mix);
      std::string standIn;
      for (std::size_t k = 0; k < stats_.levels.standInBricksPerLevel.size(); ++k)
        if (stats_.levels.standInBricksPerLevel[k])
          standIn += (standIn.empty() ? "L" : "  L") + std::to_string(k) + " " + count(stats_.levels.standInBricksPerLevel[k]);
      if (!standIn.empty()) row("stand-ins", standIn);
      char full[96];
      std::snprintf(full, sizeof full, "%.0f%% of surface pixels, bias %g%s", 100.0 * stats_.levels.fullResolutionFraction,
                    stats_.levels.lodBias, raycaster_.lodBias() > double(raycaster_.options().lodBias) ? " (raised: GPU cache)" : "");
      row("full res", full);
    }
    usageBar("GPU cache", double(stats_.resident) * double(raycaster_.slotBytes()), double(raycaster_.poolBytes()));
    const HostCacheUse hostCache = raycaster_.hostCacheUse();
    if (hostCache.budgetBytes > 0) usageBar("host cache", double(hostCache.bytesUsed), double(hostCache.budgetBytes));
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.1f MiB/s", stats_.uploadMiBPerSecond);
    row("uploads", rate);
    char drawn[32];
    // Pixels each frame drew again (RedrawTracker), not how complete the image is.
    std::snprintf(drawn, sizeof drawn, "%.0f%% of the image", 100.0 * stats_.imageDrawnAverage);
    row("redrawn", drawn);
  }
  ImGui::TextDisabled("H or F1: help");
  layout_.panelEnd = lastItemRect();
  layout_.panelScrollMax = ImGui::GetScrollMaxY();  // ImGui scrolls a window taller than its content fits
  ImGui::PopItemWidth();
  ImGui::End();
}

// The reconstructions the source's lattice has: a Cartesian grid's CC ones or a BCC dataset's BCC ones
// to choose from (a choice opens the data again with it, ViewerSession::frame), FCC data's one without
// a choice.
void ViewerSession::drawReconstructionChoice() {
  const ReconstructionInfo& inUse = source().reconstruction();
  std::vector<const ReconstructionInfo*> choices;
  for (const ReconstructionInfo& info : reconstructionInfos())
    if (info.lattice == inUse.lattice) choices.push_back(&info);
  // Only a Cartesian grid or a BCC dataset rendered as it is can be read with another of its lattice's.
  if ((inUse.lattice != Lattice::Cc && inUse.lattice != Lattice::Bcc) || choices.size() < 2) {
    row("reconstruction", std::string(inUse.name));
    return;
  }
  const bool open = ImGui::BeginCombo("reconstruction", settings_.reconstruction.c_str());
  if (!open) layout_.reconstructionCombo = lastItemRect();  // the closed combo (open: the popup is current)
  if (!open) return;
  for (const ReconstructionInfo* info : choices) {
    const std::string name(info->name);
    if (ImGui::Selectable(name.c_str(), settings_.reconstruction == name)) settings_.reconstruction = name;
    layout_.reconstructionItems.emplace_back(name, lastItemRect());
  }
  ImGui::EndCombo();
}

void ViewerSession::drawTransferSection() {
  if (!ImGui::CollapsingHeader("Transfer function", ImGuiTreeNodeFlags_DefaultOpen)) return;
  // The presets, what --tf named when that is a file (kept as it was read), and files loaded here:
  // the starting points of the editor (choosing one replaces the points).
  std::vector<std::string> names;
  if (!isTransferFunctionPreset(initialDvr_->spec)) names.push_back(initialDvr_->spec);
  for (const auto& loaded : loadedFunctions_)
    if (!isTransferFunctionPreset(loaded.first)) names.push_back(loaded.first);
  for (const std::string& preset : transferFunctionPresetNames()) names.push_back(preset);
  ImGui::SetNextItemWidth(-1.0f);
  // The editor's starting point, unless another one is chosen and not applied yet (an undo across a
  // starting point this frame has not been applied either: the editor's spec is the one shown).
  const std::string& base = settings_.transferFunction == dvr_->spec ? editor_->spec() : settings_.transferFunction;
  const std::string shown = base + (editor_->edited() ? " (edited)" : "");
  if (ImGui::BeginCombo("##transfer", shown.c_str())) {
    for (const std::string& name : names)
      if (ImGui::Selectable(name.c_str(), name == settings_.transferFunction)) settings_.transferFunction = name;
    ImGui::EndCombo();
  }
  layout_.transferCombo = lastItemRect();
  // Logarithmic: the useful scales span decades. Ctrl + click types any value (0: transparent).
  ImGui::SliderFloat("density scale", &settings_.densityScale, 0.01f, 100.0f, "%.3g",
                     ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_NoRoundToFormat);
  layout_.densitySlider = lastItemRect();
  // An opacity in the function is that of a segment this long (world units): logarithmic too.
  ImGui::SliderFloat("unit distance", &settings_.unitDistance, 0.01f * initialUnitDistance_, 100.0f * initialUnitDistance_,
                     "%.4g", ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_NoRoundToFormat);
  layout_.unitDistanceSlider = lastItemRect();
  ImGui::SliderFloat("stop opacity", &settings_.stopOpacity, 0.5f, 1.0f, "%.3f", ImGuiSliderFlags_NoRoundToFormat);
  layout_.stopOpacitySlider = lastItemRect();
  drawHistogram();  // with the opacity curve and the editor's points over it
  drawSegmentShape();   // viewer/PanelTransfer.cpp
  drawColorPointEdit();  // viewer/PanelColorPoints.cpp
  drawTransferFiles();
}

void ViewerSession::drawCameraSection() {
  if (!ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) return;
  const auto triple = [](const glm::dvec3& v) {
    char text[96];
    std::snprintf(text, sizeof text, "%.4g, %.4g, %.4g", v.x, v.y, v.z);
    return std::string(text);
  };
  row("eye", triple(camera_.eye));
  row("look at", triple(camera_.lookat));
  row("up", triple(camera_.up));
  char fov[32];
  std::snprintf(fov, sizeof fov, "%.4g deg", camera_.fovYDegrees);
  row("fov", fov);
  if (ImGui::Button("save and copy (C)")) {
    try {
      saveCamera();
    } catch (const std::exception& e) {
      notify(e.what());  // an unwritable directory must not end the session
    }
  }
  // The axis indicator at the section's right edge, beside the button. In the panel, not over the
  // image: the image beside an unchanged panel is then all a settled frame draws (ViewerSession::frame).
  const float side = kAxisIndicatorSide * ImGui::GetIO().FontGlobalScale;
  ImGui::SameLine(std::max(ImGui::GetCursorPosX(), ImGui::GetWindowContentRegionMax().x - side));
  const ImVec2 corner = ImGui::GetCursorScreenPos();
  ImGui::Dummy(ImVec2(side, side));
  drawAxes(*ImGui::GetWindowDrawList(), ImVec2(corner.x + 0.5f * side, corner.y + 0.5f * side), 0.4f * side, camera_);
}

// An axis-aligned box in world space, per axis a range over the data's extent (padded by a tenth):
// rays are cut to it and bricks outside it are never loaded (Raycaster::setClip). Until a range is
// dragged the box has no limits (the sliders show the data's extent), so that an unclipped view is
// the unclipped image, bit for bit.
void ViewerSession::drawClipSection() {
  if (!ImGui::CollapsingHeader("Clipping box")) return;
  const glm::dvec3 pad = 0.1 * (dataHi_ - dataLo_) + 1e-6;
  const char* const axes[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    const float lo = float(dataLo_[a] - pad[a]), hi = float(dataHi_[a] + pad[a]);
    float range[2] = {float(std::clamp(settings_.clipLo[a], double(lo), double(hi))),
                      float(std::clamp(settings_.clipHi[a], double(lo), double(hi)))};
    if (ImGui::DragFloatRange2(axes[a], &range[0], &range[1], (hi - lo) / 400.0f, lo, hi, "%.4g", "%.4g",
                               ImGuiSliderFlags_AlwaysClamp)) {
      settings_.clipLo[a] = range[0];
      settings_.clipHi[a] = range[1];
    }
  }
  if (ImGui::Button("no clipping")) {
    settings_.clipLo = glm::dvec3(-1e30);
    settings_.clipHi = glm::dvec3(1e30);
  }
}

void ViewerSession::drawCursorSection() {
  if (!ImGui::CollapsingHeader("Under the cursor", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (!cursor_.hit) {
    // As many lines as a hit shows: the sections below do not jump as the mouse crosses a silhouette.
    row("world", "no surface under the cursor");
    for (const char* label : {"lattice xyz", "nearest site", "value"}) row(label, "-");
    return;
  }
  char text[96];
  std::snprintf(text, sizeof text, "%.5g, %.5g, %.5g", cursor_.pWorld.x, cursor_.pWorld.y, cursor_.pWorld.z);
  row("world", text);
  std::snprintf(text, sizeof text, "%.5g, %.5g, %.5g", cursor_.xyz.x, cursor_.xyz.y, cursor_.xyz.z);
  row("lattice xyz", text);
  if (!cursor_.values) {  // a Cartesian source: no spline to evaluate on the CPU here
    for (const char* label : {"nearest site", "value"}) row(label, "-");
    return;
  }
  // The nearest FCC site and the spline's value there: the data's sample for a prefiltered file.
  std::snprintf(text, sizeof text, "%d, %d, %d: %.5g", cursor_.ijk.x, cursor_.ijk.y, cursor_.ijk.z,
                double(cursor_.valueAtSite));
  row("nearest site", text);
  // DVR's depth is where the ray's opacity reaches 0.5.
  std::snprintf(text, sizeof text, dvr() ? "%.5g (at 50%% opacity)" : "%.5g (the surface's)", double(cursor_.valueAtPoint));
  row("value", text);
}

void ViewerSession::drawHelp() {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
  ImGui::Begin("Help", &settings_.showHelp,
               ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings);
  // The keys that apply to the mode: DVR has no isovalue (ViewerSession::handleInput ignores its keys).
  struct Row {
    const char* keys;
    const char* what;
    bool isoOnly = false;
    bool dvrOnly = false;
  };
  static const Row kRows[] = {
      {"left drag", "orbit about the look-at point"},
      {"ctrl + left drag", "roll"},
      {"middle drag, shift + left drag", "pan"},
      {"wheel", "zoom"},
      {"R", "reset the camera (frame the data)"},
      {"C", "save the camera as JSON (for --camera) and copy it"},
      {"+, - (or keypad)", "isovalue (of the surface selected in the panel) up or down by 1% of its range", true},
      {"Page Up, Page Down", "isovalue up or down by 10%", true},
      {"ctrl + Z; ctrl + Y, ctrl + shift + Z", "undo; redo an edit of the transfer function", false, true},
      {"S, F12", "screenshot: PNG of the window and EXR of the image, in the current directory"},
      {"O, or drop a file", "open another file (any input `fccvdb view` takes)"},
      {"P", "show or hide the panel"},
      {"H, F1", "show or hide this help"},
      {"ctrl + click a slider", "type an exact value (Enter applies it, Esc cancels)"},
      {"Esc", "quit"},
  };
  // The descriptions start right of the widest key, at any font size.
  float keysWidth = 0.0f;
  for (const Row& r : kRows) keysWidth = std::max(keysWidth, ImGui::CalcTextSize(r.keys).x);
  const float column = ImGui::GetStyle().WindowPadding.x + keysWidth + ImGui::GetFontSize();
  layout_.helpKeysRight = 0.0f;
  layout_.helpTextLeft = FLT_MAX;
  layout_.helpKeys.clear();
  for (const Row& r : kRows) {
    if ((r.isoOnly && dvr()) || (r.dvrOnly && !dvr())) continue;
    ImGui::TextUnformatted(r.keys);
    layout_.helpKeys.push_back(r.keys);
    layout_.helpKeysRight = std::max(layout_.helpKeysRight, ImGui::GetItemRectMax().x);
    ImGui::SameLine(column);
    ImGui::TextUnformatted(r.what);
    layout_.helpTextLeft = std::min(layout_.helpTextLeft, ImGui::GetItemRectMin().x);
  }
  ImGui::End();
}

}  // namespace fcc::render
