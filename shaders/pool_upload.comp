#version 450 core
// Copies freshly staged slots into a texture pool (viewer/BrickPool.cpp; the SSBO layouts copy with
// glCopyNamedBufferSubData instead). One dispatch a batch: work group y is the batch's i-th slot,
// invocation x a texel of it. Far faster than a glTextureSubImage3D a slot from the unpack buffer
// (31 k slots/s on the H200: each call is a driver round trip).
#define FCC_GLSL 1
#include "FccSpline.h"  // pool.glsl gathers stencils in FccSpline.h's types
#include "pool.glsl"

layout(local_size_x = 64) in;

#if defined(FCC_POOL_SCALAR)
layout(binding = 3, r32f) uniform writeonly image3D uPoolImage;
layout(std430, binding = 8) readonly buffer Staged { float staged[]; };
#else
layout(binding = 3, rgba32f) uniform writeonly image3D uPoolImage;
layout(std430, binding = 8) readonly buffer Staged { vec4 staged[]; };
#endif
layout(std430, binding = 9) readonly buffer Slots { uint batchSlots[]; };

void main() {
  uint texel = gl_GlobalInvocationID.x;
  if (texel >= uint(kSlotTexels)) return;
  uint i = gl_WorkGroupID.y;
  selectSlot(batchSlots[i], ivec3(0));
  ivec3 local = ivec3(int(texel) % kSlotDim, (int(texel) / kSlotDim) % kSlotDim, int(texel) / (kSlotDim * kSlotDim));
#if defined(FCC_POOL_SCALAR)
  imageStore(uPoolImage, gSlotTexel + local, vec4(staged[i * uint(kSlotTexels) + texel]));
#else
  imageStore(uPoolImage, gSlotTexel + local, staged[i * uint(kSlotTexels) + texel]);
#endif
}
