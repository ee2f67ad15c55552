// What the viewer's info section and isovalue histogram show about an opened dataset, from the
// index (topology only) and a bounded sample of decoded bricks, so opening a file of any size costs
// the same.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "BrickSource.h"
#include "io/BrickStore.h"

namespace fcc::render {

struct DatasetSummary {
  std::string file, grid;   // grid: empty where unknown (a Cartesian source)
  uint64_t samples = 0;     // active FCC samples (four per active packed voxel); 0 where unknown
  uint64_t bricks = 0;      // leaves (FCC); bricks whose values vary (a Cartesian source)
  uint64_t bytes = 0;       // decoded size of the leaves' values (a Cartesian source: 16^3 floats a brick, BCC 2 x 8^3)
  float valueMin = 0.0f, valueMax = 0.0f;  // the range the surface can take: the spline's (the bounds' hull)
  // The data's range: the samples' before the prefilter, as convert/synth recorded them
  // (fcc_sample_min/max); the spline overshoots it where the data jumps. False for other files.
  bool hasDataRange = false;
  float dataMin = 0.0f, dataMax = 0.0f;
  // The panel's histogram, counts in equal bins over [histogramMin, histogramMax]. Preferably the
  // samples' histogram the file records (fcc_sample_histogram, sparse/SampleHistogram.h: every sample,
  // before the prefilter, over the data range; bins merged down to about `bins`), read without
  // decoding a brick: `histogramOfSamples`. Else the counts of the stored coefficients of up to
  // `maxBricks` bricks spread evenly over the file, over [valueMin, valueMax] (values outside go to
  // the end bins).
  std::vector<float> histogram;
  float histogramMin = 0.0f, histogramMax = 0.0f;
  bool histogramOfSamples = false;
  uint64_t histogramValues = 0;
  uint64_t histogramBricks = 0;  // bricks decoded for it (0 for the recorded one)
};

// `preferRecorded` false: the coefficients' histogram even where the file records its samples' (tests).
DatasetSummary summarizeDataset(const io::BrickStore& store, std::size_t maxBricks = 256, int bins = 64,
                                bool preferRecorded = true);
// Any brick source (a Cartesian grid rendered as it is): what the source knows without an FCC store.
// The file, the bricks that vary, the range the reconstruction takes (valueMin/Max), and a histogram
// over it of the stored values (the samples, or a prefiltered reconstruction's coefficients: then
// histogramOfSamples is false) at the 16^3 sites of up to `maxBricks` varying bricks spread evenly over
// them, decoded as the renderer decodes them. No data range, samples count or grid name.
DatasetSummary summarizeSource(const BrickSource& source, std::size_t maxBricks = 256, int bins = 64);

}  // namespace fcc::render
