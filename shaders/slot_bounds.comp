#version 450 core
// Bounds per packed voxel of freshly uploaded pool slots, so rays skip the cells of a resident brick
// that cannot hold the isosurface. M_fcc is non-negative and a partition of unity, so the spline on
// the voxel's eight unit cells lies between the least and the greatest coefficient their stencils
// reach (sites [2v - 1, 2v + 3), all in packed voxels v - 1 .. v + 1). Looser than the BB-coefficient
// bounds of each piece, which the raycaster checks next, but 27 reads instead of 40 cubics: the pass
// must stay cheap on a CPU rasteriser too. One invocation per packed voxel; work group y indexes
// the uploaded slots.
#define FCC_GLSL 1
#include "FccSpline.h"
#include "pool.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = 6) writeonly buffer SlotBounds { vec2 slotBounds[]; };
layout(std430, binding = 7) readonly buffer Uploaded { uint uploadedSlots[]; };

#if defined(FCC_SLOT_BOUNDS_BB)
// On a GPU the tighter bound costs nothing worth saving: min/max over the BB-coefficients of the 40
// pieces of the voxel's 8 cells (what the raycaster would otherwise find piece by piece).
void main() {
  uint voxel = gl_GlobalInvocationID.x;
  if (voxel >= uint(kSlotVoxels)) return;
  uint slot = uploadedSlots[gl_WorkGroupID.y];
  // A slot's contents do not depend on where its brick is (shifts by 16 keep site parity and
  // channels), so the brick is taken at the origin.
  selectSlot(slot, ivec3(0));
  ivec3 packedVoxel = ivec3(int(voxel) & 7, (int(voxel) >> 3) & 7, int(voxel) >> 6);
  float lo = 1.0 / 0.0, hi = -1.0 / 0.0;
  for (int c = 0; c < 8; ++c) {
    ivec3 cell = 2 * packedVoxel + ivec3(c & 1, (c >> 1) & 1, c >> 2);
    for (int piece = 0; piece < 5; ++piece) {
      FccFrame frame = fcc_locate(fcc_piece_centroid(cell, piece));
      FccRange r = fcc_cubic_range(fcc_cubic(gatherStencil(frame), frame.type));
      lo = min(lo, r.lo);
      hi = max(hi, r.hi);
    }
  }
  slotBounds[slot * uint(kSlotVoxels) + voxel] = vec2(lo, hi);
}
#else
void main() {
  uint voxel = gl_GlobalInvocationID.x;
  if (voxel >= uint(kSlotVoxels)) return;
  uint slot = uploadedSlots[gl_WorkGroupID.y];
  uint base = slot * uint(kSlotTexels);
  // Slot texel (1, 1, 1) is the brick's first packed voxel (pool.glsl).
  ivec3 v = ivec3(int(voxel) & 7, (int(voxel) >> 3) & 7, int(voxel) >> 6) + 1;
  vec4 lo = vec4(1.0 / 0.0), hi = vec4(-1.0 / 0.0);
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 t = v + ivec3(dx, dy, dz);
        vec4 c = poolTexels[base + uint((t.z * kSlotDim + t.y) * kSlotDim + t.x)];
        lo = min(lo, c);
        hi = max(hi, c);
      }
  slotBounds[slot * uint(kSlotVoxels) + voxel] =
      vec2(min(min(lo.x, lo.y), min(lo.z, lo.w)), max(max(hi.x, hi.y), max(hi.z, hi.w)));
}
#endif
