// The vectorised brick prefilter (sparse/PrefilterBricks) against the definition, spline::prefilterAt
// at every site through a value accessor, bit for bit: on random data around leaves, tiles (of every
// level) and the background, and as the whole grid prefilterGrid builds from it.
#include <gtest/gtest.h>

#include <cstring>

#include "BrickTestData.h"
#include "sparse/BrickBounds.h"
#include "sparse/Lattice.h"
#include "sparse/PrefilterBricks.h"
#include "sparse/Spline.h"

namespace fcc {
namespace {

using openvdb::Coord;
using openvdb::Vec4f;

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// q_fcc at the channel-c site of packed voxel `packed`, from its definition.
float prefilterByDefinition(FccGrid::ConstAccessor& accessor, const glm::ivec3& packed, int c) {
  return spline::prefilterAt(siteOfChannel(packed, c), [&](const glm::ivec3& ijk) {
    const glm::ivec3 p = packedVoxelOfSite(ijk);
    return accessor.getValue(Coord(p.x, p.y, p.z))[channelOfSite(ijk)];
  });
}

TEST(PrefilterBricks, EqualsTheDefinitionAtEverySiteBitForBit) {
  const FccGrid::Ptr grid = test::randomBrickGrid(11);
  // Bricks with leaves, beside leaves and tiles, inside the level-2 tile, and far away.
  std::vector<Coord> bricks;
  for (int z = -4; z <= 2; ++z)
    for (int y = -4; y <= 6; ++y)
      for (int x = -9; x <= 7; ++x) bricks.emplace_back(x, y, z);
  bricks.emplace_back(40, -40, 40);
  std::vector<Vec4f> out(bricks.size() * 512);
  prefilterBricks(*grid, bricks, out.data());

  auto accessor = grid->getConstAccessor();
  size_t mismatches = 0, differentFromBackground = 0;
  for (size_t i = 0; i < bricks.size(); ++i)
    for (int n = 0; n < 512; ++n) {
      const glm::ivec3 packed = glm::ivec3(bricks[i].x(), bricks[i].y(), bricks[i].z()) * 8 + glm::ivec3(n >> 6, (n >> 3) & 7, n & 7);
      for (int c = 0; c < 4; ++c) {
        const float expected = prefilterByDefinition(accessor, packed, c), actual = out[i * 512 + n][c];
        differentFromBackground += expected != test::kBrickTestBackground;
        if (!sameBits(actual, expected) && ++mismatches <= 10)
          ADD_FAILURE() << "brick " << bricks[i] << " voxel " << n << " channel " << c << ": prefilterBricks " << actual
                        << ", definition " << expected;
      }
    }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(differentFromBackground, 100000u) << "the data exercises leaves and tiles, not only the background";
}

TEST(PrefilterBricks, WholeGridEqualsTheDefinition) {
  const FccGrid::Ptr samples = test::randomBrickGrid(12, 0.5f);
  samples->insertMeta(meta::kValues, openvdb::StringMetadata(kValuesSamples));
  const FccGrid::Ptr coefficients = prefilterGrid(*samples);
  auto in = samples->getConstAccessor();
  auto out = coefficients->getConstAccessor();
  // Every packed voxel of the bricks around the data, active or not.
  size_t checked = 0;
  for (int z = -4 * 8; z < 3 * 8; ++z)
    for (int y = -4 * 8; y < 7 * 8; ++y)
      for (int x = -9 * 8; x < 8 * 8; ++x) {
        const Vec4f actual = out.getValue(Coord(x, y, z));
        for (int c = 0; c < 4; ++c) {
          const float expected = prefilterByDefinition(in, glm::ivec3(x, y, z), c);
          ASSERT_TRUE(sameBits(actual[c], expected))
              << "packed voxel " << Coord(x, y, z) << " channel " << c << ": " << actual[c] << " against " << expected;
        }
        ++checked;
      }
  EXPECT_EQ(checked, size_t(7 * 11 * 17) * 512);
}

}  // namespace
}  // namespace fcc
