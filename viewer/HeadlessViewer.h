// What the viewer draws into when there is no window (`fccvdb bench view`, tests): an offscreen RGBA8
// framebuffer in the window's place, and Dear ImGui with its OpenGL 3 backend and no platform backend
// (display size and time set by hand). Needs a current OpenGL 4.5 context (fcc::EglContext).
#pragma once

#include <epoxy/gl.h>

#include <vector>

namespace fcc::render {

class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height);
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;

  void bind() const;  // as the draw and read framebuffer
  int width() const { return width_; }
  int height() const { return height_; }
  // Its pixels, RGBA, 4 bytes each, row 0 at the bottom (OpenGL's order). Binds it for reading.
  std::vector<unsigned char> readRgba() const;

 private:
  int width_ = 0, height_ = 0;
  GLuint framebuffer_ = 0, color_ = 0;
};

// ImGui's context for the lifetime of this object; ImGui_ImplOpenGL3_NewFrame() and
// ImGui::NewFrame() start each frame (ViewerSession::frame renders it).
class HeadlessImGui {
 public:
  HeadlessImGui(int width, int height);
  ~HeadlessImGui();
  HeadlessImGui(const HeadlessImGui&) = delete;
  HeadlessImGui& operator=(const HeadlessImGui&) = delete;
  // Starts a frame of `secondsSinceLast` in the current context.
  static void newFrame(float secondsSinceLast = 1.0f / 60.0f);
};

}  // namespace fcc::render
