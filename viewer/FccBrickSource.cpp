#include "FccBrickSource.h"

#include "sparse/SampleHistogram.h"

namespace fcc::render {

static_assert(io::kHaloBlockVoxels * 4 == 10 * 10 * 10 * 4, "slotBlockFloats(FccPacked) is the halo block");

FccBrickSource::FccBrickSource(const io::BrickStore& store, std::size_t hostCacheBytes)
    : store_(store), ownCache_(std::make_unique<io::BrickCache>(store, hostCacheBytes)), cache_(ownCache_.get()) {}

FccBrickSource::FccBrickSource(const io::BrickStore& store, io::BrickCache& cache) : store_(store), cache_(&cache) {}

const ReconstructionInfo& FccBrickSource::reconstruction() const {
  static const ReconstructionInfo& boxSpline = findReconstruction("boxspline");
  return boxSpline;
}

void FccBrickSource::brickBox(glm::ivec3& lo, glm::ivec3& hi) const {
  const openvdb::CoordBBox& box = store_.activeBrickBox();
  lo = glm::ivec3(box.min().x(), box.min().y(), box.min().z());
  hi = glm::ivec3(box.max().x(), box.max().y(), box.max().z());
}

void FccBrickSource::forEachVaryingBrick(const std::function<void(const glm::ivec3&, float, float)>& visit) const {
  for (auto it = store_.bounds().cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    visit(glm::ivec3(c.x(), c.y(), c.z()), (*it)[0], (*it)[1]);
  }
}

std::optional<std::pair<float, float>> FccBrickSource::sampleRange() const {
  const std::optional<SampleSummary> samples = recordedSamples(store_.index());
  if (!samples) return std::nullopt;
  return std::make_pair(samples->min, samples->max);
}

std::size_t FccBrickSource::varyingBrickCount() const { return std::size_t(store_.bounds().activeVoxelCount()); }

void FccBrickSource::decode(std::vector<LoadedBrick>& chunk) const {
  io::BrickValuesMemo memo(*cache_);  // the chunk's bricks are mostly neighbours: one cache lookup each
  for (LoadedBrick& b : chunk) {
    b.halo.resize(slotBlockFloats(SlotBlock::FccPacked));  // no-op for a recycled block
    io::assembleHaloBlock(store_, memo, b.brick, b.halo.data());
  }
}

}  // namespace fcc::render
