// OpenCL C: the FCC box spline (sparse/FccSpline.h) over a dense coefficient block.
// The header below is inlined at build time by fcc_embed (tools/cmake/Embed.cmake).
#include "FccSpline.h"

// The coefficient block stores every integer point of the box [origin, origin + dims) with x fastest:
// c[(r.z * dims.y + r.y) * dims.x + r.x], r = site - origin (only the FCC sites, even x+y+z, are
// read). Sites outside the box have the coefficient `background`.
float fcc_block_coefficient(__global const float* coefficients, int4 origin, int4 dims, float background,
                            int3 site) {
  int3 r = site - origin.xyz;
  if (any(r < (int3)(0)) || any(r >= dims.xyz)) return background;
  return coefficients[(r.z * dims.y + r.y) * dims.x + r.x];
}

// results[i] = (s, ds/dx, ds/dy, ds/dz) at points[i].xyz (lattice index space; .w is ignored).
__kernel void fcc_spline_eval(__global const float4* points, uint count, __global const float* coefficients,
                              int4 origin, int4 dims, float background, __global float4* results) {
  uint i = get_global_id(0);
  if (i >= count) return;
  FccFrame frame = fcc_locate(points[i].xyz);
  FccSamples samples;
  for (int k = 0; k < FCC_STENCIL_SIZE; ++k)
    samples.v[k] = fcc_block_coefficient(coefficients, origin, dims, background, fcc_stencil_site(frame, k));
  FccValueGradient r = fcc_value_gradient(samples, frame);
  results[i] = (float4)(r.value, r.gradient);
}
