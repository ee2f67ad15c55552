#include "ViewerWindow.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE  // GL comes from libepoxy
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

#include "io/ImageOutput.h"
#include "sparse/Error.h"
#include "viewer/UploadBudget.h"

namespace fcc::render {
namespace {

std::string glfwLastError;  // GLFW reports errors through a callback; the last one explains a failure

void onGlfwError(int, const char* description) { glfwLastError = description ? description : "unknown error"; }

std::string droppedPath;  // the first file of the last drop on the window (one window per process)

void onDrop(GLFWwindow*, int count, const char** paths) {
  if (count > 0 && paths[0]) droppedPath = paths[0];
}

bool endsWith(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  return std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(),
                    [](char a, char b) { return std::tolower((unsigned char)a) == std::tolower((unsigned char)b); });
}

}  // namespace

void ViewerWindow::requireDisplay() {
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit()) throw Error("no display: use `fccvdb render` for headless images (GLFW: " + glfwLastError + ")");
}

ViewerWindow::ViewerWindow(const WindowOptions& options) : options_(options) {
  requireDisplay();
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_SCALE_TO_MONITOR, GLFW_TRUE);  // a high-DPI screen gets a window of the same apparent size
  window_ = glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw Error("cannot open an OpenGL 4.5 window (GLFW: " + glfwLastError +
                "); use `fccvdb render` for headless images");
  }
  glfwMakeContextCurrent(window_);
  bufferAge_ = std::make_unique<WindowBufferAge>(window_);
  // Automation renders as fast as it can; interactively, frames follow the display.
  glfwSwapInterval(options.screenshot.empty() ? 1 : 0);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // never write imgui.ini into the user's directory
  float scaleX = 1.0f, scaleY = 1.0f;
  glfwGetWindowContentScale(window_, &scaleX, &scaleY);
  const float scale = std::max(1.0f, std::max(scaleX, scaleY));
  io.FontGlobalScale = scale;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().ScaleAllSizes(scale);
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  glfwSetDropCallback(window_, onDrop);  // ImGui's backend installs none
  ImGui_ImplOpenGL3_Init("#version 450");
  imguiReady_ = true;
}

ViewerWindow::~ViewerWindow() {
  if (imguiReady_) {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

double ViewerWindow::aspect() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return w > 0 && h > 0 ? double(w) / double(h) : double(options_.width) / double(options_.height);
}

void ViewerWindow::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

std::optional<OpenRequest> ViewerWindow::run(ViewerSession& session) {
  const bool automated = !options_.screenshot.empty();
  // Interactively, uploads fit the display's frame time (the primary monitor's refresh rate; a window
  // on another monitor is not followed). Automation keeps 60 Hz, so its frames do not depend on the
  // machine's display.
  if (!automated) {
    GLFWmonitor* monitor = glfwGetPrimaryMonitor();
    const GLFWvidmode* mode = monitor ? glfwGetVideoMode(monitor) : nullptr;
    session.setFrameBudgetSeconds(frameBudgetForRefresh(mode ? mode->refreshRate : 0));
  }
  int frames = 0;
  while (!glfwWindowShouldClose(window_)) {
    // Idle and complete: wait for input instead of redrawing the same image.
    if (!automated && session.shownSettled()) glfwWaitEventsTimeout(0.25);
    else glfwPollEvents();
    if (!droppedPath.empty()) session.requestOpen(std::exchange(droppedPath, std::string()));
    int fbWidth = 0, fbHeight = 0, winHeight = 0;
    glfwGetFramebufferSize(window_, &fbWidth, &fbHeight);
    glfwGetWindowSize(window_, nullptr, &winHeight);
    if (fbWidth <= 0 || fbHeight <= 0) {  // minimised
      glfwWaitEvents();
      continue;
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    // Esc quits unless a text field has it (there it ends the edit).
    if (!ImGui::GetIO().WantTextInput && ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false))
      glfwSetWindowShouldClose(window_, GLFW_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    session.frame(fbWidth, fbHeight, winHeight, bufferAge_->age());
    ++frames;
    if (automated && frames >= options_.frames && session.shownSettled()) {
      const bool exr = endsWith(options_.screenshot, ".exr");
      session.writeScreenshots(exr ? "" : options_.screenshot, exr ? options_.screenshot : "");
      return std::nullopt;
    }
    glfwSwapBuffers(window_);
    if (std::optional<OpenRequest> next = session.takeOpenRequest()) return next;
  }
  return std::nullopt;
}

}  // namespace fcc::render
