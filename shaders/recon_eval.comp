#version 450 core
// GLSL compute: every reconstruction of the layer (sparse/ReconDispatch.h) over a dense block of site
// values, for the test of the dialects' agreement; the same as kernels/recon_eval.cl. Headers are
// inlined at build time by fcc_embed, after the #version line (which must stay first).
#define FCC_GLSL 1
#define FCC_SITE_PARAMS
#define FCC_SITE_ARGS
#define FCC_SITE_VALUE(ijk) fcc_block_value(ijk)

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
// Every integer point of [uOrigin, uOrigin + uDims), x fastest; outside: uBackground.
layout(std430, binding = 1) readonly buffer Values { float values[]; };
layout(std430, binding = 2) writeonly buffer Results { vec4 results[]; };

uniform ivec4 uOrigin;
uniform ivec4 uDims;
uniform float uBackground;
uniform uint uCount;
uniform int uId;
uniform ivec3 uParams;  // stack axis, shear signs
uniform int uMode;      // 0: (value, gradient) at points[i]; 1: results[i].x = the first root on the
                        // segment points[2i] -> points[2i + 1] at iso points[2i].w

float fcc_block_value(ivec3 site) {
  ivec3 r = site - uOrigin.xyz;
  if (any(lessThan(r, ivec3(0))) || any(greaterThanEqual(r, uDims.xyz))) return uBackground;
  return values[(r.z * uDims.y + r.y) * uDims.x + r.x];
}

#include "ReconDispatch.h"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  if (uMode == 1) {
    results[i] = vec4(fcc_recon_segment_root(uId, points[2 * i].xyz, points[2 * i + 1].xyz, points[2 * i].w, uParams), 0.0, 0.0, 0.0);
    return;
  }
  FccValueGradient r = fcc_recon_value_gradient(uId, points[i].xyz, uParams);
  results[i] = vec4(r.value, r.gradient);
}
