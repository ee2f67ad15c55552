#include "ViewerSession.h"

#define GLFW_INCLUDE_NONE  // key codes only; GL comes from libepoxy
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string_view>

#include "CameraFile.h"
#include "ImGuiDrawData.h"
#include "OrbitControls.h"
#include "UploadBudget.h"
#include "OutputNames.h"
#include "GlProgram.h"
#include "io/ImageOutput.h"
#include "sparse/Error.h"

namespace fcc::render {
namespace {
constexpr double kRateWindowSeconds = 0.5;

// The options a session's raycaster gets: DVR's mode and table from `dvr`.
RenderOptions optionsWith(const RenderOptions& options, const std::optional<DvrTransfer>& dvr) {
  RenderOptions o = options;
  if (dvr) {
    o.mode = RenderMode::Dvr;
    o.transfer = dvr->table();
  } else if (o.mode == RenderMode::Dvr) {
    throw ValueError("a viewer session in DVR mode needs its transfer function");
  }
  return o;
}

}  // namespace

ViewerSession::ViewerSession(const io::BrickStore& store, const RenderOptions& options, const Camera& initialCamera,
                             DatasetSummary summary)
    : store_(&store),
      raycaster_(store, optionsWith(options, std::nullopt)),
      camera_(initialCamera),
      initialCamera_(initialCamera),
      summary_(std::move(summary)) {
  init(options);
}

ViewerSession::ViewerSession(const BrickSource& source, const io::BrickStore* store, const RenderOptions& options,
                             const Camera& initialCamera, DatasetSummary summary, std::optional<DvrTransfer> dvr)
    : store_(store),
      raycaster_(source, optionsWith(options, dvr)),
      dvr_(dvr),
      initialDvr_(std::move(dvr)),
      camera_(initialCamera),
      initialCamera_(initialCamera),
      summary_(std::move(summary)) {
  init(options);
}

void ViewerSession::init(const RenderOptions& options) {
  if (store_) splineProbe_.emplace(*store_);
  indexFromWorld_ = glm::inverse(raycaster_.source().worldFromIndex());
  raycaster_.source().worldBounds(dataLo_, dataHi_);  // a walk of the topology: not once a frame
  settings_.iso = raycaster_.iso();
  settings_.lightInCamera = options.lightInCamera;
  settings_.surfaceColor = options.surfaceColor;
  settings_.surfaceOpacity = options.surfaceOpacity;
  settings_.moreSurfaces = options.moreSurfaces;
  settings_.skipEmpty = options.skipEmpty;
  settings_.finiteDifferenceNormals = options.finiteDifferenceNormals;
  settings_.clipLo = options.clipLo;  // +-1e30 (the default): no box
  settings_.clipHi = options.clipHi;
  settings_.reconstruction = std::string(raycaster_.source().reconstruction().name);
  settings_.stopOpacity = options.terminationOpacity;
  settings_.dvrShading = options.dvrShading;
  if (dvr_) {
    settings_.transferFunction = dvr_->spec;
    settings_.densityScale = appliedDensityScale_ = float(dvr_->scale.densityScale);
    settings_.unitDistance = appliedUnitDistance_ = initialUnitDistance_ = float(dvr_->scale.unitDistance);
    // Points may go anywhere on the histogram's axis (the samples' range), or the source's values
    // without one; the editor widens that to the function's own points.
    const bool axis = !summary_.histogram.empty() && summary_.histogramMax > summary_.histogramMin;
    editor_.emplace(dvr_->function, axis ? summary_.histogramMin : source().valueMin(),
                    axis ? summary_.histogramMax : source().valueMax(), dvr_->spec);
    appliedRevision_ = editor_->revision();
    for (const std::string& preset : transferFunctionPresetNames())
      colorMaps_.emplace_back(preset, fitTransferFunction(transferFunctionPreset(preset), source()).colors());
    try {
      addColorMapsOf(dvr_->spec);
    } catch (const Error&) {  // read once already (--tf); a file changed since then offers no maps
    }
  }
}

SessionView ViewerSession::view() const {
  return SessionView{camera_, initialCamera_, settings_, dvr_, editor_, appliedRevision_, loadedFunctions_, pathRecorder_, outputDirectory_};
}

void ViewerSession::continueTransferHistory(const TransferFunctionEditor& previous) {
  if (editor_) editor_->continueHistory(previous);
}

void ViewerSession::restoreView(const SessionView& view) {
  camera_ = view.camera;
  initialCamera_ = view.initialCamera;
  settings_ = view.settings;
  settings_.reconstruction = std::string(source().reconstruction().name);  // this session's: asking again would loop
  pathRecorder_ = view.pathRecorder;
  outputDirectory_ = view.outputDirectory;
  if (dvr_ && view.dvr) {
    // The function in use, edits included, in data values: the same look whatever range the new
    // reconstruction takes (fitting the preset again to it would move the colours).
    dvr_ = view.dvr;
    settings_.transferFunction = dvr_->spec;
    settings_.densityScale = appliedDensityScale_ = float(dvr_->scale.densityScale);
    settings_.unitDistance = appliedUnitDistance_ = float(dvr_->scale.unitDistance);
    raycaster_.setTransfer(dvr_->table());
    if (view.editor) {
      // Its points, starting point and history as they were (an undo may go back across the switch),
      // on this reconstruction's histogram axis too. Edits the old session had not applied yet are
      // applied by applySettings below.
      TransferFunctionEditor kept = *view.editor;
      kept.widen(editor_->lo(), editor_->hi());
      editor_ = std::move(kept);
      appliedRevision_ = view.appliedRevision;  // the kept editor's own count
    } else {
      editor_->reset(dvr_->function, dvr_->spec);
      appliedRevision_ = editor_->revision();
    }
    loadedFunctions_ = view.loadedFunctions;
    for (const auto& loaded : loadedFunctions_) {
      try {
        addColorMapsOf(loaded.first);
      } catch (const Error&) {  // read once already; a file changed since then offers no maps
      }
    }
  }
  applySettings();  // surfaces, light, skipping, normals, clipping box: before the first frame
}

void ViewerSession::notify(const std::string& text) {
  notice_ = text;
  noticeUntil_ = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                        std::chrono::duration<double>(kNoticeSeconds));
}

