// OpenCL C: preprocessing bricks (paper 4.3) — the quasi-interpolation prefilter and the per-brick
// min/max of the spline's BB-coefficients — with the math of sparse/FccSpline.h, inlined at build time.
// The host (kernels/ClBrickKernels.cpp) stages a batch of bricks as
//   pool:       the FCC leaves the batch reads, 512 float4 each, in VDB leaf order (x slowest);
//   neighbours: 27 ints per brick, for its neighbour brick (dx,dy,dz) in {-1,0,1}^3 at index
//               (dx+1) + 3 (dy+1) + 9 (dz+1): a pool slot (>= 0), or -1 - k for constants[k] (a tile's
//               value or the background) where the neighbour brick holds no leaf;
// and runs one work-group per brick. Results equal the C++ reference (sparse/BrickBounds.cpp) bit for
// bit: the same operations in the same order, and no contraction into fma (below).

// The C++ reference is compiled without fma contraction; OpenCL C allows contraction by default. The
// pragma must precede the spline header, whose functions do the arithmetic.
#pragma OPENCL FP_CONTRACT OFF
#include "FccSpline.h"

#ifndef FCC_GROUP_SIZE
#define FCC_GROUP_SIZE 128
#endif

#define FCC_BRICK_DIM 8                 // packed voxels per brick side
#define FCC_BRICK_VOXELS 512
#define FCC_HALO_SIDE 10                // a brick and a halo of one packed voxel
#define FCC_HALO_VOXELS 1000
#define FCC_BRICK_SITES 16              // lattice index units per brick side: 16^3 unit cubes

// Packed voxels [8b - 1, 8b + 9)^3 of the group's brick into block[(pz * 10 + py) * 10 + px].
void fcc_load_halo(__global const float4* pool, __global const int* neighbours, __global const float4* constants,
                   __local float4* block) {
  __global const int* table = neighbours + 27 * get_group_id(0);
  for (int i = get_local_id(0); i < FCC_HALO_VOXELS; i += FCC_GROUP_SIZE) {
    // Packed voxel relative to the brick's first, -1..8 per axis; >> 3 gives its neighbour brick.
    int px = i % FCC_HALO_SIDE - 1, py = (i / FCC_HALO_SIDE) % FCC_HALO_SIDE - 1, pz = i / (FCC_HALO_SIDE * FCC_HALO_SIDE) - 1;
    int slot = table[((px >> 3) + 1) + 3 * ((py >> 3) + 1) + 9 * ((pz >> 3) + 1)];
    block[i] = slot >= 0 ? pool[slot * FCC_BRICK_VOXELS + (((px & 7) << 6) | ((py & 7) << 3) | (pz & 7))]
                         : constants[-1 - slot];
  }
  barrier(CLK_LOCAL_MEM_FENCE);
}

// The value at FCC site r, in sites relative to the brick's first site minus 2 (the halo): 0..19.
float fcc_halo_at(__local const float4* block, int3 r) {
  int3 p = r >> 1;
  __local const float* v = (__local const float*)(block + (p.z * FCC_HALO_SIDE + p.y) * FCC_HALO_SIDE + p.x);
  return v[((r.x & 1) << 1) | (r.y & 1)];
}

// out[512 brick + n] = the prefiltered coefficients of packed voxel n (VDB leaf order).
__kernel __attribute__((reqd_work_group_size(FCC_GROUP_SIZE, 1, 1)))
void fcc_brick_prefilter(__global const float4* pool, __global const int* neighbours,
                         __global const float4* constants, __global float4* out) {
  __local float4 block[FCC_HALO_VOXELS];
  fcc_load_halo(pool, neighbours, constants, block);
  for (int n = get_local_id(0); n < FCC_BRICK_VOXELS; n += FCC_GROUP_SIZE) {
    int3 p = (int3)(n >> 6, (n >> 3) & 7, n & 7);
    float c[4];
    for (int channel = 0; channel < 4; ++channel) {
      int px = (channel >> 1) & 1, py = channel & 1;
      int3 site = 2 * p + (int3)(px, py, px ^ py) + 2;
      float neighbourSum = 0.0f;
      for (int k = 0; k < 12; ++k) neighbourSum += fcc_halo_at(block, site + fcc_neighbour_offset(k));
      c[channel] = fcc_prefilter(fcc_halo_at(block, site), neighbourSum);
    }
    out[get_group_id(0) * FCC_BRICK_VOXELS + n] = (float4)(c[0], c[1], c[2], c[3]);
  }
}

// bounds[brick] = (lo, hi) over the BB-coefficients of the five pieces of the brick's 16^3 unit cubes.
__kernel __attribute__((reqd_work_group_size(FCC_GROUP_SIZE, 1, 1)))
void fcc_brick_bounds(__global const float4* pool, __global const int* neighbours,
                      __global const float4* constants, __global float2* bounds) {
  __local float4 block[FCC_HALO_VOXELS];
  __local float2 partial[FCC_GROUP_SIZE];
  fcc_load_halo(pool, neighbours, constants, block);
  float lo = INFINITY, hi = -INFINITY;
  const int cubes = FCC_BRICK_SITES * FCC_BRICK_SITES * FCC_BRICK_SITES;
  for (int i = get_local_id(0); i < cubes; i += FCC_GROUP_SIZE) {
    // Cube corners relative to the brick's first site: even there iff even in the lattice.
    int3 corner = (int3)(i & 15, (i >> 4) & 15, i >> 8);
    for (int piece = 0; piece < 5; ++piece) {
      FccFrame frame = fcc_locate(fcc_piece_centroid(corner, piece));
      FccSamples s;
      for (int k = 0; k < FCC_STENCIL_SIZE; ++k) s.v[k] = fcc_halo_at(block, fcc_stencil_site(frame, k) + 2);
      FccRange r = fcc_cubic_range(fcc_cubic(s, frame.type));
      lo = min(lo, r.lo);
      hi = max(hi, r.hi);
    }
  }
  int lid = get_local_id(0);
  partial[lid] = (float2)(lo, hi);
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int stride = FCC_GROUP_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride) partial[lid] = (float2)(min(partial[lid].x, partial[lid + stride].x),
                                              max(partial[lid].y, partial[lid + stride].y));
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) bounds[get_group_id(0)] = partial[0];
}
