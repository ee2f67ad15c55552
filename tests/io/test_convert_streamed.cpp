// The streamed conversion (a .vdb source read leaf by leaf, tiles made without visiting their sites,
// the output built twice and never held) writes the same file as the in-memory reference path, for
// level sets, fog volumes with interior tiles and dense inputs, with --half, --no-prefilter and a
// background override; and it reads each source leaf about twice, never the volume.
#include <gtest/gtest.h>

#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>

#include <cmath>
#include <fstream>

#include "SameVdbFiles.h"
#include "io/Convert.h"
#include "sparse/FccSampler.h"
#include "io/VdbFile.h"
#include "io/VdbLeafReader.h"
#include "io/VdbSourceField.h"
#include "sparse/FccBlockBuilder.h"
#include "sparse/StreamedBuild.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using test::TempDir;

struct Variant {
  bool prefilter = true;
  bool half = false;
  std::optional<float> background;
};

std::string describe(const Variant& v) {
  std::string s = v.prefilter ? "coefficients" : "--no-prefilter";
  if (v.half) s += " --half";
  if (v.background) s += " --background " + std::to_string(*v.background);
  return s;
}

void writeGrid(const std::string& path, const openvdb::GridBase::Ptr& grid) {
  initializeVdb();
  openvdb::io::File file(path);
  file.write(openvdb::GridCPtrVec{grid});
  file.close();
}

// A narrow-band level set sphere: interior tiles of -background at every level the radius allows.
std::string writeSphere(const TempDir& dir, const std::string& name, float radius, float voxelSize,
                        bool fog = false) {
  initializeVdb();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      radius * voxelSize, openvdb::Vec3f(3.3f, -1.7f, 0.6f) * voxelSize, voxelSize, 3.0f);
  if (fog) openvdb::tools::sdfToFogVolume(*grid);  // interior: active tiles of 1
  grid->setName(name);
  const std::string path = dir / (name + ".vdb");
  writeGrid(path, grid);
  return path;
}

void expectStreamedEqualsInMemory(const TempDir& dir, const std::string& input, const ConvertOptions& base) {
  for (const Variant v : {Variant{}, Variant{true, true, {}}, Variant{false, false, {}}, Variant{true, false, 0.25f}}) {
    SCOPED_TRACE(input + " " + describe(v));
    ConvertOptions o = base;
    o.prefilter = v.prefilter;
    o.half = v.half;
    if (v.background) o.background = v.background;
    o.overwrite = true;
    const std::string streamed = dir / "streamed.vdb", inMemory = dir / "memory.vdb";
    const ConvertSummary s = convertToFcc(input, streamed, o);
    o.inMemory = true;
    const ConvertSummary m = convertToFcc(input, inMemory, o);
    EXPECT_EQ(s.activeSamples, m.activeSamples);
    EXPECT_EQ(s.bricks, m.bricks);
    EXPECT_EQ(s.boundsBricks, m.boundsBricks);
    EXPECT_EQ(s.inputVoxels, m.inputVoxels);
    test::expectSameFccFiles(inMemory, streamed);
  }
}

TEST(ConvertStreamed, LevelSetEqualsTheInMemoryPath) {
  TempDir dir;
  // Radius 150 voxels: level-2 tiles (128^3) inside as well as leaf-sized ones.
  expectStreamedEqualsInMemory(dir, writeSphere(dir, "ls", 150.0f, 0.5f), ConvertOptions{});
}

TEST(ConvertStreamed, FogVolumeWithInteriorTilesEqualsTheInMemoryPath) {
  TempDir dir;
  expectStreamedEqualsInMemory(dir, writeSphere(dir, "fog", 70.0f, 1.0f, true), ConvertOptions{});
}

TEST(ConvertStreamed, ResampleEqualsTheInMemoryPath) {
  TempDir dir;
  ConvertOptions resample;
  resample.mode = "resample";
  resample.scale = 1.3;
  expectStreamedEqualsInMemory(dir, writeSphere(dir, "ls", 40.0f, 1.0f), resample);
  expectStreamedEqualsInMemory(dir, writeSphere(dir, "fog", 30.0f, 1.0f, true), resample);
}

// A leaf without an active voxel lies outside the active box the fields' bounds come from, yet blocks
// at the edge of that box read it: the in-memory path prepares everything they reach.
TEST(ConvertStreamed, ResampleReadsLeavesOutsideTheActiveBox) {
  TempDir dir;
  initializeVdb();
  auto grid = openvdb::FloatGrid::create(0.0f);
  for (int i = 64; i <= 71; ++i) grid->tree().setValueOn(openvdb::Coord(i, 66, 67), float(i - 60));
  grid->tree().touchLeaf(openvdb::Coord(16, 64, 64))->setValueOff(openvdb::Coord(17, 65, 66), 5.0f);
  grid->setName("edge");
  const std::string input = dir / "edge.vdb";
  writeGrid(input, grid);
  ConvertOptions resample;
  resample.mode = "resample";
  resample.scale = 1.0;
  expectStreamedEqualsInMemory(dir, input, resample);
}