std::string ViewerSession::saveCamera() {
  const std::string path = uniqueTimestampedStem(outputDirectory_, "fccvdb-camera", {".json"}) + ".json";
  writeCameraFile(path, camera_);
  // The clipboard gets the same JSON (GLFW's clipboard in the window; ImGui's own without one).
  ImGui::SetClipboardText(cameraJson(camera_).c_str());
  const std::string line = "camera saved to " + path + " and copied (use it with --camera)";
  if (report_) report_(line);
  notify(line);
  return path;
}

void ViewerSession::writeScreenshots(const std::string& pngPath, const std::string& exrPath) {
  std::string written;
  if (!pngPath.empty()) {
    // The bound framebuffer as this frame drew it (image and panel), rows flipped to put row 0 at the top.
    const int w = fbWidth_, h = fbHeight_;
    std::vector<unsigned char> bottomUp(std::size_t(w) * h * 3), rgb(bottomUp.size());
    // Read what this frame drew into: the window's back buffer, or an offscreen target.
    GLint drawFramebuffer = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(drawFramebuffer));
    if (drawFramebuffer == 0) glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, bottomUp.data());
    checkGl("reading the frame for a screenshot");
    for (int y = 0; y < h; ++y)
      std::copy_n(bottomUp.data() + std::size_t(h - 1 - y) * w * 3, std::size_t(w) * 3, rgb.data() + std::size_t(y) * w * 3);
    io::writeScreenPng(pngPath, w, h, rgb);
    const long panelPixels = windowHeight_ > 0 ? std::lround(panelWidth() * float(h) / float(windowHeight_)) : 0;
    if (report_)
      report_("wrote " + pngPath + " (" + std::to_string(w) + "x" + std::to_string(h) + " window, panel " +
              std::to_string(panelPixels) + " px wide)");
    written = pngPath;
  }
  if (!exrPath.empty()) {
    writeExr(exrPath);
    if (report_) report_("wrote " + exrPath + (dvr() ? " (R,G,B,A,Z)" : " (R,G,B,A,Z,N.X,N.Y,N.Z)"));
    written += (written.empty() ? "" : " and ") + exrPath;
  }
  if (!written.empty()) notify("screenshot written: " + written);
}

