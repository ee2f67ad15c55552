// The viewer's window: GLFW (OpenGL 4.5 core), Dear ImGui's GLFW and OpenGL 3 backends, and the
// frame loop around a ViewerSession: events, the panel, screenshots, and the automation mode that
// writes one screenshot once streaming has settled and exits.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "ViewerSession.h"
#include "WindowBufferAge.h"

struct GLFWwindow;

namespace fcc::render {

struct WindowOptions {
  int width = 1280, height = 800;  // window size in screen coordinates
  std::string title = "fccvdb";
  // Automation: after `frames` frames and once streaming has settled, write `screenshot` (.png: the
  // window as shown, panel included; .exr: the rendered image's channels) and close.
  std::string screenshot;
  int frames = 30;
};

class ViewerWindow {
 public:
  // Opens the window and makes its context current. Throws fcc::Error "no display: use `fccvdb
  // render` for headless images" when there is no display, or a line naming what GLFW said.
  explicit ViewerWindow(const WindowOptions& options);
  // The same "no display" Error, before anything slow (a conversion) runs; GLFW stays initialized
  // for the window that follows.
  static void requireDisplay();
  ~ViewerWindow();
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  // The framebuffer's aspect ratio (for framing the camera before the session exists).
  double aspect() const;
  // Runs until the window closes (or the automation screenshot is written): nullopt; or until the
  // session is asked to open another file (dropped on the window, or typed after O) or its data with
  // another reconstruction (the panel): the request, and the window stays open for the next session.
  // The session reports the files it writes (ViewerSession::setReport).
  std::optional<OpenRequest> run(ViewerSession& session);
  void setTitle(const std::string& title);

 private:
  WindowOptions options_;
  GLFWwindow* window_ = nullptr;
  bool imguiReady_ = false;
  std::unique_ptr<WindowBufferAge> bufferAge_;
};

}  // namespace fcc::render
