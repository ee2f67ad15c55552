// A dense volume held in a SlabScratch as the sample field of a streamed conversion: subsampled (the
// even-parity voxels at their own positions) or resampled (the volume's tricubic B-spline at the sites
// of a lattice of another spacing; the scratch then holds its coefficients). The same samples, bit for
// bit, as the in-memory fields of io/Convert.cpp, which read a DenseVolume.
//
// prepare() reads what a slab or a batch of blocks needs from the scratch: one region per group of
// blocks (an x-layer of blocks across one level-1 node of the tree, 16 x 16 blocks), the box of the
// voxels their samples read. Grouping keeps each region near the blocks: pass 2 walks the tree, whose
// batches can end in one node and go on in another, far away, whose common box would be a whole
// slab. Memory: about one x-slab of the volume (18 columns) as float.
#pragma once

#include <memory>
#include <vector>

#include "SlabScratch.h"
#include "sparse/SampleField.h"

namespace fcc::io {

class DenseSlabField : public SampleField {
 public:
  float background() const override { return background_; }
  void prepare(const std::vector<SiteBox>& boxes) const override;

 protected:
  DenseSlabField(std::shared_ptr<const SlabScratch> scratch, float background)
      : scratch_(std::move(scratch)), background_(background) {}

  // A prepared box of voxels of the scratch.
  struct Region {
    SiteBox voxels;
    std::vector<float> values;  // x fastest
    float at(const glm::ivec3& ijk) const {
      const glm::ivec3 l = ijk - voxels.min, d = voxels.dim();
      return values[(size_t(l.z) * size_t(d.y) + size_t(l.y)) * size_t(d.x) + size_t(l.x)];
    }
  };
  // The voxels (inside the volume) whose values the samples of `sites` read; empty if none.
  virtual SiteBox voxelsFor(const SiteBox& sites) const = 0;
  // The prepared region holding every voxel the samples of `sites` read; fcc::Error if none does.
  const Region& regionFor(const SiteBox& sites) const;

  std::shared_ptr<const SlabScratch> scratch_;
  float background_;

 private:
  using GroupKey = std::tuple<int, int, int>;
  static GroupKey groupOf(const SiteBox& sites);
  mutable std::vector<Region> regions_;
  mutable std::vector<std::pair<GroupKey, size_t>> byGroup_;  // sorted
};

// Subsampling: the sample at site ijk is voxel ijk; the background outside the volume.
class DenseSlabSubsampleField final : public DenseSlabField {
 public:
  DenseSlabSubsampleField(std::shared_ptr<const SlabScratch> scratch, float background)
      : DenseSlabField(std::move(scratch), background) {}
  float sample(const glm::ivec3& ijk) const override;
  SiteBox bounds() const override { return {glm::ivec3(0), scratch_->dims() - 1}; }
  void fill(const SiteBox& box, float* out) const override;

 protected:
  SiteBox voxelsFor(const SiteBox& sites) const override { return sites.intersection(bounds()); }
};

// Resampling: the scratch holds the B-spline coefficients of the volume (resampleCoefficients);
// the sample at site ijk is the spline at voxel position ijk * spacing, as CubicBSplineVolume
// evaluates it (positions clamped to the volume, coefficients mirrored at its faces).
class DenseSlabResampleField final : public DenseSlabField {
 public:
  DenseSlabResampleField(std::shared_ptr<const SlabScratch> coefficients, float background, double spacingInVoxels);
  float sample(const glm::ivec3& ijk) const override;
  SiteBox bounds() const override { return {glm::ivec3(0), latticeMax_}; }
  void fill(const SiteBox& box, float* out) const override;

 protected:
  SiteBox voxelsFor(const SiteBox& sites) const override;

 private:
  float evaluate(const Region& region, const glm::ivec3& ijk) const;
  double spacing_;
  glm::ivec3 latticeMax_;
};

// The volume of `source` re-tiled for a field: its samples for subsampling, its B-spline coefficients
// for resampling (the prefilter along x and y on each group of slices as they are read, along z on
// the scratch's slabs: every line filtered as CubicBSplineVolume filters it, so the same bits).
std::shared_ptr<const SlabScratch> slabsOfSamples(DenseSource& source, openvdb::util::NullInterrupter* progress = nullptr);
std::shared_ptr<const SlabScratch> slabsOfCoefficients(DenseSource& source,
                                                       openvdb::util::NullInterrupter* progress = nullptr);

}  // namespace fcc::io
