#version 450 core
// Copies freshly staged slots into the pool (viewer/BrickPool.cpp), any layout. One dispatch a batch:
// work group y is the batch's i-th slot, invocation x a texel of it. Far faster than a GL call a slot
// (glTextureSubImage3D from the unpack buffer: 31 k slots/s on the H200; glCopyNamedBufferSubData:
// 300 k slots/s): each call is a driver round trip.
#define FCC_GLSL 1
#include "FccSpline.h"  // pool.glsl gathers stencils in FccSpline.h's types
#include "pool.glsl"

layout(local_size_x = 64) in;

#if defined(FCC_POOL_SCALAR)
#define FCC_TEXEL float
#else
#define FCC_TEXEL vec4
#endif
layout(std430, binding = 8) readonly buffer Staged { FCC_TEXEL staged[]; };
#if FCC_POOL_LAYOUT >= 2
#if defined(FCC_POOL_SCALAR)
layout(binding = 3, r32f) uniform writeonly image3D uPoolImage;
#else
layout(binding = 3, rgba32f) uniform writeonly image3D uPoolImage;
#endif
#else
// The pool buffer again, writable (pool.glsl reads it at binding 0).
layout(std430, binding = 10) writeonly buffer PoolOut { FCC_TEXEL poolOut[]; };
#endif
layout(std430, binding = 9) readonly buffer Slots { uint batchSlots[]; };

void main() {
  uint texel = gl_GlobalInvocationID.x;
  if (texel >= uint(kSlotTexels)) return;
  uint i = gl_WorkGroupID.y;
  FCC_TEXEL value = staged[i * uint(kSlotTexels) + texel];
  selectSlot(batchSlots[i], ivec3(0));
#if FCC_POOL_LAYOUT >= 2
  ivec3 local = ivec3(int(texel) % kSlotDim, (int(texel) / kSlotDim) % kSlotDim, int(texel) / (kSlotDim * kSlotDim));
  imageStore(uPoolImage, gSlotTexel + local, vec4(value));
#else
  poolOut[gSlotBase + texel] = value;
#endif
}
