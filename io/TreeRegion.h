// What a VDB tree holds inside a box of its index space, read from its nodes and tiles alone (never a
// leaf's values, so it works on topology-only trees whose leaves have no buffers): the leaves that
// meet the box, and the constant regions (tiles, and the background where the root has no entry).
// One pass over the nodes the box meets; no per-voxel lookups.
#pragma once

#include <openvdb/openvdb.h>

namespace fcc::io {

namespace detail {

inline openvdb::CoordBBox cubeAt(const openvdb::Coord& origin, int dim) {
  return openvdb::CoordBBox(origin, origin.offsetBy(dim - 1));
}

template <class NodeT, class OnLeaf, class OnTile>
bool visitNodeRegion(const NodeT& node, const openvdb::CoordBBox& box, OnLeaf& onLeaf, OnTile& onTile) {
  using ChildT = typename NodeT::ChildNodeType;
  constexpr int kChild = int(ChildT::DIM);
  const openvdb::Coord lo = openvdb::Coord::maxComponent(box.min(), node.origin());
  const openvdb::Coord hi = openvdb::Coord::minComponent(box.max(), node.origin().offsetBy(int(NodeT::DIM) - 1));
  for (int x = lo.x() & ~(kChild - 1); x <= hi.x(); x += kChild)
    for (int y = lo.y() & ~(kChild - 1); y <= hi.y(); y += kChild)
      for (int z = lo.z() & ~(kChild - 1); z <= hi.z(); z += kChild) {
        const openvdb::Coord xyz(x, y, z);
        if (node.isChildMaskOn(NodeT::coordToOffset(xyz))) {
          const ChildT* child = node.template probeConstNode<ChildT>(xyz);
          if constexpr (ChildT::LEVEL == 0) {
            if (!onLeaf(*child)) return false;
          } else if (!visitNodeRegion(*child, box, onLeaf, onTile)) {
            return false;
          }
        } else if (!onTile(cubeAt(xyz, kChild), node.getValue(xyz))) {
          return false;
        }
      }
  return true;
}

}  // namespace detail

// Calls onLeaf(const LeafNodeType&) for every leaf that meets `box`, and onTile(CoordBBox, value) for
// every constant region that meets it (a tile's whole box, not clipped; the root's empty regions as
// tiles of the background, one per root-child-sized cube). Either returns false to stop early; the
// result is false if one did.
template <class TreeT, class OnLeaf, class OnTile>
bool visitRegion(const TreeT& tree, const openvdb::CoordBBox& box, OnLeaf&& onLeaf, OnTile&& onTile) {
  using RootT = typename TreeT::RootNodeType;
  using TopT = typename RootT::ChildNodeType;
  static_assert(RootT::LEVEL == 3, "a tree of the standard 5-4-3 configuration");
  if (box.empty()) return true;
  constexpr int kTop = int(TopT::DIM);
  const RootT& root = tree.root();
  for (int x = box.min().x() & ~(kTop - 1); x <= box.max().x(); x += kTop)
    for (int y = box.min().y() & ~(kTop - 1); y <= box.max().y(); y += kTop)
      for (int z = box.min().z() & ~(kTop - 1); z <= box.max().z(); z += kTop) {
        const openvdb::Coord xyz(x, y, z);
        if (const TopT* top = root.template probeConstNode<TopT>(xyz)) {
          if (!detail::visitNodeRegion(*top, box, onLeaf, onTile)) return false;
        } else if (!onTile(detail::cubeAt(xyz, kTop), root.getValue(xyz))) {
          return false;
        }
      }
  return true;
}

}  // namespace fcc::io
