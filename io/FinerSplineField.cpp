#include "FinerSplineField.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "TreeRegion.h"
#include "sparse/Error.h"
#include "sparse/Lattice.h"
#include "sparse/Spline.h"

namespace fcc::io {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::Vec4f;

std::string text(const Coord& c) {
  return "(" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")";
}

// The finer grid's packed voxels that level-k sites `box` read: sites 2J and its neighbours, 2J +- 1 in
// each axis, so packed voxels [(2 min - 1) >> 1, (2 max + 1) >> 1] = [min - 1, max].
CoordBBox packedReach(const SiteBox& box) {
  return CoordBBox(Coord(box.min.x - 1, box.min.y - 1, box.min.z - 1), Coord(box.max.x, box.max.y, box.max.z));
}

// The level-k sites whose value reads any finer site of packed box `packed`: finer sites [2a, 2b + 1],
// read by J with |2J - s| <= 1 in each axis, i.e. J in [a, b + 1].
SiteBox sitesReading(const CoordBBox& packed) {
  return {glm::ivec3(packed.min().x(), packed.min().y(), packed.min().z()),
          glm::ivec3(packed.max().x() + 1, packed.max().y() + 1, packed.max().z() + 1)};
}

bool isUniform(const Vec4f& v) { return v[0] == v[1] && v[0] == v[2] && v[0] == v[3]; }

}  // namespace

FinerSplineField::FinerSplineField(const BrickStore& finer) : finer_(finer), background_(finer.background()) {
  const FccTree& tree = finer_.index().tree();
  const Vec4f bg = tree.background();
  // The finer data's packed box: its leaves and non-background tiles (never a leaf's values).
  CoordBBox data;
  for (auto it = tree.cbeginLeaf(); it; ++it) data.expand(it->getNodeBoundingBox());
  auto tiles = tree.cbeginValueAll();
  tiles.setMaxDepth(FccTree::ValueAllCIter::LEAF_DEPTH - 1);
  for (; tiles; ++tiles) {
    if (*tiles == bg) continue;
    CoordBBox box;
    tiles.getBoundingBox(box);
    data.expand(box);
  }
  if (!data.empty()) bounds_ = sitesReading(data);
}

const BrickValues& FinerSplineField::residentValues(const Leaf& leaf) const {
  const auto it = resident_.find(&leaf);
  if (it == resident_.end())
    throw Error("internal: the finer level's brick at " + text(leaf.origin()) + " was read before it was prepared");
  return *it->second;
}

Vec4f FinerSplineField::packedValue(const Coord& packed) const {
  const FccTree& tree = finer_.index().tree();
  if (const Leaf* leaf = tree.probeConstLeaf(packed)) return residentValues(*leaf)[Leaf::coordToOffset(packed)];
  return tree.getValue(packed);  // a tile or the background: no leaf is read
}

float FinerSplineField::sample(const glm::ivec3& ijk) const {
  if (!bounds_.contains(ijk)) return background_;
  auto coefficientAt = [&](const glm::ivec3& site) {
    const glm::ivec3 p = packedVoxelOfSite(site);
    return packedValue(Coord(p.x, p.y, p.z))[channelOfSite(site)];
  };
  const glm::ivec3 center = 2 * ijk;
  float neighbourSum = 0.0f;
  for (int n = 0; n < 12; ++n) neighbourSum += coefficientAt(center + spline::fcc_neighbour_offset(n));
  return splineAtSite(coefficientAt(center), neighbourSum);
}

bool FinerSplineField::mayHoldData(const SiteBox& box) const {
  if (!box.intersects(bounds_)) return false;
  const Vec4f bg = finer_.index().tree().background();
  return !visitRegion(
      finer_.index().tree(), packedReach(box), [](const Leaf&) { return false; },
      [&](const CoordBBox&, const Vec4f& v) { return v == bg; });
}

