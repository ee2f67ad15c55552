// Preprocessing through files: the bounds grid stored beside the FCC grid and found again, the
// prefilter of a --no-prefilter grid equal to the builder's, and the bounds' tightness on the engine CT.
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>

#include "io/Convert.h"
#include "io/VdbFile.h"
#include "sparse/BoundsHierarchy.h"
#include "sparse/BrickBounds.h"
#include "sparse/Lattice.h"
#include "sparse/Spline.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using openvdb::Coord;
using test::TempDir;

// A 64x64x48 f32 volume: random values in an ellipsoid, zero (the background) around it, and a
// constant box large enough that whole bricks of samples and of coefficients are uniform (tiles).
std::string writeSparseRaw(const TempDir& dir, RawLayout& layout) {
  const glm::ivec3 dims(64, 64, 48);
  std::vector<float> values(size_t(dims.x) * dims.y * dims.z);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> d(0.0f, 1.0f);
  for (int z = 0; z < dims.z; ++z)
    for (int y = 0; y < dims.y; ++y)
      for (int x = 0; x < dims.x; ++x) {
        const glm::vec3 r = (glm::vec3(x, y, z) - glm::vec3(dims) * 0.5f) / (glm::vec3(dims) * 0.45f);
        float v = glm::dot(r, r) < 1.0f ? d(rng) : 0.0f;
        if (x >= 8 && x < 56 && y >= 8 && y < 56 && z >= 8 && z < 40) v = 0.75f;
        values[(size_t(z) * dims.y + y) * dims.x + x] = v;
      }
  layout.dims = dims;
  layout.type = ScalarType::F32;
  const std::string path = dir / "sparse.raw";
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
  return path;
}

