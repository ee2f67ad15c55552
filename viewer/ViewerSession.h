// One dataset open in the interactive viewer: the camera and the panel's settings, the progressive
// raycaster, and what is drawn each frame. Window-system free: the window (viewer/ViewerWindow.h)
// or an offscreen target (`fccvdb bench view`) calls frame() after ImGui::NewFrame(), with the
// target framebuffer bound; frame() renders ImGui's frame (ImGui::Render(), the OpenGL 3 backend).
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "Camera.h"
#include "CameraPath.h"
#include "CursorProbe.h"
#include "DatasetSummary.h"
#include "DvrTransfer.h"
#include "Presenter.h"
#include "Raycaster.h"
#include "RedrawTracker.h"
#include "TransferFunctionEditor.h"
#include "UploadBudget.h"

namespace fcc::render {

// What the panel edits.
struct ViewerSettings {
  float iso = 0.0f;                             // the first surface's
  glm::vec3 lightInCamera = kDefaultLightInCamera;  // as RenderOptions
  glm::vec3 surfaceColor{0.85f, 0.72f, 0.52f};  // linear; the first surface's
  float surfaceOpacity = 1.0f;                  // the first surface's
  // Surfaces 2 to kMaxIsosurfaces (the panel's Surfaces section adds and removes them), and the one the
  // isovalue keys and a click on the histogram move (0: the first).
  std::vector<Isosurface> moreSurfaces;
  int selectedSurface = 0;
  glm::vec3 background{0.08f, 0.09f, 0.11f};    // linear, as `fccvdb render`'s PNG
  bool skipEmpty = true;
  bool finiteDifferenceNormals = false;
  // Direct volume rendering (RenderMode::Dvr): the transfer function by name (a preset, or what --tf
  // named, a file) and the density scale; the GPU's table is rebuilt when either changes.
  std::string transferFunction;
  float densityScale = 1.0f;
  // The unit distance (world units; the panel's slider spans a hundredth to a hundred times the one
  // the session started with), the opacity at which a ray stops (RenderOptions' terminationOpacity),
  // and gradient shading, its highlight and its light (RenderOptions::dvrShading; turning it on or off
  // builds the raycasting program again, the rest are uniforms).
  float unitDistance = 1.0f;
  float stopOpacity = 0.995f;
  DvrShading dvrShading;
  // The clipping box, world space (RenderOptions::clipLo/clipHi); the panel's sliders span the data.
  glm::dvec3 clipLo{-1e30}, clipHi{1e30};
  // The reconstruction the source is rendered with (its name; the panel's combo for a Cartesian grid).
  // Another name asks for the data again with it (ViewerSession::takeOpenRequest), keeping the view.
  std::string reconstruction;
  bool showPanel = true;
  bool showHelp = false;
};

// Where the last frame put some of the panel's and help window's items, in window units (tests
// check the layout with it: a click on the histogram, the swatch's colour, labels that must not overlap).
struct ImRectF {
  float x0 = 0.0f, y0 = 0.0f, x1 = 0.0f, y1 = 0.0f;
  bool empty() const { return !(x1 > x0 && y1 > y0); }
  float centreX() const { return 0.5f * (x0 + x1); }
  float centreY() const { return 0.5f * (y0 + y1); }
};
struct PanelLayout {
  ImRectF isoLabel, isoSlider, histogram, backgroundSwatch;
  ImRectF transferCombo, densitySlider;  // DVR mode's (empty in isosurface mode, as the iso ones in DVR)
  ImRectF unitDistanceSlider, stopOpacitySlider, shadingCheckbox;  // DVR mode's too
  ImRectF specularSlider, specularPowerSlider;  // DVR with gradient shading on
  std::array<ImRectF, 3> lightButtons;          // and its light's: headlight, directional, kit (DvrLight)
  ImRectF lightAzimuthSlider, lightElevationSlider;  // the isosurface's light, or DVR's without headlight
  // DVR's editor (viewer/PanelTransfer.cpp): the colour-map combo, the file field and its buttons, and
  // a small square around each opacity point drawn over the histogram (the editor's order).
  ImRectF colorMapCombo, transferPathField, transferLoad, transferSave, transferUndo, transferRedo;
  std::vector<ImRectF> opacityPoints;
  // The sliders of the segment from the last grabbed point to the next (ParaView's midpoint and
  // sharpness; empty while no point is chosen or it is the last).
  ImRectF segmentMidpointSlider, segmentSharpnessSlider;
  // The colour bar under the histogram, a square around each colour point's marker on it (the
  // editor's order), and the chosen point's colour field and remove button (empty while none is).
  ImRectF colorBar;
  std::vector<ImRectF> colorPoints;
  ImRectF colorPointEdit, colorPointRemove;
  ImRectF addSurface, removeLastSurface;  // the Surfaces section's buttons (empty when not shown)
  // The Renderer section's reconstruction combo while closed (empty for FCC data: no choice), and its
  // items (name, where) while open.
  ImRectF reconstructionCombo;
  std::vector<std::pair<std::string, ImRectF>> reconstructionItems;
  std::string histogramTooltip;  // the last one shown
  // The help window's rows: the rightmost end of a key's text and the leftmost start of a description;
  // the keys it lists (those that apply to the mode).
  float helpKeysRight = 0.0f, helpTextLeft = 0.0f;
  std::vector<std::string> helpKeys;
  // The panel's last line (the help hint) where it is drawn now, and how far the panel can scroll
  // (0 when everything fits): every section is reachable when scrolling brings that line into view.
  ImRectF panelEnd;
  float panelScrollMax = 0.0f;
};

// Live figures for the statistics section, updated every frame.
struct ViewerStats {
  double frameMs = 0.0;          // wall time per frame, averaged over the last half second
  double fps = 0.0;
  uint32_t resident = 0;         // bricks in the GPU pool
  std::size_t needed = 0;        // bricks whose bounds hold the isovalue
  std::size_t missing = 0;       // needed, not resident
  uint32_t requested = 0;        // bricks the last pass's rays asked for
  std::size_t streaming = 0;     // queued or decoding on the loader thread
  bool complete = false;         // the image is final for this view
  double uploadMiBPerSecond = 0.0;
  double passGpuMs = 0.0;        // the last raycasting pass on the GPU (RenderOptions::timeGpu; else 0)
  // Pixels the last frame drew of the image beside the panel, as a fraction of them: below 1 where
  // the back buffer's age is known (RedrawTracker.h); and its average over the frame-time window
  // (what the panel shows: a figure changing every frame would make the panel change every frame).
  double imageDrawn = 0.0, imageDrawnAverage = 0.0;
  bool uiDrawn = false;          // ImGui drew the last frame (else the back buffer already showed it)
  // Level of detail (a file with a pyramid, not --full-resolution): the levels the view draws from,
  // refreshed with the rates and when a frame completes (it reads the GPU's slot use back).
  LevelMix levels;
};

// What a session asks whoever opens datasets for (viewer/OpenAnotherFile.h): another file, dropped on
// the window or typed after O; or, with `path` empty, its own data again with another reconstruction
// (the panel's choice), the view kept (ViewerSession::view).
struct OpenRequest {
  std::string path;
  std::string reconstruction;
  bool operator==(const OpenRequest& o) const { return path == o.path && reconstruction == o.reconstruction; }
};

// What a session hands on to the one that replaces it over the same data (another reconstruction):
// the camera (and the one R goes back to), the panel's settings — surfaces, colours, light, clipping
// box, transfer function — the transfer function in use with what the panel loaded, the editor (its
// starting point and undo history), and where its keys write files and record the camera.
struct SessionView {
  Camera camera, initialCamera;
  ViewerSettings settings;
  std::optional<DvrTransfer> dvr;
  std::optional<TransferFunctionEditor> editor;
  uint64_t appliedRevision = 0;  // the editor's revision `dvr` holds
  std::vector<std::pair<std::string, TransferFunction>> loadedFunctions;
  CameraPathRecorder* pathRecorder = nullptr;
  std::string outputDirectory;
};

class ViewerSession {
 public:
  // Needs a current OpenGL 4.5 context and an ImGui context with its OpenGL backend.
  // An FCC store, through a host cache of options.hostCacheBytes; isosurface mode.
  ViewerSession(const io::BrickStore& store, const RenderOptions& options, const Camera& initialCamera,
                DatasetSummary summary);
  // Any brick source (viewer/BrickSource.h: an FCC store's, or a Cartesian grid rendered as it is; the
  // panel reports the damage it met); `store`, the FCC store behind it or null, gives the spline's
  // values under the cursor. With `dvr`, direct volume rendering with that transfer function (options' mode and
  // table are set from it); else options.mode must be Iso.
  ViewerSession(const BrickSource& source, const io::BrickStore* store, const RenderOptions& options,
                const Camera& initialCamera, DatasetSummary summary, std::optional<DvrTransfer> dvr = std::nullopt);

