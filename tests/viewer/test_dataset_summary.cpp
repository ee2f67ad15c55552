// The viewer's dataset summary: counts from the index agree with the grid read fully, and the
// histogram counts every active value of the bricks it samples into the right bin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "RenderTestSupport.h"
#include "io/DefaultIsovalue.h"
#include "tests/tools/RunCommand.h"
#include "sparse/SynthFields.h"
#include "sparse/SampleHistogram.h"
#include "viewer/DatasetSummary.h"
#include "viewer/HistogramAxis.h"

namespace fcc {
namespace {

TEST(DatasetSummary, CountsAndHistogramMatchTheFullGrid) {
  test::TempDir dir;
  const std::string path = dir / "ml.vdb";
  SynthSpec spec;
  spec.kind = "marschner-lobb";
  spec.dims = glm::ivec3(40);
  test::writeFccFile(path, *makeSynthField(spec).field);

  const io::BrickStore store(path);
  const int bins = 16;
  const render::DatasetSummary all = render::summarizeDataset(store, 1 << 20, bins);
  const FccGrid::Ptr grid = io::readFccGrid(path);  // every value, read normally
  ASSERT_TRUE(grid);
  EXPECT_EQ(all.samples, grid->activeVoxelCount() * 4);
  EXPECT_EQ(all.bricks, grid->tree().leafCount());
  EXPECT_EQ(all.histogramBricks, all.bricks);
  EXPECT_EQ(all.histogramValues, all.samples);

  std::vector<float> expected(bins, 0.0f);
  const float span = all.valueMax - all.valueMin;
  ASSERT_GT(span, 0.0f);
  for (auto v = grid->cbeginValueOn(); v; ++v) {
    if (!v.isVoxelValue()) continue;
    for (int c = 0; c < 4; ++c) {
      const int bin = std::clamp(int((v.getValue()[c] - all.valueMin) / span * bins), 0, bins - 1);
      expected[bin] += 1.0f;
    }
  }
  for (int b = 0; b < bins; ++b) EXPECT_EQ(all.histogram[b], expected[b]) << "bin " << b;
  EXPECT_GT(*std::max_element(all.histogram.begin(), all.histogram.end()), 0.0f);

  // A bounded sample reads no more bricks than asked (spread over the file).
  const render::DatasetSummary few = render::summarizeDataset(store, 3, bins);
  EXPECT_LE(few.histogramBricks, 3u);
  EXPECT_GE(few.histogramBricks, 1u);
  EXPECT_EQ(std::accumulate(few.histogram.begin(), few.histogram.end(), 0.0), double(few.histogramValues));
}

// A file that records its samples' histogram (synth, convert) gives the panel that one: every
// sample, over the data range, merged into equal bins, and no brick decoded for it.
TEST(DatasetSummary, RecordedSampleHistogramIsPreferred) {
  test::TempDir dir;
  const io::BrickStore store(test::writeSmallBlobs(dir));
  const std::optional<SampleSummary> recorded = recordedSamples(store.index());
  ASSERT_TRUE(recorded && !recorded->histogram.empty()) << "synth records no histogram: nothing to prefer";
  const render::DatasetSummary s = render::summarizeDataset(store, 256, 64);
  EXPECT_TRUE(s.histogramOfSamples);
  EXPECT_EQ(s.histogramBricks, 0u);
  EXPECT_EQ(s.histogramMin, recorded->min);
  EXPECT_EQ(s.histogramMax, recorded->max);
  ASSERT_EQ(s.histogram.size(), 64u);
  const std::size_t group = recorded->histogram.size() / 64;
  for (std::size_t b = 0; b < s.histogram.size(); ++b) {
    double expected = 0.0;
    for (std::size_t k = 0; k < group; ++k) expected += double(recorded->histogram[b * group + k]);
    EXPECT_EQ(double(s.histogram[b]), expected) << "bin " << b;
  }
  EXPECT_EQ(s.histogramValues, recorded->total());
  const render::DatasetSummary coefficients = render::summarizeDataset(store, 256, 64, /*preferRecorded=*/false);
  EXPECT_FALSE(coefficients.histogramOfSamples);
  EXPECT_GT(coefficients.histogramBricks, 0u);
  EXPECT_EQ(coefficients.histogramMin, coefficients.valueMin);
}

// One figure for each range everywhere (issue 16, item 1): the panel's "data range" (the samples') and
// "surface range" (the spline's, the slider's) are info --json's sample_min/max and min/max, and the
// isovalue render, view and bench render start at is info's suggested_iso (io/DefaultIsovalue.h).
TEST(DatasetSummary, RangesAndDefaultIsovalueAreThoseInfoPrints) {
  test::TempDir dir;
  const std::string path = test::writeSmallBlobs(dir);
  const test::CommandResult info = test::runFccvdb("info " + path + " --json");
  ASSERT_EQ(info.status, 0) << info.err;
  const auto number = [&](const std::string& key) {
    const std::size_t at = info.out.find("\"" + key + "\": ");
    EXPECT_NE(at, std::string::npos) << key << " in " << info.out;
    return at == std::string::npos ? std::nan("") : std::stod(info.out.substr(at + key.size() + 4));
  };
  const io::BrickStore store(path);
  const render::DatasetSummary s = render::summarizeDataset(store);
  ASSERT_TRUE(s.hasDataRange);
  EXPECT_EQ(s.dataMin, float(number("sample_min")));  // info prints floats with the 9 digits that round-trip them
  EXPECT_EQ(s.dataMax, float(number("sample_max")));
  EXPECT_EQ(s.valueMin, float(number("min")));
  EXPECT_EQ(s.valueMax, float(number("max")));
  EXPECT_LT(s.valueMin, s.dataMin) << "the spline overshoots the samples: two ranges, so the test can tell them apart";
  EXPECT_EQ(io::defaultIsovalue(store).value, float(number("suggested_iso")));
}

TEST(HistogramAxis, BinsAndPositions) {
  const render::HistogramAxis axis{-2.0f, 6.0f, 4};  // bins of 2
  EXPECT_EQ(axis.binAt(0.0f), 0);
  EXPECT_EQ(axis.binAt(0.49f), 1);
  EXPECT_EQ(axis.binAt(1.0f), 3) << "the right edge belongs to the last bin";
  EXPECT_EQ(axis.binAt(-3.0f), 0);
  EXPECT_EQ(axis.binLow(1), 0.0f);
  EXPECT_EQ(axis.binHigh(1), 2.0f);
  EXPECT_EQ(axis.valueAt(0.75f), 4.0f);
  EXPECT_EQ(axis.positionOf(4.0f), 0.75f);
  EXPECT_EQ(axis.positionOf(100.0f), 1.0f);
}

}  // namespace
}  // namespace fcc
