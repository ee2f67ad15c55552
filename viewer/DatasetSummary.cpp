#include "DatasetSummary.h"

#include <algorithm>

#include "sparse/SampleHistogram.h"

namespace fcc::render {

DatasetSummary summarizeDataset(const io::BrickStore& store, std::size_t maxBricks, int bins) {
  DatasetSummary s;
  s.file = store.path();
  const FccGrid& index = store.index();
  s.grid = index.getName();
  s.samples = index.tree().activeVoxelCount() * 4;  // masks only: no leaf values are read
  s.bricks = index.tree().leafCount();
  s.bytes = s.bricks * sizeof(io::BrickValues);
  s.valueMin = store.valueMin();
  s.valueMax = store.valueMax();
  if (const std::optional<SampleSummary> samples = recordedSamples(index)) {
    s.hasDataRange = true;
    s.dataMin = samples->min;
    s.dataMax = samples->max;
  }
  s.histogram.assign(std::size_t(std::max(bins, 1)), 0.0f);

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

}  // namespace fcc::render
