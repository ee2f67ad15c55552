// A few consecutive x-slabs of FCC blocks (leaves one block thick in x, of any y and z) held in one
// grid, for per-brick work that reads a brick's 26 neighbours (bounds, the prefilter): the streamed
// build (StreamedBuild.h) keeps only the slabs around the one it works on. Slabs along x follow the
// order in which a VDB tree lays out its leaves.
#pragma once

#include <deque>
#include <memory>
#include <vector>

#include "FccGrid.h"

namespace fcc {

class FccSlabWindow {
 public:
  using Leaf = FccTree::LeafNodeType;

  // A leaf-sized region of one value: a uniform leaf, which the builder's prune makes a tile.
  struct LeafTile {
    openvdb::Coord origin;  // packed voxel, a multiple of 8
    openvdb::Vec4f value;
    bool active = false;
  };
  struct Slab {
    std::vector<std::unique_ptr<Leaf>> leaves;
    std::vector<LeafTile> tiles;
  };

  explicit FccSlabWindow(const openvdb::Vec4f& background);

  // The slabs held, everything else the background (no metadata, identity transform).
  const FccGrid& grid() const { return *grid_; }

  // Adds the leaves (the window takes them) and tiles of slab `x`.
  void add(int x, Slab slab);
  // Removes the slabs with an x below `x`.
  void dropBelow(int x);

 private:
  FccGrid::Ptr grid_;
  struct Held {
    int x;
    std::vector<openvdb::Coord> origins;  // its leaves' and tiles' origins
  };
  std::deque<Held> held_;
};

}  // namespace fcc
