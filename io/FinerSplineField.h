// The spline of an FCC grid (pyramid level k-1) sampled at the sites of the FCC lattice of twice its
// spacing (level k): the sample field from which the streamed build (sparse/StreamedBuild.h) makes level
// k, prefiltering these samples as it does any field's. Read out of core through a BrickStore: the
// finer grid's topology is in memory, its bricks are decoded only for the blocks being built (prepare)
// and dropped once no longer needed.
//
// Level k's site J lies at level k-1's site 2J (an FCC site: its coordinate sum is even), and the spline
// s(x) = sum_j c_j M_fcc(x - j) at a lattice site is a 13-tap filter of the coefficients: M_fcc is 1/2 at
// 0, 1/24 at the 12 nearest neighbours and 0 at every other site (test_pyramid checks it against the
// spline's evaluation), so
//     V_k(J) = c_{k-1}(2J) / 2 + (sum of c_{k-1} at the 12 neighbours of 2J) / 24
// is the finer spline's exact value there. Tiles and the background are constant regions of the finer
// grid: a block whose reach lies in one of them is uniform (no site visited), and the blocks to build
// come from the finer grid's leaves and non-background tiles alone (io/TreeRegion.h).
#pragma once

#include <memory>
#include <unordered_map>
#include <vector>

#include "BrickStore.h"
#include "sparse/SampleField.h"

namespace fcc::io {

// M_fcc at the lattice's sites applied to one site's coefficient and the sum of its 12 neighbours'.
inline float splineAtSite(float center, float neighbourSum) { return 0.5f * center + neighbourSum * (1.0f / 24.0f); }

class FinerSplineField final : public SampleField {
 public:
  // `finer` stores coefficients (fcc_values = coefficients); it must outlive the field.
  explicit FinerSplineField(const BrickStore& finer);

  float sample(const glm::ivec3& ijk) const override;
  SiteBox bounds() const override { return bounds_; }
  bool mayHoldData(const SiteBox& box) const override;
  float background() const override { return background_; }
  void fill(const SiteBox& box, float* out) const override;
  bool uniformOver(const SiteBox& box, float& value) const override;
  bool forEachDataBox(const SiteBox& region, const std::function<void(const SiteBox&)>& visit) const override;
  void prepare(const std::vector<SiteBox>& boxes) const override;

  // Bricks of the finer grid decoded so far (one decoded again after being dropped counts again), and
  // the most held at once: what bounds the memory (test_pyramid).
  size_t bricksDecoded() const { return decoded_; }
  size_t maxBricksResident() const { return maxResident_; }

 private:
  using Leaf = FccTree::LeafNodeType;
  const BrickValues& residentValues(const Leaf& leaf) const;
  openvdb::Vec4f packedValue(const openvdb::Coord& packed) const;  // one packed voxel of the finer grid

  const BrickStore& finer_;
  float background_;
  SiteBox bounds_;
  mutable std::unordered_map<const Leaf*, std::unique_ptr<BrickValues>> resident_;
  mutable size_t decoded_ = 0, maxResident_ = 0;
};

}  // namespace fcc::io
