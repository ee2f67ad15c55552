// How old a GLFW window's back buffer is, so the viewer can draw only what changed (RedrawTracker.h).
// Apart from ViewerWindow.cpp because the X11 headers it needs define macros (None, Status, Bool).
#pragma once

struct GLFWwindow;

namespace fcc::render {

class WindowBufferAge {
 public:
  // The window's context must be current.
  explicit WindowBufferAge(GLFWwindow* window);
  // 1 if the back buffer holds the frame shown last, n if the one n frames ago, 0 if unknown (a new
  // buffer, a context that is not GLX, or no GLX_EXT_buffer_age): then the whole image is drawn.
  int age() const;
  bool supported() const { return supported_; }

 private:
  GLFWwindow* window_;
  bool supported_ = false;
};

}  // namespace fcc::render