  // One frame into the bound framebuffer of fbWidth x fbHeight pixels; the window is windowHeight
  // high in ImGui's coordinates (they differ on high-DPI screens). Reads this frame's mouse
  // and keys from ImGui (where the panel does not take them), builds the panel, steps the
  // raycaster within the upload budget, draws its image (only what changed since the frame
  // `bufferAge` frames ago, which the framebuffer still holds: 1 the previous frame, 0 unknown, so
  // everything; see RedrawTracker.h) and then ImGui's windows over it.
  void frame(int fbWidth, int fbHeight, int windowHeight, int bufferAge = 0);

  // True once the frame is complete and no brick is streaming.
  bool settled() const { return stats_.complete && stats_.streaming == 0; }
  // True when the frame just drawn is the settled image and shows no "streaming" line: what an
  // automated screenshot captures. One frame later than settled(): the line a frame draws tells the
  // figures of the frame before (the panel is built while the pass runs), so the first settled frame
  // still shows "streaming N bricks".
  bool shownSettled() const { return shownSettled_; }
  // The status line the last frame drew over the image ("streaming ...", "refining ..."); empty when none.
  const std::string& shownStatusLine() const { return shownStatusLine_; }
  // Writes the frame just drawn into the bound framebuffer (.png: image and panel, as shown) and/or
  // a complete frame of the current view (.exr: channels as `fccvdb render`, panel columns
  // included; waits for bricks still streaming); an empty path is skipped. Reports each file and
  // shows a notice naming them. The screenshot key (S, F12) calls it at the end of its frame with a
  // new timestamped name in the output directory.
  void writeScreenshots(const std::string& pngPath, const std::string& exrPath);
  void writeExr(const std::string& path);

