#include "FccSlabWindow.h"

#include <openvdb/tools/Prune.h>

namespace fcc {

FccSlabWindow::FccSlabWindow(const openvdb::Vec4f& background) : grid_(FccGrid::create(background)) {}

void FccSlabWindow::add(int x, Slab slab) {
  FccTree& tree = grid_->tree();
  Held held{x, {}};
  held.origins.reserve(slab.leaves.size() + slab.tiles.size());
  for (auto& leaf : slab.leaves) {
    held.origins.push_back(leaf->origin());
    tree.addLeaf(leaf.release());
  }
  for (const LeafTile& t : slab.tiles) {
    held.origins.push_back(t.origin);
    tree.addTile(1, t.origin, t.value, t.active);
  }
  held_.push_back(std::move(held));
}

void FccSlabWindow::dropBelow(int x) {
  FccTree& tree = grid_->tree();
  bool dropped = false;
  while (!held_.empty() && held_.front().x < x) {
    // A background tile replaces (and deletes) the leaf or tile.
    for (const openvdb::Coord& origin : held_.front().origins) tree.addTile(1, origin, tree.background(), false);
    held_.pop_front();
    dropped = true;
  }
  // Frees the internal nodes left holding only the background. What the window holds is active
  // (leaves with an active voxel, tiles of uniform active leaves), so nothing else goes.
  if (dropped) openvdb::tools::pruneInactive(tree);
}

}  // namespace fcc