// Resampling a level set densifies nothing and interpolates it: near the surface, where the source
// holds signed distances, the samples are the distance to the sphere.
TEST(ConvertStreamed, ResampledLevelSetIsTheSignedDistance) {
  TempDir dir;
  constexpr float kRadius = 60.0f;
  const std::string input = writeSphere(dir, "ls", kRadius, 1.0f);
  ConvertOptions o;
  o.mode = "resample";
  o.scale = 0.8;
  o.prefilter = false;
  convertToFcc(input, dir / "out.vdb", o);
  const FccGrid::Ptr grid = readFccGrid(dir / "out.vdb");
  EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
  const FccSampler sampler(*grid, true);
  const glm::dvec3 centre(3.3, -1.7, 0.6);
  int checked = 0;
  double worst = 0.0;
  for (int k = -90; k <= 90; k += 3)
    for (int j = -90; j <= 90; j += 5)
      for (int i = -90; i <= 90; ++i) {
        if ((i + j + k) & 1) continue;
        const openvdb::Vec3d w = grid->transform().indexToWorld(openvdb::Coord(i, j, k));
        const double distance = glm::length(glm::dvec3(w.x(), w.y(), w.z()) - centre) - kRadius;
        if (std::abs(distance) > 1.0) continue;  // well inside the band of half width 3
        worst = std::max(worst, std::abs(double(sampler.stored(glm::ivec3(i, j, k))) - distance));
        ++checked;
      }
  EXPECT_GT(checked, 1000);
  EXPECT_LT(worst, 0.02) << "over " << checked << " sites";
  // The interior is tiles of -background (3 voxels), not leaves.
  EXPECT_EQ(grid->tree().probeConstLeaf(openvdb::Coord(2, -1, 0)), nullptr);
  EXPECT_FLOAT_EQ(grid->tree().getValue(openvdb::Coord(2, -1, 0))[0], -3.0f);
}

TEST(ConvertStreamed, DenseInputEqualsTheInMemoryPath) {
  const std::string data = FCC_SHARED_DATA_DIR;
  if (!std::ifstream(data + "/engine_256x256x128_uint8.raw.gz")) GTEST_SKIP() << "no " << data;
  TempDir dir;
  ConvertOptions o;
  o.raw = RawLayout{{256, 256, 128}, ScalarType::U8, false, glm::dvec3(1.0), 0};
  expectStreamedEqualsInMemory(dir, data + "/engine_256x256x128_uint8.raw.gz", o);
}

TEST(ConvertStreamed, RealLevelSetFileEqualsTheInMemoryPath) {
  const std::string data = FCC_SHARED_DATA_DIR;
  if (!std::ifstream(data + "/sphere.vdb")) GTEST_SKIP() << "no " << data;
  TempDir dir;
  expectStreamedEqualsInMemory(dir, data + "/sphere.vdb", ConvertOptions{});
}

// The interior of a level set becomes tiles without a voxel of it visited: source leaves are decoded
// a bounded number of times (pass 1's slab window, pass 2's batches), the output keeps the level-set
// class, and its leaves lie along the surface only.
TEST(ConvertStreamed, LevelSetInteriorStaysTiles) {
  TempDir dir;
  const std::string input = writeSphere(dir, "ls", 150.0f, 1.0f);
  const auto reader = std::make_shared<VdbLeafReader>(input, "", std::vector<std::string>{openvdb::FloatTree::treeType()});
  VdbSourceField field(reader, static_cast<const openvdb::FloatGrid&>(*reader->grid()).background());
  const FccBlockBuilder builder(field, BuildOptions{});
  const StreamedBuild built = buildFccGridStreamed(builder, StreamedBuildOptions{});
  const size_t pass1 = field.leavesDecoded();
  // Every source leaf is decoded in pass 1, once per slab window that needs it (at most 2: a leaf
  // is 8 voxels wide, a slab 16).
  EXPECT_GE(pass1, reader->leafCount());
  EXPECT_LE(pass1, 2 * reader->leafCount());
  // Leaves only where the band is: far fewer than the blocks of the sphere's box.
  const double blocksInBox = std::pow(2.0 * 150.0 / 16.0, 3.0);
  EXPECT_LT(double(built.grid->tree().leafCount()), 0.5 * blocksInBox) << built.grid->tree().leafCount();
  // The centre (packed voxel of site (3, -2, 1)) is inside: a tile of the interior value, the
  // prefilter of -background.
  const openvdb::Coord centre(1, -1, 0);
  EXPECT_LT(built.grid->tree().getValue(centre)[0], 0.0f);
  EXPECT_LT(built.grid->tree().getValueDepth(centre), int(FccTree::DEPTH) - 1) << "the centre is a tile";

  ConvertOptions o;
  convertToFcc(input, dir / "out.vdb", o);
  const FccGrid::Ptr out = readFccGrid(dir / "out.vdb");
  EXPECT_EQ(out->getGridClass(), openvdb::GRID_LEVEL_SET);
}

}  // namespace
}  // namespace fcc::io
