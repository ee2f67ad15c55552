// A Cartesian float grid (.vdb fog volume or level set) as the raycaster's brick source, rendered as
// it is with a CC reconstruction (`render --reconstruction trilinear|tricubic|tricubic-bspline`): a
// slot holds the 20^3 grid points [16b - 2, 16b + 18)^3 every CC stencil of the brick's cells reads
// (io/CartesianBrickStore.h), as coefficients: the samples themselves, or for `tricubic` the
// interpolating B-spline coefficients, prefiltered per block from the samples of the block padded by
// kBSplinePrefilterReach (beyond which the filter's response is below float precision).
#pragma once

#include <vector>

#include "BrickSource.h"
#include "io/CartesianBrickStore.h"

namespace fcc::render {

class CartesianBrickSource : public BrickSource {
 public:
  // `reconstruction`: one of the CC lattice's (ValueError naming them otherwise). The bricks' value
  // ranges are the store's brickRanges() (every leaf read once per store, or the user cache's), widened
  // here for a prefiltered reconstruction: sources of several reconstructions over one store share them.
  CartesianBrickSource(const io::CartesianBrickStore& store, const ReconstructionInfo& reconstruction);

  const std::string& path() const override { return store_.path(); }
  const ReconstructionInfo& reconstruction() const override { return reconstruction_; }
  SlotBlock slotBlock() const override { return SlotBlock::Sites; }
  const glm::dmat4& worldFromIndex() const override { return store_.worldFromIndex(); }
  void brickBox(glm::ivec3& lo, glm::ivec3& hi) const override;
  void worldBounds(glm::dvec3& lo, glm::dvec3& hi) const override { store_.worldBounds(lo, hi); }
  float background() const override { return store_.background(); }
  float valueMin() const override { return valueMin_; }
  float valueMax() const override { return valueMax_; }
  void forEachVaryingBrick(const std::function<void(const glm::ivec3&, float, float)>& visit) const override;
  std::size_t varyingBrickCount() const override { return ranges_.size(); }
  void decode(std::vector<LoadedBrick>& chunk) const override;
  // Damaged leaves (the store's): each reads as the background, a hole (io/CartesianBrickStore.h).
  io::Damage damage() const override { return store_.damage(); }

  // The factor by which the interpolating prefilter can widen a range about its middle: the sum of
  // the absolute values of its 3D impulse response, (sum |h|)^3 of the 1D one.
  static double prefilterGain();

 private:
  const io::CartesianBrickStore& store_;
  const ReconstructionInfo& reconstruction_;
  bool prefiltered_ = false;
  std::vector<io::CartesianBrickStore::BrickRange> ranges_;  // of the coefficients, when prefiltered
  float valueMin_ = 0.0f, valueMax_ = 0.0f;
};

}  // namespace fcc::render
