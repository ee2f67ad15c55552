#include "DefaultIsovalue.h"

#include "sparse/SampleHistogram.h"

namespace fcc::io {

IsoChoice defaultIsovalue(const BrickStore& store) {
  const FccGrid& grid = store.index();
  if (grid.getGridClass() == openvdb::GRID_LEVEL_SET) return {0.0f, "a level set's zero crossing"};
  if (const std::optional<SampleSummary> samples = recordedSamples(grid))
    if (const std::optional<double> t = otsuThreshold(*samples, store.background()))
      return {float(*t), "Otsu's threshold of the samples' histogram, background left out"};
  return {0.5f * (store.valueMin() + store.valueMax()), "the middle of the range the surface can take"};
}

}  // namespace fcc::io