void ViewerSession::writeExr(const std::string& path) {
  // A complete frame of the whole view: the progressive one leaves the columns under the panel empty.
  const GlTexture2D& shown = raycaster_.colorTexture();
  raycaster_.render(camera_, shown.width(), shown.height());
  const FrameImages images = raycaster_.readImages();
  const io::RenderedImage image{images.width, images.height, &images.rgba, &images.normalDepth, /*normals=*/!dvr()};
  io::writeRenderedImage(path, image, settings_.background);
}

void ViewerSession::handleInput(int windowHeight) {
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureMouse) {
    const double dx = io.MouseDelta.x, dy = io.MouseDelta.y;
    const bool moved = (dx != 0.0 || dy != 0.0) && io.MousePos.x > -1e30f;
    const bool panning = io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift);
    const bool rolling = io.MouseDown[0] && io.KeyCtrl && !io.KeyShift;
    if (io.MouseClicked[2] || (io.MouseClicked[0] && io.KeyShift)) {
      // The pan holds the surface point under the cursor (else the look-at plane) under the cursor.
      const glm::dvec3 forward = glm::normalize(camera_.lookat - camera_.eye);
      panDepth_ = cursor_.hit ? glm::dot(cursor_.pWorld - camera_.eye, forward) : 0.0;
    }
    if (moved && panning) camera_ = pan(camera_, dx, dy, windowHeight, panDepth_);
    else if (moved && rolling) camera_ = roll(camera_, dx * kOrbitDegreesPerPixel);
    else if (moved && io.MouseDown[0]) camera_ = orbit(camera_, dx, dy);
    if (io.MouseWheel != 0.0f) camera_ = zoom(camera_, io.MouseWheel);
  }
  // A drag or a slider let go: the editor's next edit is a new undo step.
  if (editor_ && !io.MouseDown[0] && !ImGui::IsAnyItemActive()) editor_->closeStep();
  // Keys reach the viewer while the panel has focus (a slider held, a colour picked), but not while
  // a text field takes them (ctrl + click on a slider types its value: an "s" there is a letter).
  if (!io.WantTextInput) {
    if (ImGui::IsKeyPressed(GLFW_KEY_R, false)) camera_ = initialCamera_;
    if (ImGui::IsKeyPressed(GLFW_KEY_H, false) || ImGui::IsKeyPressed(GLFW_KEY_F1, false))
      settings_.showHelp = !settings_.showHelp;
    if (ImGui::IsKeyPressed(GLFW_KEY_P, false)) settings_.showPanel = !settings_.showPanel;
    if (ImGui::IsKeyPressed(GLFW_KEY_S, false) || ImGui::IsKeyPressed(GLFW_KEY_F12, false))
      screenshotRequested_ = true;
    // The isovalue by keyboard, within the surface range; held keys repeat.
    const float range = summary_.valueMax - summary_.valueMin;
    float isoSteps = 0.0f;
    if (ImGui::IsKeyPressed(GLFW_KEY_EQUAL, true) || ImGui::IsKeyPressed(GLFW_KEY_KP_ADD, true)) isoSteps += kIsoKeyStep;
    if (ImGui::IsKeyPressed(GLFW_KEY_MINUS, true) || ImGui::IsKeyPressed(GLFW_KEY_KP_SUBTRACT, true)) isoSteps -= kIsoKeyStep;
    if (ImGui::IsKeyPressed(GLFW_KEY_PAGE_UP, true)) isoSteps += kIsoPageStep;
    if (ImGui::IsKeyPressed(GLFW_KEY_PAGE_DOWN, true)) isoSteps -= kIsoPageStep;
    if (isoSteps != 0.0f && !dvr()) {
      float& iso = selectedIso();  // the surface selected in the panel
      iso = std::clamp(iso + isoSteps * range, summary_.valueMin, summary_.valueMax);
    }
    // DVR: the transfer function's edits undone and redone (ctrl + Z; ctrl + shift + Z or ctrl + Y).
    if (editor_ && io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Z, false)) undoTransferEdit(/*redo=*/io.KeyShift);
    if (editor_ && io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Y, false)) undoTransferEdit(/*redo=*/true);
    if (ImGui::IsKeyPressed(GLFW_KEY_O, false)) {
      openField_.shown = true;
      openField_.focus = true;
    }
    if (ImGui::IsKeyPressed(GLFW_KEY_C, false)) {
      try {
        saveCamera();
      } catch (const std::exception& e) {
        notify(e.what());  // an unwritable directory must not end the session
      }
    }
  }
}

