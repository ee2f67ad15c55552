#include "WindowBufferAge.h"

#include <epoxy/glx.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GLFW_EXPOSE_NATIVE_X11
#define GLFW_EXPOSE_NATIVE_GLX
#include <GLFW/glfw3native.h>

namespace fcc::render {

WindowBufferAge::WindowBufferAge(GLFWwindow* window) : window_(window) {
  // Debian's GLFW 3.3 speaks X11 and creates GLX contexts unless asked for EGL; glfwGetGLXContext
  // reports an error (to the callback) and returns null for any other.
  Display* display = glfwGetX11Display();
  if (!display || !glfwGetGLXContext(window)) return;
  supported_ = epoxy_has_glx_extension(display, DefaultScreen(display), "GLX_EXT_buffer_age");
}

int WindowBufferAge::age() const {
  if (!supported_) return 0;
  unsigned int age = 0;
  glXQueryDrawable(glfwGetX11Display(), glfwGetGLXWindow(window_), GLX_BACK_BUFFER_AGE_EXT, &age);
  return int(age);
}

}  // namespace fcc::render
