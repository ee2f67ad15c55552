// The Cartesian brick store (direct rendering of float grids, issue 17) against OpenVDB's own reads: every
// point of a brick's block, and the per-brick ranges, for a level set (interior tiles, exterior background)
// and a fog volume (interior tiles of 1).
#include <gtest/gtest.h>

#include <openvdb/io/File.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "LeafDamage.h"
#include "io/CartesianBrickStore.h"
#include "io/VdbFile.h"
#include "sparse/Error.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using Store = CartesianBrickStore;

std::string writeGrid(const test::TempDir& dir, const std::string& name, openvdb::FloatGrid::Ptr grid) {
  initializeVdb();
  const std::string path = dir / (name + ".vdb");
  grid->setName(name);
  openvdb::io::File file(path);
  file.write({grid});
  file.close();
  return path;
}

void expectBlocksAndRangesMatch(const std::string& path, const openvdb::FloatGrid& grid) {
  const Store store(path);
  EXPECT_EQ(store.background(), grid.background());
  ASSERT_FALSE(store.activeBrickBox().empty());
  const auto ranges = store.computeBrickRanges();
  ASSERT_FALSE(ranges.empty());
  std::set<std::tuple<int, int, int>> listed;
  for (const auto& r : ranges) listed.insert({r.brick.x, r.brick.y, r.brick.z});
  const auto accessor = grid.getConstAccessor();
  std::vector<float> block(Store::kBlockPoints);
  int checked = 0, listedBackgroundOnly = 0;
  // Every brick of the active box and one layer around it.
  const openvdb::CoordBBox box = store.activeBrickBox();
  for (int bz = box.min().z() - 1; bz <= box.max().z() + 1; ++bz)
    for (int by = box.min().y() - 1; by <= box.max().y() + 1; ++by)
      for (int bx = box.min().x() - 1; bx <= box.max().x() + 1; ++bx) {
        const glm::ivec3 brick(bx, by, bz);
        store.readBlock(brick, block.data());
        bool allBackground = true;
        float lo = block[0], hi = block[0];
        for (int z = 0; z < Store::kBlockDim; ++z)
          for (int y = 0; y < Store::kBlockDim; ++y)
            for (int x = 0; x < Store::kBlockDim; ++x) {
              const openvdb::Coord p(16 * bx - 2 + x, 16 * by - 2 + y, 16 * bz - 2 + z);
              const float v = block[(z * Store::kBlockDim + y) * Store::kBlockDim + x];
              ASSERT_EQ(v, accessor.getValue(p)) << "brick (" << bx << ", " << by << ", " << bz << ") point " << p;
              allBackground = allBackground && v == grid.background();
              lo = std::min(lo, v);
              hi = std::max(hi, v);
            }
        const bool inList = listed.count({bx, by, bz}) > 0;
        // Conservative: a brick whose block holds anything but the background is listed (the ranges are
        // made of whole leaves, so a few bricks next to data are listed too).
        if (!allBackground) EXPECT_TRUE(inList) << "brick (" << bx << ", " << by << ", " << bz << ")";
        listedBackgroundOnly += inList && allBackground;
        if (inList) {
          const auto& r = *std::find_if(ranges.begin(), ranges.end(), [&](const auto& e) { return e.brick == brick; });
          EXPECT_LE(r.lo, lo);
          EXPECT_GE(r.hi, hi);
        }
        ++checked;
      }
  EXPECT_GT(checked, 27);
  // Most listed bricks do hold data.
  EXPECT_LT(listedBackgroundOnly, int(ranges.size()) / 2) << listedBackgroundOnly << " of " << ranges.size();
}

TEST(CartesianBrickStore, LevelSetBlocksAndRangesMatchOpenVdb) {
  test::TempDir dir;
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(21.0f, openvdb::Vec3f(1.5f, -2.0f, 3.0f), 1.0f, 3.0f);
  const std::string path = writeGrid(dir, "ls", grid);
  EXPECT_TRUE(Store(path).levelSet());
  expectBlocksAndRangesMatch(path, *grid);
}

TEST(CartesianBrickStore, FogVolumeWithInteriorTilesMatchesOpenVdb) {
  test::TempDir dir;
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(30.0f, openvdb::Vec3f(0.0f), 1.0f, 3.0f);
  openvdb::tools::sdfToFogVolume(*grid);
  const std::string path = writeGrid(dir, "fog", grid);
  EXPECT_FALSE(Store(path).levelSet());
  expectBlocksAndRangesMatch(path, *grid);
}

