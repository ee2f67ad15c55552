// The per-brick work of preprocessing (paper 4.3), behind one interface so that the OpenCL kernels
// (kernels/ClBrickKernels) and the C++/TBB reference compute exactly the same thing. The drivers in
// sparse/BrickBounds.h decide which bricks need work (topology, tiles) and assemble the grids; a
// BrickKernels only maps brick coordinates to results.
//
// Brick b (`brick` coordinates) is the VDB leaf of packed voxels [8b, 8b + 8)^3; its results depend on
// the packed voxels [8b - 1, 8b + 9)^3 (a halo of one packed voxel), read from the grid as it is
// (leaves, tiles, the background).
#pragma once

#include <openvdb/openvdb.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "FccGrid.h"

namespace fcc {

class BrickKernels {
 public:
  virtual ~BrickKernels() = default;

  // "reference (C++/TBB)" or "OpenCL: <platform> / <device>".
  virtual std::string describe() const = 0;

  // out[i] = (lo, hi): min and max over the BB-coefficients of the five pieces of every unit cube with
  // corner in [16 b, 16 b + 16)^3 (lattice index space), b = bricks[i].
  virtual void bounds(const FccGrid& coefficients, const std::vector<openvdb::Coord>& bricks,
                      std::vector<openvdb::Vec2f>& out) = 0;

  // out[512 i + n] = the prefiltered coefficients (q_fcc of the stored samples) of packed voxel n of
  // brick bricks[i], n in VDB leaf order (x slowest: n = (x << 6) | (y << 3) | z).
  virtual void prefilter(const FccGrid& samples, const std::vector<openvdb::Coord>& bricks,
                         std::vector<openvdb::Vec4f>& out) = 0;

  // leaves[i] = the coefficient leaf of brick bricks[i] (sparse/PrefilterBricks.h's makeCoefficientLeaf
  // of its prefilter results; null where all are the background); the caller owns them. By default
  // prefilter() in batches, then the leaves; the C++ path builds each leaf as it computes it.
  virtual void prefilterLeaves(const FccGrid& samples, const std::vector<openvdb::Coord>& bricks,
                               std::vector<FccTree::LeafNodeType*>& leaves);

  // Seconds spent in the compute step proper (kernels, without staging and transfers) since the last
  // reset; the reference path counts all of its time.
  double computeSeconds = 0.0;
  // Bricks the drivers (sparse/BrickBounds.h) handed to this object since the last reset.
  uint64_t bricksDone = 0;
};

// The C++/TBB reference: spline::cubeBounds and spline::prefilterAt over a gathered halo block.
std::unique_ptr<BrickKernels> makeReferenceBrickKernels();

}  // namespace fcc
