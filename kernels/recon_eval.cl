// OpenCL C: every reconstruction of the layer (sparse/ReconDispatch.h) over a dense block of site
// values, for the test of the dialects' agreement; the same as shaders/recon_eval.comp. Headers are
// inlined at build time by fcc_embed.
#define FCC_SITE_PARAMS , __global const float *values, int4 origin, int4 dims, float background
#define FCC_SITE_ARGS , values, origin, dims, background
#define FCC_SITE_VALUE(ijk) fcc_block_value(values, origin, dims, background, ijk)

// Every integer point of [origin, origin + dims), x fastest; outside: the background.
float fcc_block_value(__global const float* values, int4 origin, int4 dims, float background, int3 site) {
  int3 r = site - origin.xyz;
  if (any(r < (int3)(0)) || any(r >= dims.xyz)) return background;
  return values[(r.z * dims.y + r.y) * dims.x + r.x];
}

#include "ReconDispatch.h"

// results[i] = (s, ds/dx, ds/dy, ds/dz) at points[i].xyz of reconstruction `id` (params: stack axis, shears).
__kernel void fcc_recon_eval(__global const float4* points, uint count, int id, int4 params,
                             __global const float* values, int4 origin, int4 dims, float background,
                             __global float4* results) {
  uint i = get_global_id(0);
  if (i >= count) return;
  FccValueGradient r = fcc_recon_value_gradient(id, points[i].xyz, params.xyz, values, origin, dims, background);
  results[i] = (float4)(r.value, r.gradient);
}

// results[i] = the first root (or -1) on the segment points[2i] -> points[2i + 1] at iso points[2i].w.
__kernel void fcc_recon_segment_roots(__global const float4* points, uint count, int id, int4 params,
                                      __global const float* values, int4 origin, int4 dims, float background,
                                      __global float4* results) {
  uint i = get_global_id(0);
  if (i >= count) return;
  float u = fcc_recon_segment_root(id, points[2 * i].xyz, points[2 * i + 1].xyz, points[2 * i].w, params.xyz, values,
                                   origin, dims, background);
  results[i] = (float4)(u, 0.0f, 0.0f, 0.0f);
}
