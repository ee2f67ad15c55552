#include "VdbSourceField.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "TreeRegion.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using Leaf = openvdb::FloatTree::LeafNodeType;

CoordBBox coordBox(const SiteBox& b) {
  return CoordBBox(Coord(b.min.x, b.min.y, b.min.z), Coord(b.max.x, b.max.y, b.max.z));
}

std::string text(const Coord& c) {
  return "(" + std::to_string(c.x()) + ", " + std::to_string(c.y()) + ", " + std::to_string(c.z()) + ")";
}

SiteBox siteBox(const CoordBBox& b) {
  return {glm::ivec3(b.min().x(), b.min().y(), b.min().z()), glm::ivec3(b.max().x(), b.max().y(), b.max().z())};
}

}  // namespace

VdbSourceField::VdbSourceField(std::shared_ptr<const VdbLeafReader> reader, float background)
    : reader_(std::move(reader)), background_(background) {
  grid_ = openvdb::gridConstPtrCast<openvdb::FloatGrid>(reader_->grid());
  if (!grid_) throw InputError(reader_->path() + ": grid '" + reader_->grid()->getName() + "' is not a float grid");
  sourceBackground_ = grid_->background();
  // As the in-memory conversion: the active voxels' box (from the masks; no values are read).
  if (grid_->activeVoxelCount() > 0) bounds_ = siteBox(grid_->evalActiveVoxelBoundingBox());
}

const float* VdbSourceField::residentValues(const Leaf& leaf) const {
  const auto it = resident_.find(&leaf);
  if (it == resident_.end())
    throw Error("internal: the source leaf at " + text(leaf.origin()) + " was read before it was prepared");
  return it->second.get();
}

float VdbSourceField::sample(const glm::ivec3& ijk) const {
  const Coord xyz(ijk.x, ijk.y, ijk.z);
  if (const Leaf* leaf = grid_->tree().probeConstLeaf(xyz)) return mapped(residentValues(*leaf)[Leaf::coordToOffset(xyz)]);
  return mapped(grid_->tree().getValue(xyz));
}

bool VdbSourceField::mayHoldData(const SiteBox& box) const {
  if (!box.intersects(bounds_)) return false;
  // Stops at the first leaf or non-background constant region.
  return !visitRegion(
      grid_->tree(), coordBox(box), [](const Leaf&) { return false; },
      [&](const CoordBBox&, float v) { return v == sourceBackground_; });
}

void VdbSourceField::fill(const SiteBox& box, float* out) const {
  const glm::ivec3 dim = box.dim();
  auto at = [&](int x, int y, int z) -> float& {
    return out[(size_t(z - box.min.z) * dim.y + size_t(y - box.min.y)) * dim.x + size_t(x - box.min.x)];
  };
  visitRegion(
      grid_->tree(), coordBox(box),
      [&](const Leaf& leaf) {
        const float* values = residentValues(leaf);
        const SiteBox part = siteBox(leaf.getNodeBoundingBox()).intersection(box);
        const glm::ivec3 o(leaf.origin().x(), leaf.origin().y(), leaf.origin().z());
        for (int z = part.min.z; z <= part.max.z; ++z)
          for (int y = part.min.y; y <= part.max.y; ++y)
            for (int x = part.min.x; x <= part.max.x; ++x)
              at(x, y, z) = mapped(values[((x - o.x) << 6) | ((y - o.y) << 3) | (z - o.z)]);
        return true;
      },
      [&](const CoordBBox& tile, float v) {
        const SiteBox part = siteBox(tile).intersection(box);
        const float value = mapped(v);
        for (int z = part.min.z; z <= part.max.z; ++z)
          for (int y = part.min.y; y <= part.max.y; ++y) std::fill_n(&at(part.min.x, y, z), part.dim().x, value);
        return true;
      });
}

bool VdbSourceField::uniformOver(const SiteBox& box, float& value) const {
  bool first = true;
  return visitRegion(
      grid_->tree(), coordBox(box), [](const Leaf&) { return false; },
      [&](const CoordBBox&, float v) {
        v = mapped(v);
        if (first) {
          value = v;
          first = false;
          return true;
        }
        return v == value;
      });
}

bool VdbSourceField::forEachDataBox(const SiteBox& region, const std::function<void(const SiteBox&)>& visit) const {
  visitRegion(
      grid_->tree(), coordBox(region),
      [&](const Leaf& leaf) {
        visit(siteBox(leaf.getNodeBoundingBox()));
        return true;
      },
      [&](const CoordBBox& tile, float v) {
        if (v != sourceBackground_) visit(siteBox(tile));
        return true;
      });
  return true;
}

void VdbSourceField::prepare(const std::vector<SiteBox>& boxes) const {
  // The leaves the boxes meet, gathered in parallel (a slab holds thousands of boxes).
  tbb::enumerable_thread_specific<std::vector<const Leaf*>> perThread;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, boxes.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<const Leaf*>& found = perThread.local();
    for (size_t b = r.begin(); b != r.end(); ++b)
      visitRegion(
          grid_->tree(), coordBox(boxes[b]),
          [&](const Leaf& leaf) {
            found.push_back(&leaf);
            return true;
          },
          [](const CoordBBox&, float) { return true; });
  });
  std::vector<const Leaf*> needed;
  for (const std::vector<const Leaf*>& found : perThread) needed.insert(needed.end(), found.begin(), found.end());
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());

  // Keep what is still needed, decode the rest in parallel, drop everything else.
  std::unordered_map<const Leaf*, std::unique_ptr<float[]>> next;
  next.reserve(needed.size());
  std::vector<const Leaf*> missing;
  for (const Leaf* leaf : needed) {
    auto it = resident_.find(leaf);
    if (it != resident_.end()) next.emplace(leaf, std::move(it->second));
    else missing.push_back(leaf);
  }
  std::vector<std::unique_ptr<float[]>> values(missing.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, missing.size(), 8), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      // The reader indexes leaves by origin, in the order of this same topology tree.
      const std::optional<size_t> index = reader_->leafIndexAt(missing[i]->origin());
      if (!index) throw Error("internal: the leaf reader has no leaf at " + text(missing[i]->origin()));
      values[i].reset(new float[Leaf::SIZE]);
      reader_->readLeaf(*index, values[i].get());
    }
  });
  for (size_t i = 0; i < missing.size(); ++i) next.emplace(missing[i], std::move(values[i]));
  decoded_ += missing.size();
  resident_ = std::move(next);
}

}  // namespace fcc::io