TEST(CartesianBrickStore, NotAFloatGridIsOneLine) {
  test::TempDir dir;
  const std::string path = dir / "v.vdb";
  initializeVdb();
  auto grid = openvdb::Vec3SGrid::create();
  grid->setName("v");
  openvdb::io::File file(path);
  file.write({grid});
  file.close();
  try {
    Store store(path);
    FAIL() << "opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

// A dense fog-like grid on [0, 48)^3 (every leaf present), values z + x / 64 (all below the background).
openvdb::FloatGrid::Ptr denseGrid(float background) {
  auto grid = openvdb::FloatGrid::create(background);
  auto accessor = grid->getAccessor();
  for (int z = 0; z < 48; ++z)
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 48; ++x) accessor.setValue(openvdb::Coord(x, y, z), float(z) + float(x) / 64.0f);
  return grid;
}

// A leaf whose bytes are damaged is never trusted and never fails a read: it reads as the background
// in every block and box that holds it (its own brick's and its neighbours'), the ranges hold the
// background where the blocks do, every other point reads as stored, and the damage is recorded once,
// naming the file and the leaf.
TEST(CartesianBrickStore, DamagedLeafReadsAsTheBackgroundAndIsRecordedOnce) {
  test::TempDir dir;
  const float background = 100.0f;
  auto grid = denseGrid(background);
  const std::string path = writeGrid(dir, "dense", grid);
  const openvdb::Coord damagedOrigin(16, 8, 24);
  test::damageLeafValues(path, {"Tree_float_5_4_3"}, damagedOrigin);
  const openvdb::CoordBBox damagedBox(damagedOrigin, damagedOrigin.offsetBy(7));

  const Store store(path);
  EXPECT_EQ(store.damage().count, 0u) << "opening reads no leaf";
  const auto ranges = store.computeBrickRanges();
  const Damage damage = store.damage();
  EXPECT_EQ(damage.count, 1u);
  EXPECT_EQ(damage.unit, "leaf");
  EXPECT_EQ(damagedCountText(damage), "1 damaged leaf");
  EXPECT_NE(damage.first.find(path), std::string::npos) << damage.first;
  EXPECT_NE(damage.first.find("leaf at (16, 8, 24) is damaged"), std::string::npos) << damage.first;
  ASSERT_EQ(damage.messages.size(), 1u);

  const auto accessor = grid->getConstAccessor();
  std::vector<float> block(Store::kBlockPoints);
  int damagedPoints = 0;
  // Every brick whose block holds a point of the damaged leaf (leaf 2 b + {-1 .. 2} of brick b).
  for (int bz = 1; bz <= 2; ++bz)
    for (int by = 0; by <= 1; ++by)
      for (int bx = 0; bx <= 1; ++bx) {
        const glm::ivec3 brick(bx, by, bz);
        store.readBlock(brick, block.data());
        float lo = INFINITY, hi = -INFINITY;
        for (int z = 0; z < Store::kBlockDim; ++z)
          for (int y = 0; y < Store::kBlockDim; ++y)
            for (int x = 0; x < Store::kBlockDim; ++x) {
              const openvdb::Coord p(16 * bx - 2 + x, 16 * by - 2 + y, 16 * bz - 2 + z);
              const float v = block[(z * Store::kBlockDim + y) * Store::kBlockDim + x];
              const bool damaged = damagedBox.isInside(p);
              damagedPoints += damaged;
              ASSERT_EQ(v, damaged ? background : accessor.getValue(p)) << "brick " << brick.x << brick.y << brick.z << " point " << p;
              lo = std::min(lo, v);
              hi = std::max(hi, v);
            }
        const auto r = std::find_if(ranges.begin(), ranges.end(), [&](const auto& e) { return e.brick == brick; });
        ASSERT_NE(r, ranges.end()) << "brick " << brick.x << brick.y << brick.z;
        EXPECT_LE(r->lo, lo);
        EXPECT_GE(r->hi, hi) << "the range must hold the background the block now holds";
      }
  // Per axis the leaf's 8 points in one block and 2 in the other: (8 + 2)^3 over the eight blocks.
  EXPECT_EQ(damagedPoints, 1000);
  EXPECT_EQ(store.damage().count, 1u) << "each damaged leaf is recorded once";
}

}  // namespace
}  // namespace fcc::io