  // Where the keys write their files (screenshots, cameras): empty, the current directory.
  void setOutputDirectory(const std::string& directory) { outputDirectory_ = directory; }
  // Gets one line for each file a key wrote (the window prints it); also shown on screen (notice()).
  void setReport(std::function<void(const std::string&)> report) { report_ = std::move(report); }
  // A line shown over the top of the image for kNoticeSeconds ("camera saved to ...").
  void notify(const std::string& text);
  // The notice shown now; empty when none.
  const std::string& notice() const { return notice_; }
  static constexpr double kNoticeSeconds = 4.0;

  // The C key: writes the camera (viewer/CameraFile.h) to a new timestamped .json in the output
  // directory, copies its JSON to the clipboard, and says so. Returns the file's path.
  std::string saveCamera();

  // DVR's transfer-function editor (docs/VIEWER.md): the function as edited (null outside DVR mode).
  const TransferFunctionEditor* transferEditor() const { return editor_ ? &*editor_ : nullptr; }
  // The panel's Save: the function in use as ParaView colour-map JSON in a new timestamped
  // fccvdb-tf-*.json in the output directory (atomically; `--tf` and ParaView read it); says so and
  // returns its path. OutputError when it cannot be written.
  std::string saveTransferFunction();
  // The panel's Load: what `--tf SPEC` would give (a preset, a file, FILE.json:NAME) becomes the
  // function in use from the next frame on, and a ParaView file's maps join the colour-map choice.
  // InputError / ValueError (one line) for a bad SPEC; nothing changes then.
  void loadTransferFunction(const std::string& spec);

  // What is under the mouse, as of the last frame: the surface point (world, lattice index space),
  // the nearest FCC site and the spline's values; hit false over the background, the panel or
  // outside the window. Read back from the raycaster's depth only when the pixel or the image changed.
  const CursorProbe& cursor() const { return cursor_; }
  // The isovalue keys' steps, as fractions of the surface range: + / - and Page Up / Page Down.
  static constexpr float kIsoKeyStep = 0.01f, kIsoPageStep = 0.1f;

