// The preprocessing kernels (kernels/preprocess.cl through ClBrickKernels) against the C++/TBB
// reference (sparse/BrickBounds.cpp), brick by brick and as whole grids, on random data with touching
// and isolated bricks and tiles: the prefilter bit for bit; the bounds within kBoundsTol, since the
// kernel sums each distinct BB-coefficient once, in another order than the reference's per-piece
// sums. Skipped without OpenCL, failed when CI is set.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

#include "kernels/ClBrickKernels.h"
#include "tests/kernels/ClTestSuite.h"
#include "sparse/BrickBounds.h"
#include "sparse/BrickKernels.h"
#include "tests/sparse/BrickTestData.h"

namespace fcc {
namespace {

using openvdb::Coord;

class Preprocess : public test::ClSuite<ClBrickKernels> {};

// Bricks with a leaf, bricks beside leaves and tiles, and bricks far from anything.
std::vector<Coord> someBricks() {
  std::vector<Coord> bricks;
  for (int z = -2; z <= 2; ++z)
    for (int y = -1; y <= 6; ++y)
      for (int x = -2; x <= 7; ++x) bricks.emplace_back(x, y, z);
  for (const Coord& b : {Coord(-4, -3, 2), Coord(-8, 4, 1), Coord(-1, 5, -3), Coord(0, 5, -3), Coord(-5, 3, -4), Coord(40, 40, 40)})
    bricks.push_back(b);
  return bricks;
}

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Two float sums of at most 13 terms of |w c| <= 24 max|c|, scaled by 1/24: each is within
// 13 * 2^-24 * max|c| (about 8e-7) of the exact value. The test data has |c| <= 1.
constexpr float kBoundsTol = 2e-6f;

TEST_F(Preprocess, BoundsKernelEqualsReferenceWithinTolerance) {
  const FccGrid::Ptr grid = test::randomBrickGrid(3);
  const std::vector<Coord> bricks = someBricks();
  std::vector<openvdb::Vec2f> expected, actual;
  makeReferenceBrickKernels()->bounds(*grid, bricks, expected);
  device->bounds(*grid, bricks, actual);
  ASSERT_EQ(actual.size(), bricks.size());
  int varying = 0, bitEqual = 0;
  float largest = 0.0f;
  for (size_t i = 0; i < bricks.size(); ++i) {
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(actual[i][k], expected[i][k], kBoundsTol)
          << "brick " << bricks[i] << ": OpenCL " << actual[i] << ", reference " << expected[i];
      largest = std::max(largest, std::abs(actual[i][k] - expected[i][k]));
      bitEqual += sameBits(actual[i][k], expected[i][k]);
    }
    varying += expected[i][0] < expected[i][1];
  }
  EXPECT_GT(varying, 20) << "the data exercises varying bricks";
  std::printf("[   INFO   ] %zu bricks on %s: %d of %zu bounds bit-equal, largest difference %g\n", bricks.size(),
              device->describe().c_str(), bitEqual, 2 * bricks.size(), double(largest));
}

TEST_F(Preprocess, PrefilterKernelEqualsReferenceBitForBit) {
  const FccGrid::Ptr grid = test::randomBrickGrid(4);
  const std::vector<Coord> bricks = someBricks();
  std::vector<openvdb::Vec4f> expected, actual;
  makeReferenceBrickKernels()->prefilter(*grid, bricks, expected);
  device->prefilter(*grid, bricks, actual);
  ASSERT_EQ(actual.size(), expected.size());
  size_t mismatches = 0;
  for (size_t i = 0; i < expected.size(); ++i)
    for (int c = 0; c < 4; ++c)
      if (!sameBits(actual[i][c], expected[i][c]) && ++mismatches < 10)
        ADD_FAILURE() << "brick " << bricks[i / 512] << " voxel " << i % 512 << " channel " << c << ": OpenCL "
                      << actual[i][c] << ", reference " << expected[i][c];
  EXPECT_EQ(mismatches, 0u);
}

TEST_F(Preprocess, WholeGridsEqualReference) {
  const FccGrid::Ptr grid = test::randomBrickGrid(5);
  const BoundsGrid::Ptr expected = computeBrickBounds(*grid);
  const BoundsGrid::Ptr actual = computeBrickBounds(*grid, device.get());
  EXPECT_NEAR(double(actual->activeVoxelCount()), double(expected->activeVoxelCount()), 0.01 * expected->activeVoxelCount());
  auto a = actual->getConstAccessor();
  for (auto it = expected->cbeginValueAll(); it; ++it) {
    const openvdb::CoordBBox box = it.getBoundingBox();
    if (box.volume() > 64) continue;  // large tiles: their corners below
    for (auto c = box.begin(); c; ++c) {
      const openvdb::Vec2f b = a.getValue(*c);
      ASSERT_NEAR(b[0], (*it)[0], kBoundsTol) << "brick " << *c;
      ASSERT_NEAR(b[1], (*it)[1], kBoundsTol) << "brick " << *c;
      if ((*it)[1] - (*it)[0] > kBoundsTol) {
        ASSERT_TRUE(a.isValueOn(*c)) << "brick " << *c;
      }
    }
  }

  grid->insertMeta(meta::kValues, openvdb::StringMetadata(kValuesSamples));
  const FccGrid::Ptr expectedCoefficients = prefilterGrid(*grid);
  const FccGrid::Ptr actualCoefficients = prefilterGrid(*grid, device.get());
  EXPECT_EQ(actualCoefficients->activeVoxelCount(), expectedCoefficients->activeVoxelCount());
  EXPECT_EQ(actualCoefficients->tree().leafCount(), expectedCoefficients->tree().leafCount());
  auto ac = actualCoefficients->getConstAccessor();
  for (auto it = expectedCoefficients->cbeginValueOn(); it; ++it) ASSERT_EQ(ac.getValue(it.getCoord()), *it) << it.getCoord();
}

TEST(PreprocessDevices, SelectorsAreCheckedAndReferenceIsAlwaysThere) {
  EXPECT_EQ(checkDeviceSelector("auto"), "");
  EXPECT_EQ(checkDeviceSelector("reference"), "");
  EXPECT_EQ(checkDeviceSelector("1"), "");
  const std::string complaint = checkDeviceSelector("fastest");
  EXPECT_NE(complaint.find("reference"), std::string::npos) << complaint;
  EXPECT_NE(complaint.find("gpu"), std::string::npos) << complaint;
  EXPECT_THROW(makeBrickKernels("fastest"), ValueError);
  EXPECT_EQ(makeBrickKernels("reference")->describe(), "reference (C++/TBB)");
}

}  // namespace
}  // namespace fcc
