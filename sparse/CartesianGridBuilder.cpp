#include "CartesianGridBuilder.h"

#include <tbb/parallel_for.h>

#include <memory>
#include <vector>

namespace fcc {

openvdb::FloatGrid::Ptr buildCartesianGrid(const SiteBox& box, float background,
                                           const std::function<float(const glm::ivec3&)>& value,
                                           const std::function<bool(const SiteBox&)>& mayHoldData) {
  using Leaf = openvdb::FloatTree::LeafNodeType;
  constexpr int kDim = int(Leaf::DIM);
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(background);
  if (box.empty()) return grid;
  // The leaves that meet the box, by origin (a multiple of the leaf size, also below zero).
  const glm::ivec3 first = glm::ivec3(box.min.x & ~(kDim - 1), box.min.y & ~(kDim - 1), box.min.z & ~(kDim - 1));
  const glm::ivec3 count = (box.max - first) / kDim + 1;
  const size_t total = size_t(count.x) * count.y * count.z;
  std::vector<std::unique_ptr<Leaf>> leaves(total);
  tbb::parallel_for(size_t(0), total, [&](size_t i) {
    const glm::ivec3 c(int(i % size_t(count.x)), int(i / size_t(count.x) % size_t(count.y)),
                       int(i / (size_t(count.x) * count.y)));
    const glm::ivec3 origin = first + kDim * c;
    const SiteBox part = SiteBox{origin, origin + (kDim - 1)}.intersection(box);
    if (mayHoldData && !mayHoldData(part)) return;
    auto leaf = std::make_unique<Leaf>(openvdb::Coord(origin.x, origin.y, origin.z), background, false);
    for (int z = part.min.z; z <= part.max.z; ++z)
      for (int y = part.min.y; y <= part.max.y; ++y)
        for (int x = part.min.x; x <= part.max.x; ++x)
          leaf->setValueOn(openvdb::Coord(x, y, z), value(glm::ivec3(x, y, z)));
    leaves[i] = std::move(leaf);
  });
  for (auto& leaf : leaves)
    if (leaf) grid->tree().addLeaf(leaf.release());
  return grid;
}

}  // namespace fcc
