#version 450 core
// GLSL compute: the FCC box spline (sparse/FccSpline.h) over a dense coefficient block; the same
// evaluation as kernels/spline_eval.cl. The header is inlined at build time by fcc_embed, after the
// #version line (which must stay first).
#define FCC_GLSL 1
#include "FccSpline.h"

layout(local_size_x = 64) in;

// results[i] = (s, ds/dx, ds/dy, ds/dz) at points[i].xyz (lattice index space; .w is ignored).
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
// Every integer point of the box [uOrigin, uOrigin + uDims) with x fastest (only FCC sites are read);
// sites outside the box have the coefficient uBackground.
layout(std430, binding = 1) readonly buffer Coefficients { float coefficients[]; };
layout(std430, binding = 2) writeonly buffer Results { vec4 results[]; };

uniform ivec4 uOrigin;
uniform ivec4 uDims;
uniform float uBackground;
uniform uint uCount;

float fcc_block_coefficient(ivec3 site) {
  ivec3 r = site - uOrigin.xyz;
  if (any(lessThan(r, ivec3(0))) || any(greaterThanEqual(r, uDims.xyz))) return uBackground;
  return coefficients[(r.z * uDims.y + r.y) * uDims.x + r.x];
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  FccFrame frame = fcc_locate(points[i].xyz);
  FccSamples samples;
  for (int k = 0; k < FCC_STENCIL_SIZE; ++k) samples.v[k] = fcc_block_coefficient(fcc_stencil_site(frame, k));
  FccValueGradient r = fcc_value_gradient(samples, frame);
  results[i] = vec4(r.value, r.gradient);
}
