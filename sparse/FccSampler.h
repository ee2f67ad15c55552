// Point evaluation of the spline stored in an FCC grid, on the CPU: the reference the GPU paths and
// `fccvdb probe` use. One sampler per thread (it holds a VDB value accessor).
#pragma once

#include "FccGrid.h"
#include "Lattice.h"
#include "Spline.h"

namespace fcc {

class FccSampler {
 public:
  // `storesSamples`: the grid holds raw samples V (converted with --no-prefilter), so the coefficients
  // are prefiltered on the fly; otherwise it holds the coefficients c.
  FccSampler(const FccGrid& grid, bool storesSamples)
      : grid_(grid), accessor_(grid.getConstAccessor()), storesSamples_(storesSamples) {}

  // Stored value at FCC site ijk (the background where nothing is stored).
  float stored(const glm::ivec3& ijk) const {
    const glm::ivec3 v = packedVoxelOfSite(ijk);
    return accessor_.getValue(openvdb::Coord(v.x, v.y, v.z))[channelOfSite(ijk)];
  }

  float coefficient(const glm::ivec3& ijk) const {
    if (!storesSamples_) return stored(ijk);
    return spline::prefilterAt(ijk, [this](const glm::ivec3& s) { return stored(s); });
  }

  // Value and gradient at a position in the lattice's index space.
  spline::FccValueGradient evaluateIndex(const glm::vec3& xyz) const {
    return spline::evaluateWithGradient(xyz, [this](const glm::ivec3& ijk) { return coefficient(ijk); });
  }

  // Value and gradient (with respect to world coordinates) at a world position.
  spline::FccValueGradient evaluateWorld(const openvdb::Vec3d& pWorld) const {
    const openvdb::Vec3d xyz = grid_.transform().worldToIndex(pWorld);
    spline::FccValueGradient r = evaluateIndex(glm::vec3(float(xyz.x()), float(xyz.y()), float(xyz.z())));
    // d/dworld = (d index / d world)^T d/dindex: the map's inverse Jacobian transposed.
    const openvdb::Vec3d gWorld = grid_.transform().baseMap()->applyIJT(
        openvdb::Vec3d(r.gradient.x, r.gradient.y, r.gradient.z), xyz);
    r.gradient = glm::vec3(float(gWorld.x()), float(gWorld.y()), float(gWorld.z()));
    return r;
  }

 private:
  const FccGrid& grid_;
  FccGrid::ConstAccessor accessor_;
  bool storesSamples_;
};

}  // namespace fcc
