// The brick pool as the raycaster and the slot-bounds pass read it: slot s holds packed voxels
// [8b - 1, 8b + 9)^3 of its brick b (the brick and the one-voxel halo its cells' stencils reach),
// x fastest, kSlotTexels vec4 per slot (viewer/Raycaster.cpp uploads io::assembleHaloBlock's layout).
// Per slot and packed voxel, slotBounds holds the min and max BB-coefficient of the 8 unit cells of
// that voxel (40 pieces), computed on upload by shaders/slot_bounds.comp.
layout(std430, binding = 0) readonly buffer Pool { vec4 poolTexels[]; };

const int kSlotDim = 10;
const int kSlotTexels = kSlotDim * kSlotDim * kSlotDim;
const int kSlotVoxels = 512;  // packed voxels of a brick: one bounds entry each

// The slot and brick that coefficientAt reads: set before gathering.
uint gSlotBase;
ivec3 gSlotPackedOrigin;

void selectSlot(uint slot, ivec3 brick) {
  gSlotBase = slot * uint(kSlotTexels);
  gSlotPackedOrigin = brick * 8 - 1;
}

float coefficientAt(ivec3 ijk) {
  ivec3 local = (ijk >> 1) - gSlotPackedOrigin;
  vec4 t = poolTexels[gSlotBase + uint((local.z * kSlotDim + local.y) * kSlotDim + local.x)];
  // Select the channel ((x & 1) << 1) | (y & 1) without a dynamic vector index (which some
  // compilers spill to local memory).
  vec2 xy = (ijk.x & 1) != 0 ? t.zw : t.xy;
  return (ijk.y & 1) != 0 ? xy.y : xy.x;
}

FccSamples gatherStencil(FccFrame frame) {
  FccSamples s;
  for (int i = 0; i < FCC_STENCIL_SIZE; ++i) s.v[i] = coefficientAt(fcc_stencil_site(frame, i));
  return s;
}
