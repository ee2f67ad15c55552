// The brick pool as the raycaster and the slot-bounds pass read it. Slot s holds the packed voxels
// [8b - 1, 8b + 9)^3 of its brick b (the brick and the one-voxel halo its cells' stencils reach), in
// one of four layouts chosen by FCC_POOL_LAYOUT (viewer/BrickPool.h defines it; for the texture layouts
// BrickPool::setUniforms sets uPoolGrid, the slots per row and per layer of the 3D texture: a uniform,
// not a define, so that the compiled shaders do not depend on the pool's size and the driver's shader
// cache serves every budget):
//   0 ssbo-vec4       SSBO of vec4, 10^3 per slot, x fastest; the site's channel selected by parity
//   1 ssbo-scalar     SSBO of float, the one-channel embedding: 20^3 sites [16b - 2, 16b + 18)^3 per
//                     slot (non-FCC sites unused), read at the site itself, no channel selection
//   2 texture-vec4    RGBA32F 3D texture, a 10^3 block per slot, texelFetch, channel by parity
//   3 texture-scalar  R32F 3D texture, a 20^3 block of sites per slot, texelFetch
// A Cartesian grid's slot (viewer/CartesianBrickSource.h) holds its 20^3 grid points [16b - 2, 16b + 18)^3
// in the same place, every one used: the scalar layouts only. A BCC slot (FCC_SLOT_BCC,
// viewer/BccBrickSource.h) holds the two cosets' 12^3 voxels [8b - 2, 8b + 10)^3 one after the other in
// the first 2 * 12^3 of its 20^3 floats (x fastest, as a texture's texels run); site x is coset x & 1's
// voxel x >> 1.
// Per slot and packed voxel (2^3 unit cells), slotBounds holds bounds of the reconstruction on those 8
// cells (for FCC the min and max BB-coefficient of their 40 pieces, or the hull of the coefficients
// their stencils read), computed on upload by shaders/slot_bounds.comp.
#ifndef FCC_POOL_LAYOUT
#define FCC_POOL_LAYOUT 0
#endif

#if FCC_POOL_LAYOUT == 1 || FCC_POOL_LAYOUT == 3
const int kSlotDim = 20;   // sites per side
#define FCC_POOL_SCALAR 1
#else
const int kSlotDim = 10;   // packed voxels per side
#endif
const int kSlotTexels = kSlotDim * kSlotDim * kSlotDim;
const int kSlotVoxels = 512;  // packed voxels of a brick: one bounds entry each

#if FCC_POOL_LAYOUT == 0
layout(std430, binding = 0) readonly buffer Pool { vec4 poolTexels[]; };
#elif FCC_POOL_LAYOUT == 1
layout(std430, binding = 0) readonly buffer Pool { float poolSites[]; };
#else
layout(binding = 3) uniform sampler3D uPoolTexture;
uniform ivec2 uPoolGrid;
#endif

// The slot that coefficientAt reads, and the lattice site at its first element: set before gathering.
uint gSlotBase;      // SSBO layouts: index of the slot's first element
ivec3 gSlotTexel;    // texture layouts: texel of the slot's first element
ivec3 gSlotOrigin;   // the packed voxel (vec4 layouts) or site (scalar layouts) of the first element
ivec3 gSlotShift;    // FCC and CC texture layouts: gSlotTexel - gSlotOrigin, a site's (packed voxel's) texel

void selectSlot(uint slot, ivec3 brick) {
  gSlotBase = slot * uint(kSlotTexels);
#if FCC_POOL_LAYOUT >= 2
  int s = int(slot);
  gSlotTexel = ivec3(s % uPoolGrid.x, (s / uPoolGrid.x) % uPoolGrid.y, s / (uPoolGrid.x * uPoolGrid.y)) * kSlotDim;
#endif
#if defined(FCC_SLOT_BCC)
  gSlotOrigin = brick * 8 - 2;
#elif defined(FCC_POOL_SCALAR)
  gSlotOrigin = brick * 16 - 2;
#else
  gSlotOrigin = brick * 8 - 1;
#endif
#if FCC_POOL_LAYOUT >= 2
  gSlotShift = gSlotTexel - gSlotOrigin;
#endif
}

#if !defined(FCC_POOL_SCALAR)
// Select the channel ((x & 1) << 1) | (y & 1) without a dynamic vector index (which some compilers
// spill to local memory).
float channelOf(vec4 t, ivec3 ijk) {
  vec2 xy = (ijk.x & 1) != 0 ? t.zw : t.xy;
  return (ijk.y & 1) != 0 ? xy.y : xy.x;
}
#endif

#if defined(FCC_SLOT_BCC)
const int kBccDim = 12;  // coset voxels per side (viewer/BrickSource.h, kBccSlotDim)
float coefficientAt(ivec3 ijk) {
  ivec3 local = (ijk >> 1) - gSlotOrigin;  // arithmetic shift: floor(x / 2) for negative x too
  int i = (ijk.x & 1) * (kBccDim * kBccDim * kBccDim) + (local.z * kBccDim + local.y) * kBccDim + local.x;
#if FCC_POOL_LAYOUT == 1
  return poolSites[gSlotBase + uint(i)];
#else
  return texelFetch(uPoolTexture, gSlotTexel + ivec3(i % kSlotDim, (i / kSlotDim) % kSlotDim, i / (kSlotDim * kSlotDim)), 0).r;
#endif
}
#else
float coefficientAt(ivec3 ijk) {
#if FCC_POOL_LAYOUT == 0
  ivec3 local = (ijk >> 1) - gSlotOrigin;
  return channelOf(poolTexels[gSlotBase + uint((local.z * kSlotDim + local.y) * kSlotDim + local.x)], ijk);
#elif FCC_POOL_LAYOUT == 1
  ivec3 local = ijk - gSlotOrigin;
  return poolSites[gSlotBase + uint((local.z * kSlotDim + local.y) * kSlotDim + local.x)];
#elif FCC_POOL_LAYOUT == 2
  return channelOf(texelFetch(uPoolTexture, (ijk >> 1) + gSlotShift, 0), ijk);
#else
  return texelFetch(uPoolTexture, ijk + gSlotShift, 0).r;
#endif
}
#endif

// Written out rather than looped: constant indices keep the 19 values in registers whatever the
// compiler decides about unrolling (a dynamically indexed array may live in local memory).
#define FCC_GATHER(i) s.v[i] = coefficientAt(fcc_stencil_site(frame, i))
FccSamples gatherStencil(FccFrame frame) {
  FccSamples s;
  FCC_GATHER(0); FCC_GATHER(1); FCC_GATHER(2); FCC_GATHER(3); FCC_GATHER(4); FCC_GATHER(5); FCC_GATHER(6);
  FCC_GATHER(7); FCC_GATHER(8); FCC_GATHER(9); FCC_GATHER(10); FCC_GATHER(11); FCC_GATHER(12); FCC_GATHER(13);
  FCC_GATHER(14); FCC_GATHER(15); FCC_GATHER(16); FCC_GATHER(17); FCC_GATHER(18);
  return s;
}
#undef FCC_GATHER