bool sameBits(const openvdb::Vec4f& a, const openvdb::Vec4f& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every value and active state of a equals b's, and the other way round.
void expectSameGrids(const FccGrid& a, const FccGrid& b) {
  EXPECT_EQ(a.activeVoxelCount(), b.activeVoxelCount());
  EXPECT_EQ(a.tree().leafCount(), b.tree().leafCount());
  EXPECT_EQ(a.tree().activeTileCount(), b.tree().activeTileCount());
  for (const auto* pair : {&a, &b}) {
    const FccGrid& other = pair == &a ? b : a;
    auto acc = other.getConstAccessor();
    int mismatches = 0;
    for (auto it = pair->cbeginValueOn(); it; ++it) {
      if (!it.isVoxelValue()) {
        EXPECT_TRUE(sameBits(acc.getValue(it.getCoord()), *it)) << "tile at " << it.getCoord();
        continue;
      }
      if ((!sameBits(acc.getValue(it.getCoord()), *it) || !acc.isValueOn(it.getCoord())) && ++mismatches < 5)
        ADD_FAILURE() << "at packed voxel " << it.getCoord() << ": " << *it << " vs " << acc.getValue(it.getCoord());
    }
    EXPECT_EQ(mismatches, 0);
  }
}

TEST(PreprocessFiles, PrefilterGridEqualsTheBuilders) {
  TempDir dir;
  ConvertOptions o;
  o.raw.emplace();
  const std::string raw = writeSparseRaw(dir, *o.raw);
  convertToFcc(raw, dir / "coefficients.vdb", o);
  o.prefilter = false;
  convertToFcc(raw, dir / "samples.vdb", o);
  const FccGrid::Ptr coefficients = readFccGrid(dir / "coefficients.vdb");
  const FccGrid::Ptr samples = readFccGrid(dir / "samples.vdb");
  ASSERT_TRUE(storesSamples(*samples));
  EXPECT_GT(samples->tree().activeTileCount(), 0u) << "the samples hold uniform bricks";
  const FccGrid::Ptr prefiltered = prefilterGrid(*samples);
  EXPECT_FALSE(storesSamples(*prefiltered));
  EXPECT_EQ(prefiltered->getName(), coefficients->getName());
  expectSameGrids(*prefiltered, *coefficients);
}

TEST(PreprocessFiles, BoundsAreStoredBesideTheGridAndFound) {
  TempDir dir;
  ConvertOptions o;
  o.raw.emplace();
  const std::string raw = writeSparseRaw(dir, *o.raw);
  const ConvertSummary summary = convertToFcc(raw, dir / "with.vdb", o);
  EXPECT_GT(summary.boundsBricks, 0u);
  const auto grids = listGrids(dir / "with.vdb");
  ASSERT_EQ(grids.size(), 2u);
  EXPECT_TRUE(grids[0].fcc);
  EXPECT_FALSE(grids[1].fcc) << "the bounds grid is not an FCC grid";
  EXPECT_EQ(grids[1].name, boundsGridName(grids[0].name));
  const FccWithBounds with = readFccGridWithBounds(dir / "with.vdb");
  ASSERT_TRUE(with.bounds);
  EXPECT_EQ(with.bounds->activeVoxelCount(), summary.boundsBricks);
  EXPECT_EQ(readFccGrid(dir / "with.vdb")->getName(), grids[0].name);
  EXPECT_TRUE(readBoundsGrid(dir / "with.vdb", grids[0].name));

  // Raw samples: the bounds are those of the prefiltered coefficients, the same as above.
  o.prefilter = false;
  convertToFcc(raw, dir / "samples.vdb", o);
  const FccWithBounds samples = readFccGridWithBounds(dir / "samples.vdb");
  ASSERT_TRUE(samples.bounds);
  EXPECT_EQ(samples.bounds->activeVoxelCount(), with.bounds->activeVoxelCount());
  auto acc = samples.bounds->getConstAccessor();
  for (auto it = with.bounds->cbeginValueOn(); it; ++it) ASSERT_EQ(acc.getValue(it.getCoord()), *it) << it.getCoord();

  // Files written before bounds existed have none.
  o.bounds = false;
  convertToFcc(raw, dir / "without.vdb", o);
  EXPECT_EQ(listGrids(dir / "without.vdb").size(), 1u);
  EXPECT_FALSE(readFccGridWithBounds(dir / "without.vdb").bounds);
}

TEST(PreprocessFiles, HalfStoredBoundsAreThoseOfTheStoredValues) {
  // Bounds of the float values would not bound the half-rounded spline a reader evaluates.
  TempDir dir;
  ConvertOptions o;
  o.raw.emplace();
  const std::string raw = writeSparseRaw(dir, *o.raw);
  o.half = true;
  convertToFcc(raw, dir / "half.vdb", o);
  const FccWithBounds file = readFccGridWithBounds(dir / "half.vdb");
  ASSERT_TRUE(file.bounds);
  const BoundsGrid::Ptr recomputed = computeBrickBounds(*file.grid);
  EXPECT_EQ(recomputed->activeVoxelCount(), file.bounds->activeVoxelCount());
  auto acc = recomputed->getConstAccessor();
  int differ = 0;
  for (auto it = file.bounds->cbeginValueOn(); it; ++it) differ += acc.getValue(it.getCoord()) != *it;
  EXPECT_EQ(differ, 0) << "bricks whose stored bounds are not those of the stored values";
}

// Whether the spline takes values on both sides of `iso` in brick b: sampled at the points of spacing
// 1/2 in the brick's closed box, from the brick's halo of coefficients.
bool brickHoldsSurface(FccGrid::ConstAccessor& accessor, const Coord& b, float iso) {
  std::vector<float> block(10 * 10 * 10 * 4);
  const glm::ivec3 origin = glm::ivec3(b.x(), b.y(), b.z()) * kBrickPackedDim - 1;
  for (int z = 0; z < 10; ++z)
    for (int y = 0; y < 10; ++y)
      for (int x = 0; x < 10; ++x) {
        const openvdb::Vec4f v = accessor.getValue(Coord(origin.x + x, origin.y + y, origin.z + z));
        for (int c = 0; c < 4; ++c) block[((z * 10 + y) * 10 + x) * 4 + c] = v[c];
      }
  auto coefficientAt = [&](const glm::ivec3& ijk) {
    const glm::ivec3 p = packedVoxelOfSite(ijk) - origin;
    return block[((p.z * 10 + p.y) * 10 + p.x) * 4 + channelOfSite(ijk)];
  };
  bool below = false, above = false;
  const glm::vec3 first = glm::vec3(b.x(), b.y(), b.z()) * float(kBrickSites);
  for (int z = 0; z <= 2 * kBrickSites; ++z)
    for (int y = 0; y <= 2 * kBrickSites; ++y)
      for (int x = 0; x <= 2 * kBrickSites; ++x) {
        const float v = spline::evaluate(first + 0.5f * glm::vec3(x, y, z), coefficientAt);
        below = below || v < iso;
        above = above || v > iso;
        if (below && above) return true;
      }
  return false;
}

TEST(PreprocessFiles, EngineBoundsAreTight) {
  const std::string engine = std::string(FCC_SHARED_DATA_DIR) + "/engine_256x256x128_uint8.raw.gz";
  if (!std::ifstream(engine)) GTEST_SKIP() << "missing " << engine;
  TempDir dir;
  ConvertOptions o;
  o.raw = RawLayout{glm::ivec3(256, 256, 128), ScalarType::U8, false, glm::dvec3(1.0), 0};
  convertToFcc(engine, dir / "engine.vdb", o);
  const FccWithBounds file = readFccGridWithBounds(dir / "engine.vdb");
  ASSERT_TRUE(file.bounds);
  constexpr float kIso = 100.0f;
  const BoundsHierarchy hierarchy(*file.bounds);
  const uint64_t total = hierarchy.total().bricks;
  const uint64_t kept = hierarchy.kept(kIso).bricks;
  // Bricks the hierarchy drops cannot hold the surface (the bounds are conservative:
  // test_brick_bounds), so only the kept ones are sampled.
  std::vector<Coord> keptBricks;
  for (auto it = file.bounds->cbeginValueOn(); it; ++it)
    if (BoundsHierarchy::holds(*it, kIso)) keptBricks.push_back(it.getCoord());
  ASSERT_EQ(keptBricks.size(), kept);
  std::atomic<uint64_t> actual{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, keptBricks.size()), [&](const tbb::blocked_range<size_t>& r) {
    auto accessor = file.grid->getConstAccessor();
    for (size_t i = r.begin(); i != r.end(); ++i) actual += brickHoldsSurface(accessor, keptBricks[i], kIso);
  });
  std::printf("[   INFO   ] engine at iso %g: the hierarchy keeps %llu of %llu bricks (%.1f%%); %llu (%.1f%%) hold the surface\n",
              double(kIso), (unsigned long long)kept, (unsigned long long)total, 100.0 * double(kept) / double(total),
              (unsigned long long)actual.load(), 100.0 * double(actual.load()) / double(total));
  EXPECT_GT(actual.load(), 100u);
  EXPECT_LT(kept, 2 * actual.load());
}

}  // namespace
}  // namespace fcc::io
