// Whether an OpenGL renderer (GL_RENDERER) is one of Mesa's software rasterizers: the GPU pipeline run
// on the CPU, tens to hundreds of times slower, so benchmarks time fewer frames there.
#pragma once

#include <string>

namespace fcc::cli {

inline bool isCpuRenderer(const std::string& renderer) {
  for (const char* name : {"llvmpipe", "softpipe", "lavapipe", "SwiftShader"})
    if (renderer.find(name) != std::string::npos) return true;
  return false;
}

}  // namespace fcc::cli
