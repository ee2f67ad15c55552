// A Cartesian float grid in a .vdb file as the sample field of a subsampling conversion, read out of
// core: its topology (leaf masks, tiles) is in memory, its leaves are decoded from the file only for
// the blocks being built (prepare) and dropped when no longer needed. Tiles are never visited voxel
// by voxel: a block inside one constant region is uniform, and the blocks to build are found from
// the leaves and non-background tiles alone (TreeRegion.h). Samples equal those of the grid read
// whole (io::readFloatGrid), so the conversion's output is the same file.
#pragma once

#include <memory>
#include <unordered_map>
#include <vector>

#include "VdbLeafReader.h"
#include "sparse/SampleField.h"

namespace fcc::io {

class VdbSourceField final : public SampleField {
 public:
  // `reader` holds a float grid. Values equal to its background read as `background` (--background).
  VdbSourceField(std::shared_ptr<const VdbLeafReader> reader, float background);

  const openvdb::FloatGrid& topology() const { return *grid_; }

  float sample(const glm::ivec3& ijk) const override;
  SiteBox bounds() const override { return bounds_; }
  bool mayHoldData(const SiteBox& box) const override;
  float background() const override { return background_; }
  void fill(const SiteBox& box, float* out) const override;
  bool uniformOver(const SiteBox& box, float& value) const override;
  bool forEachDataBox(const SiteBox& region, const std::function<void(const SiteBox&)>& visit) const override;
  void prepare(const std::vector<SiteBox>& boxes) const override;

  // Leaves decoded so far (a leaf decoded again after being dropped counts again): for tests and the
  // benchmark's report.
  size_t leavesDecoded() const { return decoded_; }

 private:
  float mapped(float v) const { return v == sourceBackground_ ? background_ : v; }
  const float* residentValues(const openvdb::FloatTree::LeafNodeType& leaf) const;

  std::shared_ptr<const VdbLeafReader> reader_;
  openvdb::FloatGrid::ConstPtr grid_;
  float sourceBackground_;
  float background_;
  SiteBox bounds_;
  // Decoded leaves, by their leaf in the topology tree (fill() meets them there): replaced by
  // prepare(), read-only while blocks are built.
  mutable std::unordered_map<const openvdb::FloatTree::LeafNodeType*, std::unique_ptr<float[]>> resident_;
  mutable size_t decoded_ = 0;
};

}  // namespace fcc::io
