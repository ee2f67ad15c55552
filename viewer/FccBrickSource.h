// An FCC .vdb as the raycaster's brick source: its bounds grid says which bricks vary (and over which
// BB-coefficients), blocks are assembled from the host cache of decoded bricks (io/BrickCache.h) in
// the four-channel packing, and the shader evaluates the six-direction box spline.
#pragma once

#include <memory>

#include "BrickSource.h"
#include "io/BrickCache.h"
#include "io/BrickStore.h"

namespace fcc::render {

class FccBrickSource : public BrickSource {
 public:
  // A host cache of its own, of `hostCacheBytes`.
  FccBrickSource(const io::BrickStore& store, std::size_t hostCacheBytes);
  // Blocks from `cache`, which outlives this (benchmarks time a cache cold and warm).
  FccBrickSource(const io::BrickStore& store, io::BrickCache& cache);

  const io::BrickStore& store() const { return store_; }
  const io::BrickCache& cache() const { return *cache_; }
  void setHostCacheBytes(std::size_t bytes) { cache_->setBudgetBytes(bytes); }

  const std::string& path() const override { return store_.path(); }
  const ReconstructionInfo& reconstruction() const override;
  SlotBlock slotBlock() const override { return SlotBlock::FccPacked; }
  const glm::dmat4& worldFromIndex() const override { return store_.worldFromIndex(); }
  void brickBox(glm::ivec3& lo, glm::ivec3& hi) const override;
  void worldBounds(glm::dvec3& lo, glm::dvec3& hi) const override { store_.worldBounds(lo, hi); }
  float background() const override { return store_.background(); }
  float valueMin() const override { return store_.valueMin(); }
  float valueMax() const override { return store_.valueMax(); }
  std::optional<std::pair<float, float>> sampleRange() const override;  // fcc_sample_min, fcc_sample_max
  void forEachVaryingBrick(const std::function<void(const glm::ivec3&, float, float)>& visit) const override;
  std::size_t varyingBrickCount() const override;
  void decode(std::vector<LoadedBrick>& chunk) const override;
  HostCacheUse hostCacheUse() const override { return {cache_->bytesUsed(), cache_->budgetBytes()}; }
  io::Damage damage() const override { return store_.damage(); }

 private:
  const io::BrickStore& store_;
  std::unique_ptr<io::BrickCache> ownCache_;
  io::BrickCache* cache_;
};

}  // namespace fcc::render
