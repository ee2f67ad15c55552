#include "viewer/GpuWarmup.h"

#include <chrono>

#include "embedded_shaders.h"
#include "viewer/GlProgram.h"

namespace fcc::render {

int warmUpGpu(double seconds) {
  if (!(seconds > 0.0)) return 0;
  // Dispatches grow from 64 work groups of 256 invocations (4 096 dependent FMAs each) while one
  // takes under 2 ms, to at most 8 192 groups: a few milliseconds a dispatch on a large GPU, small ones
  // on a slow renderer, so the wall-time check between them overshoots little anywhere.
  constexpr GLuint kMaxGroups = 8192;
  constexpr int kIterations = 4096;
  const GlProgram program = GlProgram::compute(embedded::shaders("shaders/gpu_warmup.comp"), "shaders/gpu_warmup.comp");
  GlBuffer sink(kMaxGroups * sizeof(float));
  sink.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  program.use();
  glUniform1i(program.uniformLocation("uIterations"), kIterations);
  const auto start = std::chrono::steady_clock::now();
  const auto end = start + std::chrono::duration<double>(seconds);
  GLuint groups = 64;
  int dispatches = 0;
  for (auto now = start; dispatches == 0 || now < end;) {
    glDispatchCompute(groups, 1, 1);
    glFinish();
    ++dispatches;
    const auto after = std::chrono::steady_clock::now();
    if (after - now < std::chrono::milliseconds(2) && groups < kMaxGroups) groups *= 2;
    now = after;
  }
  checkGl("warming the GPU up");
  glUseProgram(0);
  return dispatches;
}

}  // namespace fcc::render
