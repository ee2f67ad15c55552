#include "BoundsHierarchy.h"

#include <algorithm>
#include <limits>

namespace fcc {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::Vec2f;

void widen(Vec2f& into, const Vec2f& b) {
  into[0] = std::min(into[0], b[0]);
  into[1] = std::max(into[1], b[1]);
}

const Vec2f kEmpty(std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity());

// Widens the interval of every node (of 2^log2 bricks per side) that `bricks` overlaps.
void widenNodes(BoundsHierarchy::NodeMap& nodes, const CoordBBox& bricks, int log2, const Vec2f& b) {
  const Coord lo(bricks.min().x() >> log2, bricks.min().y() >> log2, bricks.min().z() >> log2);
  const Coord hi(bricks.max().x() >> log2, bricks.max().y() >> log2, bricks.max().z() >> log2);
  for (int z = lo.z(); z <= hi.z(); ++z)
    for (int y = lo.y(); y <= hi.y(); ++y)
      for (int x = lo.x(); x <= hi.x(); ++x) widen(nodes.try_emplace(Coord(x, y, z), kEmpty).first->second, b);
}

}  // namespace

BoundsHierarchy::BoundsHierarchy(const BoundsGrid& bounds) : bounds_(bounds), root_(kEmpty) {
  for (auto it = bounds.cbeginValueOn(); it; ++it) {
    const CoordBBox box = it.getBoundingBox();  // one brick, or a tile's bricks
    widenNodes(level1_, box, kLevel1Log2Bricks, *it);
    widenNodes(level2_, box, kLevel2Log2Bricks, *it);
    widen(root_, *it);
    total_.bricks += box.volume();
  }
  total_.nodes1 = level1_.size();
  total_.nodes2 = level2_.size();
}

BoundsHierarchy::Counts BoundsHierarchy::kept(float iso) const {
  Counts c;
  if (!holds(root_, iso)) return c;
  for (auto it = bounds_.cbeginValueOn(); it; ++it)
    if (holds(*it, iso)) c.bricks += it.getBoundingBox().volume();
  for (const auto& [key, b] : level1_) c.nodes1 += holds(b, iso);
  for (const auto& [key, b] : level2_) c.nodes2 += holds(b, iso);
  return c;
}

}  // namespace fcc
