// The loader's halo blocks (io::assembleHaloBlock over the host cache, rows copied from bricks kept
// x-fastest) against the grid read whole by OpenVDB: every voxel of every block, including those from
// neighbours without a leaf (tiles, the background); through a memo cleared per chunk as the loader
// does, and through one that overflows and clears itself.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "RenderTestSupport.h"
#include "io/BrickCache.h"
#include "sparse/SynthFields.h"
#include "tests/tools/RunCommand.h"

namespace fcc {
namespace {

TEST(HaloBlocks, EveryVoxelIsTheGridsValue) {
  test::TempDir dir;
  const std::string path = dir / "blobs.vdb";
  SynthSpec spec;
  spec.kind = "blobs";  // sparse: leaves next to empty space, so neighbours of every kind
  spec.dims = glm::ivec3(96);
  test::writeFccFile(path, *makeSynthField(spec).field);
  const io::BrickStore store(path);
  const FccGrid::Ptr grid = io::readFccGrid(path);  // the slow reference: every value, read normally
  ASSERT_TRUE(grid);
  const auto accessor = grid->getConstAccessor();
  // A cache smaller than the bricks touched: evictions happen while blocks are assembled.
  io::BrickCache cache(store, 40 * io::BrickCache::kBytesPerBrick);
  std::vector<float> block(size_t(io::kHaloBlockVoxels) * 4);
  // clearEvery 3: the loader's pattern (a memo a chunk); 0: one memo for every block, which fills it
  // past what it holds (256 bricks) so that it clears itself mid-block.
  for (const int clearEvery : {3, 0}) {
    SCOPED_TRACE("memo cleared every " + std::to_string(clearEvery) + " blocks (0: never)");
    io::BrickValuesMemo memo(cache);
    int blocks = 0;
    std::set<std::tuple<int, int, int>> touched;
    for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf) {
      const glm::ivec3 brick(leaf->origin().x() / kBrickPackedDim, leaf->origin().y() / kBrickPackedDim,
                             leaf->origin().z() / kBrickPackedDim);
      if (clearEvery > 0 && blocks % clearEvery == 0) memo.clear();
      io::assembleHaloBlock(store, memo, brick, block.data());
      for (int nz = -1; nz <= 1; ++nz)
        for (int ny = -1; ny <= 1; ++ny)
          for (int nx = -1; nx <= 1; ++nx) touched.emplace(brick.x + nx, brick.y + ny, brick.z + nz);
      constexpr int H = io::kHaloBlockDim;
      for (int z = 0; z < H; ++z)
        for (int y = 0; y < H; ++y)
          for (int x = 0; x < H; ++x) {
            const openvdb::Coord voxel(brick.x * kBrickPackedDim - 1 + x, brick.y * kBrickPackedDim - 1 + y,
                                       brick.z * kBrickPackedDim - 1 + z);
            const openvdb::Vec4f expected = accessor.getValue(voxel);
            for (int c = 0; c < 4; ++c)
              ASSERT_EQ(block[4 * ((z * H + y) * H + x) + c], expected[c])
                  << "brick (" << brick.x << ", " << brick.y << ", " << brick.z << ") block voxel (" << x << ", "
                  << y << ", " << z << ") channel " << c;
          }
      ++blocks;
    }
    EXPECT_GT(blocks, 20);
    EXPECT_GT(touched.size(), 256u) << "the never-cleared memo must overflow what it holds";
  }
}

}  // namespace
}  // namespace fcc
