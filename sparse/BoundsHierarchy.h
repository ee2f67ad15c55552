// The min/max hierarchy of a bounds grid (sparse/BrickBounds.h): brick intervals reduced to the FCC
// tree's internal-node levels and the root, so that a renderer (and `fccvdb info --iso`) can skip
// whole nodes whose interval does not hold the isovalue. Only active bricks (where the spline may
// vary) take part: a constant brick holds no surface.
//
// Levels, in brick coordinates b (bounds-grid voxels): a level-1 node is the FCC tree's lower
// internal node, 16^3 bricks (key b >> 4); a level-2 node is its upper internal node, 32^3 level-1
// nodes (key b >> 9).
#pragma once

#include <openvdb/openvdb.h>

#include <cstdint>
#include <map>

#include "BrickBounds.h"

namespace fcc {

class BoundsHierarchy {
 public:
  static constexpr int kLevel1Log2Bricks = 4;  // FccTree's lower internal node: 16^3 leaves
  static constexpr int kLevel2Log2Bricks = 9;  // upper internal node: 32^3 lower nodes

  using NodeMap = std::map<openvdb::Coord, openvdb::Vec2f>;

  struct Counts {
    uint64_t bricks = 0, nodes1 = 0, nodes2 = 0;
  };

  explicit BoundsHierarchy(const BoundsGrid& bounds);

  // Active bricks (tiles count their bricks) and the internal nodes that hold any.
  const Counts& total() const { return total_; }
  // Those whose interval holds `iso` (lo <= iso <= hi).
  Counts kept(float iso) const;

  // Interval of every node of `level` (1 or 2) holding an active brick, keyed by node coordinate.
  const NodeMap& nodes(int level) const { return level == 1 ? level1_ : level2_; }
  // Hull of all active bricks; lo > hi when there are none.
  const openvdb::Vec2f& root() const { return root_; }

  static bool holds(const openvdb::Vec2f& interval, float iso) { return interval[0] <= iso && iso <= interval[1]; }

 private:
  const BoundsGrid& bounds_;
  NodeMap level1_, level2_;
  openvdb::Vec2f root_;
  Counts total_;
};

}  // namespace fcc
