// A headless OpenGL 4.5 core context through EGL, with no window and no surface
// (EGL_KHR_surfaceless_context); GL entry points come from libepoxy (include <epoxy/gl.h>).
//
// Displays are tried in this order, the first that gives a 4.5 core context wins:
//   1. the EGL device platform (EGL_EXT_device_enumeration or _base, EGL_EXT_platform_device), hardware
//      devices before Mesa's software device: a GPU without any X or Wayland server;
//   2. Mesa's surfaceless platform (EGL_MESA_platform_surfaceless): llvmpipe or a render node;
//   3. the default display (eglGetDisplay(EGL_DEFAULT_DISPLAY)).
#pragma once

#include <string>

#include "sparse/Error.h"

namespace fcc {

class EglContext {
 public:
  // Creates the context and makes it current on the calling thread. Throws fcc::Error, one line:
  // "no usable EGL/OpenGL 4.5: <what each display attempt said>". `hardwareDevice` >= 0: of the hardware
  // devices the EGL device platform lists, the one at that index modulo their count is tried first
  // (an MPI rank's GPU, CUDA_VISIBLE_DEVICES-style); -1: the list's order.
  explicit EglContext(int hardwareDevice = -1);
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  void makeCurrent() const;               // on the calling thread (a context is current on one thread)
  const std::string& renderer() const { return renderer_; }  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  const std::string& version() const { return version_; }    // GL_VERSION
  const std::string& platform() const { return platform_; }  // which attempt succeeded, e.g. "EGL device 1/2 (software)"
  std::string describe() const { return renderer_ + " (" + platform_ + ", OpenGL " + version_ + ")"; }
  // Why the displays tried before platform() were not used ("" when the first one worked), for logs.
  const std::string& fallbacks() const { return fallbacks_; }

 private:
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  std::string renderer_, version_, platform_, fallbacks_;
};

}  // namespace fcc
