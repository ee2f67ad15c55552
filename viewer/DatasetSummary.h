// What the viewer's info section and isovalue histogram show about an opened dataset, from the
// index (topology only) and a bounded sample of decoded bricks, so opening a file of any size costs
// the same.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/BrickStore.h"

namespace fcc::render {

struct DatasetSummary {
  std::string file, grid;
  uint64_t samples = 0;     // active FCC samples (four per active packed voxel)
  uint64_t bricks = 0;      // leaves
  uint64_t bytes = 0;       // decoded size of the leaves' values
  float valueMin = 0.0f, valueMax = 0.0f;  // the range the surface can take: the spline's (the bounds' hull)
  // The data's range: the samples' before the prefilter, as convert/synth recorded them
  // (fcc_sample_min/max); the spline overshoots it where the data jumps. False for other files.
  bool hasDataRange = false;
  float dataMin = 0.0f, dataMax = 0.0f;
  // Counts of the active values of up to `maxBricks` bricks spread evenly over the file, in equal
  // bins over [valueMin, valueMax] (values outside go to the end bins).
  std::vector<float> histogram;
  uint64_t histogramValues = 0;
  uint64_t histogramBricks = 0;
};

DatasetSummary summarizeDataset(const io::BrickStore& store, std::size_t maxBricks = 256, int bins = 64);

}  // namespace fcc::render