  // Another file to open in this window: from a file dropped on it (requestOpen) or typed after O; or
  // this data with another reconstruction (the panel's choice, settings().reconstruction). The window
  // hands it to whoever opens datasets (`fccvdb view`), which replaces this session.
  void requestOpen(const std::string& path) { openRequest_ = OpenRequest{path, {}}; }
  std::optional<OpenRequest> takeOpenRequest() { return std::exchange(openRequest_, std::nullopt); }
  bool openFieldShown() const { return openField_.shown; }
  // The view to carry over to a session of the same data (another reconstruction), and taking it on:
  // the settings apply at once (the first frame is of the view kept), the transfer function in use
  // replaces the one this session was made with.
  SessionView view() const;
  void restoreView(const SessionView& view);
  // Taking on the undo history of another file's transfer-function editor (transferEditor): this
  // session's function stays in use, and ctrl + Z brings back the other file's
  // (TransferFunctionEditor::continueHistory). Nothing outside DVR.
  void continueTransferHistory(const TransferFunctionEditor& previous);

  const Camera& camera() const { return camera_; }
  void setCamera(const Camera& camera) { camera_ = camera; }
  // `view --record-path`: every frame from now on records the camera it renders into `recorder`
  // (null: stop). The recorder outlives the session or is replaced first.
  void recordPath(CameraPathRecorder* recorder) { pathRecorder_ = recorder; }
  const ViewerSettings& settings() const { return settings_; }
  ViewerSettings& settings() { return settings_; }
  const ViewerStats& stats() const { return stats_; }
  bool dvr() const { return raycaster_.options().mode == RenderMode::Dvr; }
  const RenderOptions& renderOptions() const { return raycaster_.options(); }  // as the renderer has them now
  // The transfer function in use (DVR mode; null otherwise): as of the last frame's settings.
  const DvrTransfer* transfer() const { return dvr_ ? &*dvr_ : nullptr; }
  const BrickSource& source() const { return raycaster_.source(); }
  const DatasetSummary& summary() const { return summary_; }
  const PanelLayout& panelLayout() const { return layout_; }
  // The panel's width in window coordinates (0 while hidden), where the image is covered.
  float panelWidth() const { return settings_.showPanel ? panelWidth_ : 0.0f; }
  // The upload time budget per frame (seconds), so a frame's uploads do not stall the UI.
  // At most: less when the last frame's other work leaves less of the frame budget (viewer/UploadBudget.h).
  static constexpr double kUploadSecondsPerFrame = 0.004;
  // The display's frame time (ViewerWindow sets it from the monitor's refresh rate; 60 Hz until then).
  void setFrameBudgetSeconds(double seconds) {
    if (seconds > 0.0 && std::isfinite(seconds)) frameBudgetSeconds_ = seconds;
  }
  static constexpr float kPanelWidth = 330.0f;  // window units, before the font scale

 private:
  void init(const RenderOptions& options);
  void handleInput(int windowHeight);
  bool applySettings();  // true when a setting changed the image (it restarts the frame)
  void applyTransfer();  // DVR: a new table when the transfer function or density scale changed
  void useTransfer(DvrTransfer next);  // applyTransfer's: `next` in use (its table on the GPU), or a throw
  void drawTransferSection();  // viewer/ViewerPanel.cpp
  void drawReconstructionChoice();  // viewer/ViewerPanel.cpp
  void drawLightSliders();  // viewer/ViewerPanel.cpp: lightInCamera as azimuth and elevation
  void drawSurfacesSection();  // viewer/PanelSurfaces.cpp
  std::vector<Isosurface> surfacesOfSettings() const;  // settings_'s surfaces, the first from iso/surfaceColor
  float& selectedIso();        // the isovalue the keys and the histogram move
  void drawOpacityCurve(float x0, float x1, float yLo, float yHi);  // viewer/PanelHistogram.cpp
  // viewer/PanelTransfer.cpp: the opacity points over the histogram (mouse and Delete), and the
  // colour-map combo, file field, Load and Save below it.
  void editOpacityPoints(float x0, float x1, float yLo, float yHi, float axisMin, float axisMax, bool hovered,
                         bool active);
  void drawTransferFiles();
  void drawSegmentShape();
  void undoTransferEdit(bool redo);  // viewer/PanelTransfer.cpp: the editor's undo or redo, with a notice
  // viewer/PanelColorPoints.cpp: the colour bar under the histogram (the function's colours on its
  // value axis, a marker at each colour point; click, drag, right-click) and the chosen point's colour.
  void editColorPoints(float x0, float x1, float axisMin, float axisMax);
  void drawColorPointEdit();
  TransferFunction baseFunction(const std::string& name) const;  // a preset, --tf's or a loaded one, fitted
  void addColorMapsOf(const std::string& spec);  // a ParaView file's maps, for the colour-map combo
  void updateCursor(int fbWidth, int fbHeight, int windowHeight);
  void drawCursorSection();
  void updateStats(const StepStats& step, double imageDrawn, bool uiDrawn);
  void drawPanel(int windowHeight);  // viewer/ViewerPanel.cpp
  void drawHelp();
  void drawCameraSection();
  void drawClipSection();
  void drawHistogram();  // viewer/PanelHistogram.cpp
  void drawAxisIndicator(int windowHeight);
  void drawNotice();
  void drawOpenField();  // viewer/ViewerOverlays.cpp
  std::string statusLine() const;  // of the last frame's figures; empty once settled
  void drawStreamingLine(int windowHeight);

