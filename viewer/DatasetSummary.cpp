#include "DatasetSummary.h"

#include <algorithm>

#include "sparse/SampleHistogram.h"

namespace fcc::render {

DatasetSummary summarizeDataset(const io::BrickStore& store, std::size_t maxBricks, int bins, bool preferRecorded) {
  DatasetSummary s;
  s.file = store.path();
  const FccGrid& index = store.index();
  s.grid = index.getName();
  s.samples = index.tree().activeVoxelCount() * 4;  // masks only: no leaf values are read
  s.bricks = index.tree().leafCount();
  s.bytes = s.bricks * sizeof(io::BrickValues);
  s.valueMin = store.valueMin();
  s.valueMax = store.valueMax();
  const std::optional<SampleSummary> samples = recordedSamples(index);
  if (samples) {
    s.hasDataRange = true;
    s.dataMin = samples->min;
    s.dataMax = samples->max;
  }
  if (preferRecorded && samples && !samples->histogram.empty()) {
    // The file's own record of every sample: exact, and free to read. Merged by whole groups so the
    // bins stay equal (256 recorded bins become 64 for the default).
    const std::size_t recorded = samples->histogram.size();
    std::size_t group = std::max<std::size_t>(1, recorded / std::size_t(std::max(bins, 1)));
    while (recorded % group != 0) --group;
    s.histogram.assign(recorded / group, 0.0f);
    for (std::size_t b = 0; b < recorded; ++b) s.histogram[b / group] += float(samples->histogram[b]);
    s.histogramMin = samples->min;
    s.histogramMax = samples->max;
    s.histogramOfSamples = true;
    s.histogramValues = samples->total();
    return s;
  }
  s.histogram.assign(std::size_t(std::max(bins, 1)), 0.0f);
  s.histogramMin = s.valueMin;
  s.histogramMax = s.valueMax;

  const std::size_t stride = std::max<std::size_t>(1, (s.bricks + maxBricks - 1) / std::max<std::size_t>(maxBricks, 1));
  const float span = s.valueMax - s.valueMin;
  io::BrickValues values;
  std::size_t leafNumber = 0;
  for (auto leaf = index.tree().cbeginLeaf(); leaf; ++leaf, ++leafNumber) {
    if (leafNumber % stride != 0) continue;
    const openvdb::Coord origin = leaf->origin();
    const glm::ivec3 brick(origin.x() / kBrickPackedDim, origin.y() / kBrickPackedDim, origin.z() / kBrickPackedDim);
    store.readBrick(brick, values);  // a decoded copy: the delay-loaded leaf stays unread
    ++s.histogramBricks;
    for (auto on = leaf->getValueMask().beginOn(); on; ++on) {
      const openvdb::Vec4f& v = values[on.pos()];
      for (int c = 0; c < 4; ++c) {
        const float t = span > 0.0f ? (v[c] - s.valueMin) / span : 0.5f;
        const int bin = std::clamp(int(t * float(s.histogram.size())), 0, int(s.histogram.size()) - 1);
        s.histogram[std::size_t(bin)] += 1.0f;
        ++s.histogramValues;
      }
    }
  }
  return s;
}

DatasetSummary summarizeSource(const BrickSource& source, std::size_t maxBricks, int bins) {
  DatasetSummary s;
  s.file = source.path();
  s.bricks = source.varyingBrickCount();
  // A brick's samples: 16^3 Cartesian points, or 2 x 8^3 BCC sites (a quarter of the index points).
  s.bytes = s.bricks * std::size_t(source.slotBlock() == SlotBlock::BccPacked ? 2 * 8 * 8 * 8 : 16 * 16 * 16) * sizeof(float);
  s.valueMin = source.valueMin();
  s.valueMax = source.valueMax();
  s.histogram.assign(std::size_t(std::max(bins, 1)), 0.0f);
  s.histogramMin = s.valueMin;
  s.histogramMax = s.valueMax;
  s.histogramOfSamples = source.reconstruction().prefilter == Prefilter::None;
  if (source.slotBlock() == SlotBlock::FccPacked) return s;  // FCC sources: summarizeDataset
  const std::size_t stride = std::max<std::size_t>(1, (s.bricks + maxBricks - 1) / std::max<std::size_t>(maxBricks, 1));
  std::vector<LoadedBrick> chunk;
  std::size_t number = 0;
  source.forEachVaryingBrick([&](const glm::ivec3& brick, float, float) {
    if (number++ % stride == 0) chunk.push_back(LoadedBrick{brick, {}});
  });
  source.decode(chunk);
  const float span = s.valueMax - s.valueMin;
  const auto count = [&](float v) {
    const float t = span > 0.0f ? (v - s.valueMin) / span : 0.5f;
    const int bin = std::clamp(int(t * float(s.histogram.size())), 0, int(s.histogram.size()) - 1);
    s.histogram[std::size_t(bin)] += 1.0f;
    ++s.histogramValues;
  };
  // The brick's own values in its block: Cartesian points [16b, 16b + 16) of the block's
  // [16b - 2, 16b + 18)^3; BCC coset voxels [8b, 8b + 8) of each coset's [8b - 2, 8b + 10)^3.
  const bool bcc = source.slotBlock() == SlotBlock::BccPacked;
  const int dim = bcc ? kBccSlotDim : 20, lo = bcc ? kBccSlotLo : 2, own = bcc ? 8 : 16, blocks = bcc ? 2 : 1;
  for (const LoadedBrick& b : chunk) {
    ++s.histogramBricks;
    for (int k = 0; k < blocks; ++k)
      for (int z = lo; z < lo + own; ++z)
        for (int y = lo; y < lo + own; ++y)
          for (int x = lo; x < lo + own; ++x)
            count(b.halo[std::size_t(k) * dim * dim * dim + (std::size_t(z) * dim + y) * dim + x]);
  }
  return s;
}

}  // namespace fcc::render
