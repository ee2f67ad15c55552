#version 450 core
// Arithmetic alone, to keep the GPU busy before a measurement (viewer/GpuWarmup.h): no data is read,
// so no cache a measurement depends on is touched. One value a work group is written so that the
// compiler keeps the loop.
layout(local_size_x = 256) in;
layout(std430, binding = 0) writeonly buffer Sink { float sink[]; };
uniform int uIterations;

void main() {
  float x = float(gl_GlobalInvocationID.x) * 1e-7;
  for (int i = 0; i < uIterations; ++i) x = fma(x, 0.999999, 1e-7);
  if (gl_LocalInvocationID.x == 0u) sink[gl_WorkGroupID.x] = x;
}
