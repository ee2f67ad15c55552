#version 450 core
// Bounds per packed voxel of freshly uploaded pool slots, so rays skip the cells of a resident brick
// that cannot hold the isosurface. M_fcc is non-negative and a partition of unity, so the spline on
// the voxel's eight unit cells lies between the least and the greatest coefficient their stencils
// reach (sites [2v - 1, 2v + 3), all in packed voxels v - 1 .. v + 1). Looser than the BB-coefficient
// bounds of each piece, which the raycaster checks next, but 27 reads instead of 40 cubics: the pass
// must stay cheap on a CPU rasteriser too. One invocation per packed voxel; work group y indexes
// the uploaded slots.
#define FCC_GLSL 1
#include "ReconIds.h"
#include "FccSpline.h"
#include "pool.glsl"

#ifndef FCC_RECON
#define FCC_RECON FCC_RECON_BOXSPLINE
#endif

layout(local_size_x = 64) in;

layout(std430, binding = 5) writeonly buffer SlotUse { uint slotLastUse[]; };
layout(std430, binding = 6) writeonly buffer SlotBounds { vec2 slotBounds[]; };
layout(std430, binding = 7) readonly buffer Uploaded { uint uploadedSlots[]; };
// The pass in which the slots were uploaded: they count as used in it, so the next assignment does
// not evict them first (one write a slot here instead of a buffer update a slot on the host).
uniform uint uPass;

void markUsed(uint slot) {
  if (gl_GlobalInvocationID.x == 0u) slotLastUse[slot] = uPass;
}


#if FCC_RECON == FCC_RECON_TRILINEAR || FCC_RECON == FCC_RECON_TRICUBIC || FCC_RECON == FCC_RECON_TYPE6
// A Cartesian slot (20^3 grid points, viewer/CartesianBrickSource.h): the reconstructions are convex
// combinations of the coefficients their stencils read, so the voxel's 8 cells (2v .. 2v + 1 from the
// brick's corner) lie within the hull of the points [2v, 2v + 3)^3 (trilinear) or [2v - 1, 2v + 4)^3
// (tricubic; type 6: the cubes of the corners 2v .. 2v + 2, their samples 2v - 1 .. 2v + 3). The
// raycaster then checks each cell's own corners, Bezier or BB coefficients.
void main() {
  uint voxel = gl_GlobalInvocationID.x;
  if (voxel >= uint(kSlotVoxels)) return;
  uint slot = uploadedSlots[gl_WorkGroupID.y];
  markUsed(slot);
  selectSlot(slot, ivec3(0));  // the brick taken at the origin: a slot's values do not depend on it
  ivec3 v = ivec3(int(voxel) & 7, (int(voxel) >> 3) & 7, int(voxel) >> 6);
#if FCC_RECON == FCC_RECON_TRILINEAR
  ivec3 lo = 2 * v, hi = 2 * v + 3;
#else
  ivec3 lo = 2 * v - 1, hi = 2 * v + 4;
#endif
  float mn = 1.0 / 0.0, mx = -1.0 / 0.0;
  for (int z = lo.z; z < hi.z; ++z)
    for (int y = lo.y; y < hi.y; ++y)
      for (int x = lo.x; x < hi.x; ++x) {
        float c = coefficientAt(ivec3(x, y, z));
        mn = min(mn, c);
        mx = max(mx, c);
      }
  slotBounds[slot * uint(kSlotVoxels) + voxel] = vec2(mn, mx);
}
#elif defined(FCC_SLOT_BCC)
// A BCC slot (viewer/BccBrickSource.h): every BCC scheme is a convex combination of sites within 3 index
// units of the point (the sheared cells reach 3 along their sheared axes, the others 2), so the voxel's
// 8 cells [2v, 2v + 2]^3 lie within the hull of the sites in [2v - 3, 2v + 5]^3: the primary coset's
// voxels m in [v - 1, v + 2] (sites 2m) and the secondary's in [v - 2, v + 2] (sites 2m + 1).
void main() {
  uint voxel = gl_GlobalInvocationID.x;
  if (voxel >= uint(kSlotVoxels)) return;
  uint slot = uploadedSlots[gl_WorkGroupID.y];
  markUsed(slot);
  selectSlot(slot, ivec3(0));  // the brick taken at the origin: a slot's values do not depend on it
  ivec3 v = ivec3(int(voxel) & 7, (int(voxel) >> 3) & 7, int(voxel) >> 6);
  float mn = 1.0 / 0.0, mx = -1.0 / 0.0;
  for (int coset = 0; coset < 2; ++coset)
    for (int z = v.z - 2 + (1 - coset); z <= v.z + 2; ++z)
      for (int y = v.y - 2 + (1 - coset); y <= v.y + 2; ++y)
        for (int x = v.x - 2 + (1 - coset); x <= v.x + 2; ++x) {
          float c = coefficientAt(2 * ivec3(x, y, z) + coset);
          mn = min(mn, c);
          mx = max(mx, c);
        }
  slotBounds[slot * uint(kSlotVoxels) + voxel] = vec2(mn, mx);
}
#elif defined(FCC_SLOT_BOUNDS_BB)
// On a GPU the tighter bound costs nothing worth saving: min/max over the BB-coefficients of the 40
// pieces of the voxel's 8 cells (what the raycaster would otherwise find piece by piece).
void main() {
  uint voxel = gl_GlobalInvocationID.x;
  if (voxel >= uint(kSlotVoxels)) return;
  uint slot = uploadedSlots[gl_WorkGroupID.y];
  markUsed(slot);
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
  markUsed(slot);
  selectSlot(slot, ivec3(0));  // as above: the brick taken at the origin
  ivec3 v = ivec3(int(voxel) & 7, (int(voxel) >> 3) & 7, int(voxel) >> 6);
  // The FCC sites of packed voxels v - 1 .. v + 1: sites [2v - 2, 2v + 4)^3 with an even coordinate sum.
  float lo = 1.0 / 0.0, hi = -1.0 / 0.0;
  for (int z = 2 * v.z - 2; z < 2 * v.z + 4; ++z)
    for (int y = 2 * v.y - 2; y < 2 * v.y + 4; ++y)
      for (int x = 2 * v.x - 2 + ((y + z) & 1); x < 2 * v.x + 4; x += 2) {
        float c = coefficientAt(ivec3(x, y, z));
        lo = min(lo, c);
        hi = max(hi, c);
      }
  slotBounds[slot * uint(kSlotVoxels) + voxel] = vec2(lo, hi);
}
#endif