void ViewerSession::updateCursor(int fbWidth, int fbHeight, int windowHeight) {
  const ImGuiIO& io = ImGui::GetIO();
  const float pixelsPerUnit = windowHeight > 0 ? float(fbHeight) / float(windowHeight) : 1.0f;
  const bool overImage = io.MousePos.x > -1e30f && !io.WantCaptureMouse && io.MousePos.x >= panelWidth() &&
                         io.MousePos.y >= 0.0f;
  const glm::ivec2 pixel(int(std::floor(io.MousePos.x * pixelsPerUnit)), int(std::floor(io.MousePos.y * pixelsPerUnit)));
  const GlTexture2D& normalDepth = raycaster_.normalDepthTexture();
  if (!overImage || pixel.x >= std::min(fbWidth, normalDepth.width()) || pixel.y >= std::min(fbHeight, normalDepth.height())) {
    cursor_ = CursorProbe{};
    cursorPixel_ = glm::ivec2(-1);
    return;
  }
  // A settled image under a still cursor reads nothing: no GPU sync while idle.
  if (pixel == cursorPixel_ && stats_.complete && shownSettled_) return;
  cursorPixel_ = pixel;
  float normalDepthTexel[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glGetTextureSubImage(normalDepth.id(), 0, pixel.x, pixel.y, 0, 1, 1, 1, GL_RGBA, GL_FLOAT, sizeof normalDepthTexel,
                       normalDepthTexel);
  checkGl("reading the depth under the cursor");
  cursor_ = splineProbe_ ? probeSurface(*splineProbe_, indexFromWorld_, camera_, pixel.x, pixel.y, normalDepth.width(),
                                        normalDepth.height(), normalDepthTexel[3])
                         : probePoint(indexFromWorld_, camera_, pixel.x, pixel.y, normalDepth.width(),
                         normalDepth.height(), normalDepthTexel[3]);
}

// The raycaster's setters restart the progressive frame, so only what changed is passed on.
bool ViewerSession::applySettings() {
  const RenderOptions o = raycaster_.options();
  const std::vector<Isosurface> surfaces = raycaster_.surfaces();
  const std::shared_ptr<const TransferTable> transfer = o.transfer;
  if (dvr_) {
    applyTransfer();
    if (settings_.dvrShading != o.dvrShading) {
      try {
        raycaster_.setDvrShading(settings_.dvrShading);
      } catch (const Error& e) {  // a strength typed out of range (ctrl + click), or the shaded program
        settings_.dvrShading = o.dvrShading;  // failed to build: the settings go back
        notify(e.what());
      }
    }
    if (settings_.stopOpacity != o.terminationOpacity) {
      try {
        raycaster_.setTerminationOpacity(settings_.stopOpacity);
      } catch (const Error& e) {  // typed out of range (ctrl + click): the setting goes back
        settings_.stopOpacity = o.terminationOpacity;
        notify(e.what());
      }
    }
  } else if (surfacesOfSettings() != surfaces) {
    raycaster_.setSurfaces(surfacesOfSettings());
  }
  if (settings_.skipEmpty != o.skipEmpty) raycaster_.setSkipEmpty(settings_.skipEmpty);
  if (settings_.finiteDifferenceNormals != o.finiteDifferenceNormals)
    raycaster_.setFiniteDifferenceNormals(settings_.finiteDifferenceNormals);
  if (settings_.lightInCamera != o.lightInCamera) raycaster_.setLightInCamera(settings_.lightInCamera);
  if (settings_.clipLo != o.clipLo || settings_.clipHi != o.clipHi) raycaster_.setClip(settings_.clipLo, settings_.clipHi);
  const RenderOptions& now = raycaster_.options();
  return raycaster_.surfaces() != surfaces || now.transfer != transfer || now.skipEmpty != o.skipEmpty ||
         now.finiteDifferenceNormals != o.finiteDifferenceNormals || now.surfaceColor != o.surfaceColor ||
         now.lightInCamera != o.lightInCamera || now.clipLo != o.clipLo || now.clipHi != o.clipHi ||
         now.dvrShading != o.dvrShading || now.terminationOpacity != o.terminationOpacity;
}

std::vector<Isosurface> ViewerSession::surfacesOfSettings() const {
  std::vector<Isosurface> all{Isosurface{settings_.iso, settings_.surfaceColor, settings_.surfaceOpacity}};
  all.insert(all.end(), settings_.moreSurfaces.begin(), settings_.moreSurfaces.end());
  return all;
}

float& ViewerSession::selectedIso() {
  const int k = settings_.selectedSurface;
  return k >= 1 && k <= int(settings_.moreSurfaces.size()) ? settings_.moreSurfaces[std::size_t(k - 1)].iso : settings_.iso;
}

void ViewerSession::useTransfer(DvrTransfer next) {
  // Validates the scale first: a throw changes nothing. Only the table is uploaded (and the bricks
  // needed recomputed when its zero entries moved): resident bricks stay.
  raycaster_.setTransfer(next.table());
  dvr_ = std::move(next);
  settings_.transferFunction = dvr_->spec;
}

void ViewerSession::applyTransfer() {
  // Another starting point (the combo, or Load) replaces the editor's points, as an undo step; else
  // the editor's points and colours, when edited, are the function, and its starting point the spec
  // (an undo can go back across a starting point chosen).
  // (reloadBase_ taken first: left set, it would start the same function again next frame, a second
  // undo step.)
  const bool reload = std::exchange(reloadBase_, false);
  const bool newBase = reload || settings_.transferFunction != dvr_->spec;
  const bool edited = editor_->revision() != appliedRevision_;
  if (!newBase && !edited && settings_.densityScale == appliedDensityScale_ && settings_.unitDistance == appliedUnitDistance_)
    return;
  try {
    const std::string name = newBase ? settings_.transferFunction : editor_->spec();
    const TransferFunction function = newBase ? baseFunction(name) : editor_->function();
    // The unit distance as the session has it (a double: --unit-distance, or the voxel size) until the
    // slider moves it, so that the table stays render's, bit for bit.
    const double unitDistance =
        settings_.unitDistance == appliedUnitDistance_ ? dvr_->scale.unitDistance : double(settings_.unitDistance);
    useTransfer(DvrTransfer{name, function, OpticalScale{unitDistance, double(settings_.densityScale)}});
    if (newBase) {
      editor_->start(dvr_->function, dvr_->spec);
      dragPoint_ = shapePoint_ = dragColor_ = selectedColor_ = -1;
    }
    appliedRevision_ = editor_->revision();
    appliedDensityScale_ = settings_.densityScale;
    appliedUnitDistance_ = settings_.unitDistance;
  } catch (const Error& e) {  // a typed density scale below 0, say: the settings go back
    settings_.transferFunction = dvr_->spec;
    settings_.densityScale = appliedDensityScale_;
    settings_.unitDistance = appliedUnitDistance_;
    notify(e.what());
    if (!edited) return;
    // The editor's function at the scale in use: the scale was what failed, so its edits (an undo
    // across a starting point too) still apply. Only a function refused there too starts anew.
    try {
      useTransfer(DvrTransfer{editor_->spec(), editor_->function(), dvr_->scale});
    } catch (const Error&) {
      editor_->reset(dvr_->function, dvr_->spec);
      dragPoint_ = shapePoint_ = dragColor_ = selectedColor_ = -1;
    }
    appliedRevision_ = editor_->revision();
  }
}

void ViewerSession::updateStats(const StepStats& step, double imageDrawn, bool uiDrawn) {
  // Frame time and upload rate over windows of about kRateWindowSeconds: steady numbers to read,
  // and a slow first frame (shader compilation) does not linger in them.
  const auto now = std::chrono::steady_clock::now();
  if (firstFrame_) {
    rateWindowStart_ = now;
    uploadedAtWindowStart_ = raycaster_.bricksUploaded();
    firstFrame_ = false;
  } else {
    ++framesInWindow_;
    imageDrawnInWindow_ += imageDrawn;
  }
  const double window = std::chrono::duration<double>(now - rateWindowStart_).count();
  if (window >= kRateWindowSeconds && framesInWindow_ > 0) {
    stats_.frameMs = 1000.0 * window / framesInWindow_;
    stats_.fps = framesInWindow_ / window;
    const uint64_t uploaded = raycaster_.bricksUploaded() - uploadedAtWindowStart_;
    stats_.uploadMiBPerSecond = double(uploaded) * double(raycaster_.slotBytes()) / double(1 << 20) / window;
    uploadedAtWindowStart_ = raycaster_.bricksUploaded();
    stats_.imageDrawnAverage = imageDrawnInWindow_ / framesInWindow_;
    rateWindowStart_ = now;
    framesInWindow_ = 0;
    imageDrawnInWindow_ = 0.0;
    if (raycaster_.levelCount() > 1) stats_.levels = raycaster_.levelMix();
  }
  if (step.complete && !stats_.complete && raycaster_.levelCount() > 1) stats_.levels = raycaster_.levelMix();
  stats_.imageDrawn = imageDrawn;
  stats_.uiDrawn = uiDrawn;
  stats_.resident = raycaster_.residentCount();
  stats_.needed = raycaster_.neededCount();
  stats_.missing = raycaster_.missingCount();
  if (step.dispatched) stats_.requested = step.requested;
  stats_.passGpuMs = 1e3 * step.gpuSeconds;
  stats_.streaming = step.streaming;
  stats_.complete = step.complete;
}

void ViewerSession::frame(int fbWidth, int fbHeight, int windowHeight, int bufferAge) {
  const auto frameStart = std::chrono::steady_clock::now();
  fbWidth_ = fbWidth;
  fbHeight_ = fbHeight;
  windowHeight_ = windowHeight;
  handleInput(windowHeight);
  if (pathRecorder_) pathRecorder_->record(camera_);  // the camera this frame renders
  panelWidth_ = kPanelWidth * ImGui::GetIO().FontGlobalScale;
  // The panel is opaque: the columns wholly under it get no rays and no image. Framebuffer pixels
  // per window unit: fbHeight / windowHeight.
  const int covered = windowHeight > 0 ? int(std::floor(panelWidth() * float(fbHeight) / float(windowHeight))) : 0;
  const FrameLook look{fbWidth, fbHeight, std::clamp(covered, 0, fbWidth), settings_.background};
  // The whole frame is queued behind the pass before the CPU waits for the pass's results: the
  // panel is built while the pass runs, and the GPU goes on to the image and the panel without
  // waiting for the CPU (on the H200, waiting first cost 0.1-0.2 ms a frame, 7-13% at 1080p). So
  // panel edits take effect from the next frame on, and the streaming line tells the last frame's.
  // Uploads within what the frame budget leaves after the last frame's other work (viewer/UploadBudget.h).
  raycaster_.startStep(camera_, fbWidth, fbHeight, uploadSecondsWithin(frameBudgetSeconds_, lastFrameRest_, kUploadSecondsPerFrame),
                       covered);
  drawPanel(windowHeight);
  if (settings_.showHelp) drawHelp();
  drawAxisIndicator(windowHeight);
  drawOpenField();
  if (!notice_.empty() && std::chrono::steady_clock::now() > noticeUntil_) notice_.clear();
  drawNotice();
  shownStatusLine_ = statusLine();
  drawStreamingLine(windowHeight);
  ImGui::Render();
  ImDrawData* ui = ImGui::GetDrawData();
  const std::vector<PixelRect> overlays = overlaysOf(*ui, look.imageArea());
  const uint64_t uiHash = hashOf(*ui);
  std::vector<PixelRect> regions = redraw_.regions(look, bufferAge);
  // The look's background, as the regions assume: a panel edit made this frame shows from the next.
  presenter_.draw(raycaster_.colorTexture(), look.background, regions, look.imageArea(), &raycaster_.passResults());
  // A panel the back buffer already shows, with nothing over the image, is not drawn again (on the
  // H200 ImGui's draw lists cost 0.04 ms a frame, mostly the panel's background). Only while the
  // OpenGL backend does nothing else in RenderDrawData: from ImGui 1.92 it uploads textures there.
  constexpr bool kUiMaySkip = IMGUI_VERSION_NUM < 19200;
  const bool uiShown = kUiMaySkip && overlays.empty() && redraw_.holdsUi(look, bufferAge, uiHash);
  if (!uiShown) ImGui_ImplOpenGL3_RenderDrawData(ui);
  const StepStats step = raycaster_.finishStep();
  updateCursor(fbWidth, fbHeight, windowHeight);
  regions.front() = intersected(united(regions.front(), raycaster_.surfaceRect()), look.imageArea());  // as drawn
  redraw_.drawn(look, raycaster_.surfaceRect(), overlays, uiHash);
  // A setting edited in this frame's panel shows from the next frame: this one is not the final image.
  const bool changed = applySettings() || settings_.background != look.background;
  // Another reconstruction (the panel's combo) is another source: this session asks for its data again
  // with it (viewer/OpenAnotherFile.h), which replaces the session and keeps the view; until then, and
  // if that fails, the combo shows the one in use.
  if (settings_.reconstruction != source().reconstruction().name) {
    openRequest_ = OpenRequest{{}, settings_.reconstruction};
    settings_.reconstruction = std::string(source().reconstruction().name);
  }
  updateStats(step, double(coveredArea(regions)) / double(std::max<long long>(1, look.imageArea().area())), !uiShown);
  // This frame's image is complete (its pass was the last one) and its line told a settled frame.
  shownSettled_ = shownStatusLine_.empty() && settled() && !changed;
  if (std::exchange(screenshotRequested_, false)) {
    // Here, once the frame is drawn: the PNG shows it as the window will (the notice from the next frame on).
    const std::string stem = uniqueTimestampedStem(outputDirectory_, "fccvdb", {".png", ".exr"});
    try {
      writeScreenshots(stem + ".png", stem + ".exr");
    } catch (const std::exception& e) {
      notify(e.what());  // an unwritable directory must not end the session
    }
  }
  // The swap (and its wait for the display) is not part of it: this is the frame's own work.
  lastFrameRest_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - frameStart).count() - step.uploadSeconds;
}

}  // namespace fcc::render
