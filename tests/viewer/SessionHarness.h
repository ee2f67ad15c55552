// A viewer session without a window, for tests: an offscreen target, ImGui without a platform
// backend, and helpers that play the mouse and keys into ImGui's input as GLFW's backend would.
#pragma once

#define GLFW_INCLUDE_NONE  // key codes only
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "RenderTestSupport.h"
#include "viewer/DatasetSummary.h"
#include "viewer/DvrTransfer.h"
#include "viewer/FccBrickSource.h"
#include "viewer/HeadlessViewer.h"
#include "viewer/ViewerSession.h"

namespace fcc::test {

struct SessionHarness {
  static constexpr int kWidth = 400, kHeight = 240;
  // A pool that holds every brick of the small blobs: one load, no eviction (tests not of streaming).
  static constexpr std::size_t kLargePoolBytes = std::size_t(64) << 20;
  // The window's size (the tests' pixel helpers assume kWidth x kHeight).
  int width = kWidth, height = kHeight;
  std::optional<io::BrickStore> store;  // the FCC file's, for the sessions the harness makes
  std::unique_ptr<render::FccBrickSource> source;  // DVR sessions' (the other constructor)
  render::HeadlessImGui imgui{width, height};
  render::OffscreenTarget target{width, height};
  std::unique_ptr<render::ViewerSession> session;

  // `size` and `fontScale`: another window than the small default (a font of half size: a narrower
  // panel, more image, fewer rays on llvmpipe); `view`'s own window is 1280 x 800 at font scale 1.
  explicit SessionHarness(const std::string& path, float iso = 0.3f, std::size_t gpuCacheBytes = kSmallPoolBytes,
                          glm::ivec2 size = {kWidth, kHeight}, float fontScale = 0.5f)
      : width(size.x), height(size.y), store(std::in_place, path) {
    ImGuiIO& io = ImGui::GetIO();
    io.FontGlobalScale = fontScale;
    // The keys text fields use, mapped as GLFW's backend maps them.
    io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
    io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
    io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
    io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
    render::RenderOptions options;
    options.iso = iso;
    options.gpuCacheBytes = gpuCacheBytes;
    session = std::make_unique<render::ViewerSession>(*store, options, smallBlobsCamera(), render::summarizeDataset(*store));
  }
  // ImGui and the target only: the test makes the session (a Cartesian source, a loop over datasets).
  struct NoSession {};
  explicit SessionHarness(NoSession, glm::ivec2 size = {kWidth, kHeight}, float fontScale = 0.5f)
      : width(size.x), height(size.y) {
    ImGui::GetIO().FontGlobalScale = fontScale;
  }
  // A DVR session over an FCC source with the preset `tf` fitted as `view --mode dvr --tf` fits it.
  SessionHarness(const std::string& path, const std::string& tf, std::size_t gpuCacheBytes = kLargePoolBytes)
      : store(std::in_place, path), source(std::make_unique<render::FccBrickSource>(*store, std::size_t(64) << 20)) {
    ImGui::GetIO().FontGlobalScale = 0.5f;
    render::RenderOptions options;
    options.gpuCacheBytes = gpuCacheBytes;
    render::DvrTransfer dvr{tf, render::fitTransferFunction(transferFunctionPreset(tf), *source),
                            OpticalScale{render::defaultUnitDistance(*source), 1.0}};
    session = std::make_unique<render::ViewerSession>(*source, &*store, options, smallBlobsCamera(),
                                                      render::summarizeDataset(*store), std::move(dvr));
  }

  // One frame; `input` sets ImGui's input state for it (keys, mouse) before ImGui::NewFrame().
  template <class Input>
  void frame(Input&& input) {
    input(ImGui::GetIO());
    render::HeadlessImGui::newFrame();
    target.bind();
    session->frame(width, height, height, 0);
  }
  void frame() {
    frame([](ImGuiIO&) {});
  }
  // Frames until the session shows its settled image (false after `limit` frames).
  bool settle(int limit = 2000) {
    for (int n = 0; n < limit; ++n) {
      frame();
      if (session->shownSettled()) return true;
    }
    return false;
  }
  // A key pressed for one frame and released the next (IsKeyPressed fires once).
  void press(int glfwKey, bool shift = false, bool ctrl = false) {
    frame([&](ImGuiIO& io) {
      io.KeysDown[glfwKey] = true;
      io.KeyShift = shift;
      io.KeyCtrl = ctrl;
    });
    frame([&](ImGuiIO& io) {
      io.KeysDown[glfwKey] = false;
      io.KeyShift = false;
      io.KeyCtrl = false;
    });
  }
  // Characters typed into ImGui (a text field), one frame.
  void type(const std::string& text) {
    frame([&](ImGuiIO& io) {
      for (char c : text) io.AddInputCharacter(static_cast<unsigned>(c));
    });
  }
  // A click at (x, y) in window units: moved there, pressed a frame, released the next.
  void click(float x, float y, bool ctrl = false) {
    frame([&](ImGuiIO& io) { io.MousePos = ImVec2(x, y); });
    frame([&](ImGuiIO& io) {
      io.MouseDown[0] = true;
      io.KeyCtrl = ctrl;
    });
    frame([&](ImGuiIO& io) {
      io.MouseDown[0] = false;
      io.KeyCtrl = false;
    });
  }
  // RGBA pixels of the target, row 0 at the top.
  std::vector<unsigned char> pixels() const {
    std::vector<unsigned char> bottomUp = target.readRgba(), topDown(bottomUp.size());
    const std::size_t row = std::size_t(width) * 4;
    for (int y = 0; y < height; ++y)
      std::copy_n(bottomUp.data() + std::size_t(height - 1 - y) * row, row, topDown.data() + std::size_t(y) * row);
    return topDown;
  }
};

}  // namespace fcc::test
