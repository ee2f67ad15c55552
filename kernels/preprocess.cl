// OpenCL C: preprocessing bricks (paper 4.3) — the quasi-interpolation prefilter and the per-brick
// min/max of the spline's BB-coefficients — with the math of sparse/FccSpline.h, inlined at build time.
// The host (kernels/ClBrickKernels.cpp) stages a batch of bricks as
//   pool:       the FCC leaves the batch reads, 512 float4 each, in VDB leaf order (x slowest);
//   neighbours: 27 ints per brick, for its neighbour brick (dx,dy,dz) in {-1,0,1}^3 at index
//               (dx+1) + 3 (dy+1) + 9 (dz+1): its pool slot; a neighbour without a leaf (a tile's
//               value or the background) points to a slot filled with that value, one per value;
// and runs one work-group per brick. Results equal the C++ reference (sparse/BrickBounds.cpp) bit for
// bit: the same operations in the same order, and no contraction into fma (below).

// The C++ reference is compiled without fma contraction; OpenCL C allows contraction by default. The
// pragma must precede the spline header, whose functions do the arithmetic.
#pragma OPENCL FP_CONTRACT OFF
#include "FccSpline.h"

#ifndef FCC_GROUP_SIZE
#define FCC_GROUP_SIZE 128
#endif

#define FCC_BRICK_VOXELS 512            // packed voxels per brick (8^3)
#define FCC_HALO_SIDE 10                // a brick and a halo of one packed voxel
#define FCC_HALO_VOXELS 1000
// The halo block in local memory, one plane per channel (so that work items at consecutive halo
// positions read consecutive floats): plane[h], h = (hz * 10 + hy) * 10 + hx for the packed voxel
// h - 1 relative to the brick's first. Padded with zeros so that reads one voxel beyond the block
// (by work items whose results are discarded) stay inside it.
#define FCC_PLANE 1120
#define FCC_DX 1
#define FCC_DY 10
#define FCC_DZ 100
// The first halo position of a brick voxel (packed (0,0,0) at h = (1,1,1)).
#define FCC_FIRST_INNER 111

void fcc_load_halo(__global const float4* pool, __global const int* neighbours, __local float* planes) {
  __global const int* table = neighbours + 27 * get_group_id(0);
  for (int i = get_local_id(0); i < FCC_HALO_VOXELS; i += FCC_GROUP_SIZE) {
    // Packed voxel relative to the brick's first, -1..8 per axis; >> 3 gives its neighbour brick.
    int px = i % FCC_HALO_SIDE - 1, py = (i / FCC_HALO_SIDE) % FCC_HALO_SIDE - 1, pz = i / (FCC_HALO_SIDE * FCC_HALO_SIDE) - 1;
    int slot = table[((px >> 3) + 1) + 3 * ((py >> 3) + 1) + 9 * ((pz >> 3) + 1)];
    float4 v = pool[slot * FCC_BRICK_VOXELS + (((px & 7) << 6) | ((py & 7) << 3) | (pz & 7))];
    planes[i] = v.x;
    planes[FCC_PLANE + i] = v.y;
    planes[2 * FCC_PLANE + i] = v.z;
    planes[3 * FCC_PLANE + i] = v.w;
  }
  for (int i = FCC_HALO_VOXELS + get_local_id(0); i < FCC_PLANE; i += FCC_GROUP_SIZE)
    planes[i] = planes[FCC_PLANE + i] = planes[2 * FCC_PLANE + i] = planes[3 * FCC_PLANE + i] = 0.0f;
  barrier(CLK_LOCAL_MEM_FENCE);
}

// The value at site (2q + parity + e) for the work item at halo position h of packed voxel q: the
// channel and packed offset of parity + e.
float fcc_plane_at(__local const float* planes, int h, int3 siteOffset) {
  int3 d = siteOffset >> 1;
  int channel = ((siteOffset.x & 1) << 1) | (siteOffset.y & 1);
  return planes[channel * FCC_PLANE + h + d.z * FCC_DZ + d.y * FCC_DY + d.x * FCC_DX];
}

