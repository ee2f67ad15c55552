// The viewer's dataset summary: counts from the index agree with the grid read fully, and the
// histogram counts every active value of the bricks it samples into the right bin.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

#include "RenderTestSupport.h"
#include "tests/tools/RunCommand.h"
#include "sparse/SynthFields.h"
#include "viewer/DatasetSummary.h"

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

}  // namespace
}  // namespace fcc