void FinerSplineField::fill(const SiteBox& box, float* out) const {
  // The finer coefficients the box reads, gathered once into a dense block of packed voxels (a block's
  // 18^3 sites read 19^3 of them), then 13 reads a site from it.
  static tbb::enumerable_thread_specific<std::vector<Vec4f>> scratch;
  const CoordBBox reach = packedReach(box);
  const Coord lo = reach.min();
  const openvdb::Coord dim = reach.dim();
  std::vector<Vec4f>& packed = scratch.local();
  packed.resize(size_t(dim.x()) * dim.y() * dim.z());
  auto at = [&](int x, int y, int z) -> Vec4f& {
    return packed[(size_t(z - lo.z()) * dim.y() + size_t(y - lo.y())) * dim.x() + size_t(x - lo.x())];
  };
  visitRegion(
      finer_.index().tree(), reach,
      [&](const Leaf& leaf) {
        const BrickValues& values = residentValues(leaf);
        CoordBBox part = leaf.getNodeBoundingBox();
        part.intersect(reach);
        const Coord o = leaf.origin();
        for (int z = part.min().z(); z <= part.max().z(); ++z)
          for (int y = part.min().y(); y <= part.max().y(); ++y)
            for (int x = part.min().x(); x <= part.max().x(); ++x)
              at(x, y, z) = values[((x - o.x()) << 6) | ((y - o.y()) << 3) | (z - o.z())];
        return true;
      },
      [&](const CoordBBox& tile, const Vec4f& v) {
        CoordBBox part = tile;
        part.intersect(reach);
        for (int z = part.min().z(); z <= part.max().z(); ++z)
          for (int y = part.min().y(); y <= part.max().y(); ++y)
            std::fill_n(&at(part.min().x(), y, z), part.dim().x(), v);
        return true;
      });
  auto coefficientAt = [&](const glm::ivec3& site) {
    const glm::ivec3 p = packedVoxelOfSite(site);
    return at(p.x, p.y, p.z)[channelOfSite(site)];
  };
  const glm::ivec3 d = box.dim();
  for (int z = box.min.z; z <= box.max.z; ++z)
    for (int y = box.min.y; y <= box.max.y; ++y) {
      float* row = out + (size_t(z - box.min.z) * d.y + size_t(y - box.min.y)) * d.x;
      for (int x = box.min.x + ((box.min.x + y + z) & 1); x <= box.max.x; x += 2) {  // FCC sites only
        const glm::ivec3 center(2 * x, 2 * y, 2 * z);
        float neighbourSum = 0.0f;
        for (int n = 0; n < 12; ++n) neighbourSum += coefficientAt(center + spline::fcc_neighbour_offset(n));
        row[x - box.min.x] = splineAtSite(coefficientAt(center), neighbourSum);
      }
    }
}

bool FinerSplineField::uniformOver(const SiteBox& box, float& value) const {
  bool first = true;
  Vec4f common;
  const bool uniform = visitRegion(
      finer_.index().tree(), packedReach(box), [](const Leaf&) { return false; },
      [&](const CoordBBox&, const Vec4f& v) {
        if (!isUniform(v)) return false;
        if (first) {
          common = v;
          first = false;
          return true;
        }
        return v == common;
      });
  if (!uniform || first) return false;
  // The same sums fill() makes of one value everywhere, so a uniform block equals a built one.
  float neighbourSum = 0.0f;
  for (int n = 0; n < 12; ++n) neighbourSum += common[0];
  value = splineAtSite(common[0], neighbourSum);
  return true;
}

bool FinerSplineField::forEachDataBox(const SiteBox& region, const std::function<void(const SiteBox&)>& visit) const {
  const Vec4f bg = finer_.index().tree().background();
  visitRegion(
      finer_.index().tree(), packedReach(region),
      [&](const Leaf& leaf) {
        visit(sitesReading(leaf.getNodeBoundingBox()));
        return true;
      },
      [&](const CoordBBox& tile, const Vec4f& v) {
        if (v != bg) visit(sitesReading(tile));
        return true;
      });
  return true;
}

void FinerSplineField::prepare(const std::vector<SiteBox>& boxes) const {
  // The finer leaves the boxes read, gathered in parallel (a slab holds thousands of boxes).
  tbb::enumerable_thread_specific<std::vector<const Leaf*>> perThread;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, boxes.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<const Leaf*>& found = perThread.local();
    for (size_t b = r.begin(); b != r.end(); ++b)
      visitRegion(
          finer_.index().tree(), packedReach(boxes[b]),
          [&](const Leaf& leaf) {
            found.push_back(&leaf);
            return true;
          },
          [](const CoordBBox&, const Vec4f&) { return true; });
  });
  std::vector<const Leaf*> needed;
  for (const std::vector<const Leaf*>& found : perThread) needed.insert(needed.end(), found.begin(), found.end());
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());

  // Keep what is still needed, decode the rest in parallel (BrickStore: validated, a damaged brick is
  // recorded in its damage()), drop everything else.
  std::unordered_map<const Leaf*, std::unique_ptr<BrickValues>> next;
  next.reserve(needed.size());
  std::vector<const Leaf*> missing;
  for (const Leaf* leaf : needed) {
    auto it = resident_.find(leaf);
    if (it != resident_.end()) next.emplace(leaf, std::move(it->second));
    else missing.push_back(leaf);
  }
  resident_.clear();  // before decoding: at most `needed` bricks at once
  std::vector<std::unique_ptr<BrickValues>> values(missing.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, missing.size(), 8), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const Coord b = missing[i]->origin() >> 3;
      values[i] = std::make_unique<BrickValues>();
      finer_.readBrick(glm::ivec3(b.x(), b.y(), b.z()), *values[i]);
    }
  });
  for (size_t i = 0; i < missing.size(); ++i) next.emplace(missing[i], std::move(values[i]));
  decoded_ += missing.size();
  resident_ = std::move(next);
  maxResident_ = std::max(maxResident_, resident_.size());
}

}  // namespace fcc::io
