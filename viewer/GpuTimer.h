// The GPU time between two points of the command stream (a pair of GL_TIMESTAMP queries): what a pass
// costs on the GPU itself, apart from the CPU's submission and waiting. For benchmarks; the queries
// add no synchronisation until seconds() is asked.
#pragma once

#include <epoxy/gl.h>

namespace fcc {

class GpuInterval {
 public:
  GpuInterval();  // needs a current OpenGL context
  ~GpuInterval();
  GpuInterval(const GpuInterval&) = delete;
  GpuInterval& operator=(const GpuInterval&) = delete;

  void begin();
  void end();
  // Seconds between begin() and end() on the GPU; waits for the GPU to reach end().
  double seconds() const;

 private:
  GLuint queries_[2] = {0, 0};
};

}  // namespace fcc