// out[512 brick + n] = the prefiltered coefficients of packed voxel n (VDB leaf order).
__kernel __attribute__((reqd_work_group_size(FCC_GROUP_SIZE, 1, 1)))
void fcc_brick_prefilter(__global const float4* pool, __global const int* neighbours,
                         __global float4* out) {
  __local float planes[4 * FCC_PLANE];
  fcc_load_halo(pool, neighbours, planes);
  // Work items over consecutive halo positions (reads at fixed offsets are consecutive); those
  // outside the brick compute and discard.
  for (int h = FCC_FIRST_INNER + get_local_id(0); h < FCC_HALO_VOXELS - FCC_FIRST_INNER; h += FCC_GROUP_SIZE) {
    int3 q = (int3)(h % FCC_HALO_SIDE, (h / FCC_HALO_SIDE) % FCC_HALO_SIDE, h / (FCC_HALO_SIDE * FCC_HALO_SIDE)) - 1;
    float c[4];
#pragma unroll
    for (int channel = 0; channel < 4; ++channel) {
      int px = (channel >> 1) & 1, py = channel & 1;
      int3 parity = (int3)(px, py, px ^ py);
      float neighbourSum = 0.0f;
#pragma unroll
      for (int k = 0; k < 12; ++k) neighbourSum += fcc_plane_at(planes, h, parity + fcc_neighbour_offset(k));
      c[channel] = fcc_prefilter(fcc_plane_at(planes, h, parity), neighbourSum);
    }
    if (all(q >= 0) && all(q <= 7))
      out[get_group_id(0) * FCC_BRICK_VOXELS + ((q.x << 6) | (q.y << 3) | q.z)] = (float4)(c[0], c[1], c[2], c[3]);
  }
}

// Bit s of the result: the cell of packed voxel q holds brick domain points of group s, whose
// positions are 0 (mod a cell) along the axes in s (bit 0: x, 1: y, 2: z) and inside the cell along
// the others. A brick's cells are q in [0, 7]^3, plus q = 8 along an axis for the points on the
// brick's far face.
int fcc_cell_groups(int3 q) {
  if (any(q < 0)) return 0;
  int groups = 0;
  for (int s = 0; s < 8; ++s) {
    bool ok = (q.x <= 7 || ((s & 1) && q.x == 8)) && (q.y <= 7 || ((s & 2) && q.y == 8)) &&
              (q.z <= 7 || ((s & 4) && q.z == 8));
    groups |= (int)ok << s;
  }
  return groups;
}

// FCC_CELL_BB_RANGE (the host replaces this line)

// bounds[brick] = (lo, hi) over the BB-coefficients of the brick's 16^3 unit cubes' pieces, as the
// min/max over the distinct domain points of the closed brick (sparse/BBDomainPoints.h):
// fcc_cell_bb_range is generated from the shared header's tables by the host.
__kernel __attribute__((reqd_work_group_size(FCC_GROUP_SIZE, 1, 1)))
void fcc_brick_bounds(__global const float4* pool, __global const int* neighbours,
                      __global float2* bounds) {
  __local float planes[4 * FCC_PLANE];
  __local float2 partial[FCC_GROUP_SIZE];
  fcc_load_halo(pool, neighbours, planes);
  float lo = INFINITY, hi = -INFINITY;
  for (int h = FCC_FIRST_INNER + get_local_id(0); h < FCC_HALO_VOXELS; h += FCC_GROUP_SIZE) {
    int3 q = (int3)(h % FCC_HALO_SIDE, (h / FCC_HALO_SIDE) % FCC_HALO_SIDE, h / (FCC_HALO_SIDE * FCC_HALO_SIDE)) - 1;
    float2 r = fcc_cell_bb_range(planes, h, fcc_cell_groups(q));
    lo = min(lo, r.x);
    hi = max(hi, r.y);
  }
  int lid = get_local_id(0);
  partial[lid] = (float2)(lo, hi);
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int stride = FCC_GROUP_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride) partial[lid] = (float2)(min(partial[lid].x, partial[lid + stride].x),
                                              max(partial[lid].y, partial[lid + stride].y));
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  // Scaling after the min/max is the same as before it: x * (1/24) rounds monotonically.
  if (lid == 0) bounds[get_group_id(0)] = partial[0] * (1.0f / FCC_CUBIC_DENOM);
}
