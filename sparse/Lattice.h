// The four-channel packing of the FCC lattice (paper 4.4): FCC site j (integer point with an even
// coordinate sum, in the lattice's index space) lives in packed voxel j >> 1, channel
// ((j.x & 1) << 1) | (j.y & 1). The four sites of packed voxel v are 2v, 2v + (0,1,1), 2v + (1,0,1)
// and 2v + (1,1,0), in channel order.
#pragma once

#include <glm/glm.hpp>

namespace fcc {

inline glm::ivec3 packedVoxelOfSite(const glm::ivec3& ijk) { return ijk >> 1; }

inline int channelOfSite(const glm::ivec3& ijk) { return ((ijk.x & 1) << 1) | (ijk.y & 1); }

inline glm::ivec3 siteOfChannel(const glm::ivec3& packedVoxel, int channel) {
  // channel bits: x parity in bit 1, y parity in bit 0; z parity completes an even sum.
  const int px = (channel >> 1) & 1, py = channel & 1;
  return 2 * packedVoxel + glm::ivec3(px, py, px ^ py);
}

}  // namespace fcc