  const io::BrickStore* store_;  // for the cursor's spline values; may be null
  Raycaster raycaster_;
  std::optional<DvrTransfer> dvr_, initialDvr_;  // in use; what the session opened with (--tf)
  float appliedDensityScale_ = 1.0f;
  float appliedUnitDistance_ = 1.0f;
  float initialUnitDistance_ = 1.0f;  // the unit distance slider's centre
  // The editor over dvr_'s function, the revision the table was last built from, the point a drag
  // holds (-1: none), functions loaded from the panel (spec, fitted function) and the colour maps
  // offered (name, colours in data values: the presets fitted to the source, then files' maps).
  std::optional<TransferFunctionEditor> editor_;
  uint64_t appliedRevision_ = 0;  // the editor's revision dvr_ holds
  int dragPoint_ = -1;
  int shapePoint_ = -1;  // the point whose segment's shape the panel's sliders edit (-1: none)
  int dragColor_ = -1;      // the colour point a drag on the colour bar holds (-1: none)
  int selectedColor_ = -1;  // the colour point whose colour the panel's picker edits (-1: none)
  bool reloadBase_ = false;
  std::vector<std::pair<std::string, TransferFunction>> loadedFunctions_;
  std::vector<std::pair<std::string, std::vector<ColorPoint>>> colorMaps_;
  char transferPath_[1024] = {};
  Presenter presenter_;
  RedrawTracker redraw_;
  Camera camera_, initialCamera_;
  ViewerSettings settings_;
  ViewerStats stats_;
  DatasetSummary summary_;
  PanelLayout layout_;
  std::optional<SplineProbe> splineProbe_;  // with a store
  glm::dmat4 indexFromWorld_{1.0};
  glm::dvec3 dataLo_{0.0}, dataHi_{0.0};  // the data's world box, once (the clip sliders span it)
  CursorProbe cursor_;
  glm::ivec2 cursorPixel_{-1, -1};  // the framebuffer pixel cursor_ was read at
  double panDepth_ = 0.0;           // along the view, of the point a pan grabbed (0: the look-at point's)
  float panelWidth_ = 0.0f;
  int fbWidth_ = 0, fbHeight_ = 0, windowHeight_ = 0;  // of the last frame
  bool screenshotRequested_ = false;
  CameraPathRecorder* pathRecorder_ = nullptr;
  std::optional<OpenRequest> openRequest_;
  struct OpenField {
    bool shown = false, focus = false;
    char path[1024] = {};
  } openField_;
  std::string outputDirectory_;
  std::function<void(const std::string&)> report_;
  std::string notice_;
  std::chrono::steady_clock::time_point noticeUntil_;
  double lastFrameRest_ = -1.0;  // the last frame()'s time besides its uploads, seconds (< 0: none yet)
  double frameBudgetSeconds_ = frameBudgetForRefresh(0);
  std::string shownStatusLine_;
  bool shownSettled_ = false;
  std::chrono::steady_clock::time_point rateWindowStart_;
  int framesInWindow_ = 0;
  double imageDrawnInWindow_ = 0.0;
  uint64_t uploadedAtWindowStart_ = 0;
  bool firstFrame_ = true;
};

}  // namespace fcc::render
