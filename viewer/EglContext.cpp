#include "EglContext.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <algorithm>
#include <vector>

namespace fcc {

namespace {

const char* eglErrorName(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "EGL error";
  }
}

std::string eglFailure(const char* call) { return std::string(call) + " failed (" + eglErrorName(eglGetError()) + ")"; }

bool hasClientExtension(const char* name) {
  // With EGL_NO_DISPLAY the extension string lists the client extensions (EGL_EXT_client_extensions).
  const char* exts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  eglGetError();  // clear EGL_BAD_DISPLAY where client extensions are unsupported
  if (!exts) return false;
  const std::string all = std::string(" ") + exts + " ";
  return all.find(std::string(" ") + name + " ") != std::string::npos;
}

struct Attempt {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
};

// Initializes `display` and creates a current 4.5 core context on it; on failure returns false and
// sets `why`. The display is not terminated (EGL displays are per-process singletons that another
// EglContext may be using).
bool tryDisplay(EGLDisplay display, Attempt& out, std::string& why) {
  if (display == EGL_NO_DISPLAY) {
    why = std::string("no display (") + eglErrorName(eglGetError()) + ")";
    return false;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    why = eglFailure("eglInitialize");
    return false;
  }
  if (major * 10 + minor < 15 && !epoxy_has_egl_extension(display, "EGL_KHR_create_context")) {
    why = "EGL " + std::to_string(major) + "." + std::to_string(minor) + " without EGL_KHR_create_context";
    return false;
  }
  if (!epoxy_has_egl_extension(display, "EGL_KHR_surfaceless_context")) {
    why = "no EGL_KHR_surfaceless_context";
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = eglFailure("eglBindAPI(EGL_OPENGL_API)");
    return false;
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!epoxy_has_egl_extension(display, "EGL_KHR_no_config_context")) {
    const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, attribs, &config, 1, &count) || count < 1) {
      why = "no EGL config with EGL_OPENGL_BIT";
      return false;
    }
  }
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
  if (context == EGL_NO_CONTEXT) {
    why = eglFailure("eglCreateContext(OpenGL 4.5 core)");
    return false;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    why = eglFailure("eglMakeCurrent without a surface");
    eglDestroyContext(display, context);
    return false;
  }
  if (epoxy_gl_version() < 45) {
    const char* v = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    why = std::string("the context is OpenGL ") + (v ? v : "?");
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
    return false;
  }
  out.display = display;
  out.context = context;
  return true;
}

bool isSoftwareDevice(EGLDeviceEXT device) {
  const char* exts = eglQueryDeviceStringEXT(device, EGL_EXTENSIONS);
  eglGetError();
  return exts && std::string(exts).find("EGL_MESA_device_software") != std::string::npos;
}

}  // namespace

EglContext::EglContext(int hardwareDevice) {
  std::vector<std::string> reasons;
  Attempt ok;
  auto attempt = [&](EGLDisplay display, const std::string& label) {
    std::string why;
    if (tryDisplay(display, ok, why)) {
      platform_ = label;
      return true;
    }
    reasons.push_back(label + ": " + why);
    return false;
  };

  bool done = false;
  // 1. The device platform: GPUs first, Mesa's software device last.
  // NVIDIA advertises EGL_EXT_device_base (enumeration + query in one), glvnd/Mesa the split names.
  const bool canEnumerate = hasClientExtension("EGL_EXT_device_enumeration") || hasClientExtension("EGL_EXT_device_base");
  if (canEnumerate && hasClientExtension("EGL_EXT_platform_device")) {
    EGLint n = 0;
    std::vector<EGLDeviceEXT> devices;
    if (eglQueryDevicesEXT(0, nullptr, &n) && n > 0) {
      devices.resize(size_t(n));
      if (!eglQueryDevicesEXT(n, devices.data(), &n)) n = 0;
      devices.resize(size_t(std::max(n, 0)));
    }
    if (devices.empty()) reasons.push_back("EGL device platform: no devices");
    const auto software = std::stable_partition(devices.begin(), devices.end(), [](EGLDeviceEXT d) { return !isSoftwareDevice(d); });
    const long hardware = long(software - devices.begin());
    if (hardwareDevice >= 0 && hardware > 1)  // the chosen GPU first, the others after it as a fallback
      std::rotate(devices.begin(), devices.begin() + hardwareDevice % hardware, software);
    for (size_t i = 0; i < devices.size() && !done; ++i) {
      std::string label = "EGL device " + std::to_string(i + 1) + "/" + std::to_string(devices.size());
      if (isSoftwareDevice(devices[i])) label += " (software)";
      done = attempt(eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), label);
    }
  } else {
    reasons.push_back(canEnumerate ? "EGL device platform: no EGL_EXT_platform_device"
                                   : "EGL device platform: no EGL_EXT_device_enumeration or EGL_EXT_device_base");
  }
  // 2. Mesa's surfaceless platform.
  if (!done) {
    if (hasClientExtension("EGL_MESA_platform_surfaceless") && hasClientExtension("EGL_EXT_platform_base"))
      done = attempt(eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
                     "Mesa surfaceless platform");
    else
      reasons.push_back("Mesa surfaceless platform: not supported");
  }
  // 3. Whatever the default display is.
  if (!done) done = attempt(eglGetDisplay(EGL_DEFAULT_DISPLAY), "default display");

  std::string joined;
  for (size_t i = 0; i < reasons.size(); ++i) joined += (i ? "; " : "") + reasons[i];
  if (!done) throw Error("no usable EGL/OpenGL 4.5: " + joined);
  fallbacks_ = joined;
  display_ = ok.display;
  context_ = ok.context;
  auto str = [](GLenum name) {
    const char* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "?");
  };
  renderer_ = str(GL_RENDERER);
  version_ = str(GL_VERSION);
}

EglContext::~EglContext() {
  if (context_ == nullptr) return;
  if (eglGetCurrentContext() == static_cast<EGLContext>(context_))
    eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(static_cast<EGLDisplay>(display_), static_cast<EGLContext>(context_));
}

void EglContext::makeCurrent() const {
  if (!eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                      static_cast<EGLContext>(context_)))
    throw Error("making the OpenGL context current: " + eglFailure("eglMakeCurrent"));
}

}  // namespace fcc
