// The streamed build (sparse/StreamedBuild.h) writes what the in-memory builder and
// computeBrickBounds write: for every synth kind, with and without --half and --no-prefilter, and for
// a field whose uniform leaves become tiles of every level; its leaves never hold values.
#include <gtest/gtest.h>

#include <functional>

#include "SameVdbFiles.h"
#include "io/SynthFile.h"
#include "io/VdbFile.h"
#include "kernels/ClBrickKernels.h"
#include "sparse/BrickBounds.h"
#include "sparse/BrickKernels.h"
#include "sparse/FccBuilder.h"
#include "sparse/StreamedBuild.h"
#include "sparse/StreamedFccTree.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using test::TempDir;

struct Variant {
  bool prefilter = true;
  bool half = false;
};

std::string describe(const Variant& v) {
  return std::string(v.prefilter ? "coefficients" : "--no-prefilter") + (v.half ? " --half" : "");
}

using Describe = std::function<void(FccGrid&, const SampleSummary& samples)>;

// The dataset as `synth` wrote it before it streamed: the whole grid in memory, then its bounds.
void writeInMemory(const std::string& path, const SampleField& field, const Variant& v, BrickKernels* kernels,
                   const Describe& describeGrid) {
  BuildOptions build;
  build.prefilter = v.prefilter;
  const BuildResult built = buildFccGrid(field, build);
  describeGrid(*built.grid, built.samples);
  built.grid->setSaveFloatAsHalf(v.half);
  const BoundsGrid::Ptr bounds = computeBrickBounds(*coefficientsOf(valuesAsStored(built.grid), kernels), kernels);
  writeVdbAtomically(path, openvdb::GridCPtrVec{built.grid, bounds}, false);
}

// The same through the streamed build (what writeSynthFile does for synth fields); `options` sets
// more than v's half and the kernels. Returns how pass 2 wrote the leaves: (copied, rebuilt).
std::pair<size_t, size_t> writeStreamed(const std::string& path, const SampleField& field, const Variant& v,
                                        BrickKernels* kernels, const Describe& describeGrid,
                                        StreamedBuildOptions options = {}) {
  BuildOptions build;
  build.prefilter = v.prefilter;
  const FccBlockBuilder builder(field, build);
  options.half = v.half;
  options.kernels = kernels;
  const StreamedBuild built = buildFccGridStreamed(builder, options);
  describeGrid(*built.grid, built.samples);
  writeVdbAtomically(path, openvdb::GridCPtrVec{built.grid, boundsGridOf(built.bounds, *built.grid)}, false);
  const auto& tree = static_cast<const StreamedFccTree&>(built.grid->tree());
  return {tree.leavesCopied(), tree.leavesRebuilt()};
}

TEST(SynthStreamed, EqualsTheInMemoryBuild) {
  TempDir dir;
  const std::unique_ptr<BrickKernels> reference = makeReferenceBrickKernels();
  for (const std::string kind : {"sphere", "marschner-lobb", "blobs"})
    for (const Variant v : {Variant{true, false}, Variant{true, true}, Variant{false, false}, Variant{false, true}}) {
      SCOPED_TRACE(kind + " " + describe(v));
      SynthOptions options;
      options.spec = SynthSpec{kind, glm::ivec3(40, 56, 48), 3};
      options.prefilter = v.prefilter;
      options.half = v.half;
      options.preprocess = reference.get();
      const std::string streamed = dir / (kind + "_streamed.vdb"), inMemory = dir / (kind + "_memory.vdb");
      writeSynthFile(streamed, options);
      const SynthField synth = makeSynthField(options.spec);
      writeInMemory(inMemory, *synth.field, v, reference.get(), [&](FccGrid& grid, const SampleSummary& samples) {
        describeSynthGrid(grid, kind, synth, v.prefilter, samples);
      });
      test::expectSameFccFiles(inMemory, streamed);
      std::filesystem::remove(streamed);
      std::filesystem::remove(inMemory);
    }
}

TEST(SynthStreamed, EqualsTheInMemoryBuildWithOpenCl) {
  // The kernels see other batches of bricks (a slab's, not the grid's); each brick's result must not
  // depend on them.
  TempDir dir;
  const std::unique_ptr<BrickKernels> kernels = makeBrickKernels("auto");
  for (const Variant v : {Variant{true, true}, Variant{false, false}}) {
    SCOPED_TRACE(describe(v) + " on " + kernels->describe());
    SynthOptions options;
    options.spec = SynthSpec{"blobs", glm::ivec3(64, 48, 56), 5};
    options.prefilter = v.prefilter;
    options.half = v.half;
    options.preprocess = kernels.get();
    writeSynthFile(dir / "streamed.vdb", options);
    const SynthField synth = makeSynthField(options.spec);
    writeInMemory(dir / "memory.vdb", *synth.field, v, kernels.get(), [&](FccGrid& grid, const SampleSummary& samples) {
      describeSynthGrid(grid, "blobs", synth, v.prefilter, samples);
    });
    test::expectSameFccFiles(dir / "memory.vdb", dir / "streamed.vdb");
    std::filesystem::remove(dir / "streamed.vdb");
    std::filesystem::remove(dir / "memory.vdb");
  }
}

// Pass 2 copies the leaves pass 1 kept encoded instead of rebuilding them; a cap on the scratch file
// leaves the rest to be rebuilt, and without it every leaf is rebuilt: the same file every way.
TEST(SynthStreamed, PassTwoCopiesTheLeavesPassOneKeptAndRebuildsTheRest) {
  TempDir dir;
  const std::unique_ptr<BrickKernels> reference = makeReferenceBrickKernels();
  const SynthField synth = makeSynthField(SynthSpec{"blobs", glm::ivec3(64, 48, 56), 5});
  for (const Variant v : {Variant{true, false}, Variant{true, true}}) {
    SCOPED_TRACE(describe(v));
    auto describeGrid = [&](FccGrid& grid, const SampleSummary& samples) {
      describeSynthGrid(grid, "blobs", synth, v.prefilter, samples);
    };
    writeInMemory(dir / "memory.vdb", *synth.field, v, reference.get(), describeGrid);
    const size_t leaves = readFccGrid(dir / "memory.vdb")->tree().leafCount();
    ASSERT_GT(leaves, 8u);

    const auto [copied, rebuilt] = writeStreamed(dir / "kept.vdb", *synth.field, v, reference.get(), describeGrid);
    EXPECT_EQ(copied, leaves) << "every leaf copied";
    EXPECT_EQ(rebuilt, 0u);
    test::expectSameFccFiles(dir / "memory.vdb", dir / "kept.vdb");

    StreamedBuildOptions capped;
    capped.keepLeavesMaxBytes = 12 << 10;  // a few leaves' bytes
    const auto [someCopied, someRebuilt] =
        writeStreamed(dir / "capped.vdb", *synth.field, v, reference.get(), describeGrid, capped);
    EXPECT_GT(someCopied, 0u);
    EXPECT_GT(someRebuilt, 0u);
    EXPECT_EQ(someCopied + someRebuilt, leaves);
    test::expectSameFccFiles(dir / "memory.vdb", dir / "capped.vdb");

    StreamedBuildOptions none;
    none.keepLeaves = false;
    const auto [noneCopied, allRebuilt] = writeStreamed(dir / "rebuilt.vdb", *synth.field, v, reference.get(), describeGrid, none);
    EXPECT_EQ(noneCopied, 0u);
    EXPECT_EQ(allRebuilt, leaves);
    test::expectSameFccFiles(dir / "memory.vdb", dir / "rebuilt.vdb");
    for (const char* f : {"memory.vdb", "kept.vdb", "capped.vdb", "rebuilt.vdb"}) std::filesystem::remove(dir / f);
  }
}

// 0.75 in a box of sites reaching past an aligned 256^3 (a level-2 node of the FCC tree, 16^3 leaves):
// inside, whole leaves of samples and of coefficients are uniform, so the builder's prune makes them
// tiles of every level; near the box's faces the prefilter makes leaves. Its x faces are those of
// blocks, so coefficients spread into the blocks beyond, and the background is not zero, so the
// bounds of bricks of background coefficients computed exactly (the neighbours of those blocks) are
// not quite the background's: a streamed build must compute the same bricks.
class ConstantBoxField : public SampleField {
 public:
  float sample(const glm::ivec3& ijk) const override {
    return glm::all(glm::greaterThanEqual(ijk, kBox.min)) && glm::all(glm::lessThanEqual(ijk, kBox.max)) ? 0.75f
                                                                                                           : background();
  }
  SiteBox bounds() const override { return kBox; }
  float background() const override { return 0.1f; }

 private:
  static constexpr SiteBox kBox{glm::ivec3(-32, -4, -36), glm::ivec3(287, 261, 270)};
};

TEST(SynthStreamed, UniformLeavesBecomeTheSameTiles) {
  TempDir dir;
  const ConstantBoxField field;
  // Thousands of bricks of non-zero coefficients: OpenCL where there is a device (the reference
  // otherwise), as the two builds use the same kernels either way.
  const std::unique_ptr<BrickKernels> kernels = makeBrickKernels("auto");
  for (const Variant v : {Variant{true, true}, Variant{false, false}}) {
    SCOPED_TRACE(describe(v));
    auto name = [&](FccGrid& grid, const SampleSummary& samples) {
      grid.setName("box");
      FccProvenance p;
      p.coefficients = v.prefilter;
      p.mode = "test";
      p.sampleMin = samples.min;
      p.sampleMax = samples.max;
      setFccMetadata(grid, p);
      recordSampleHistogram(grid, samples);
    };
    writeInMemory(dir / "memory.vdb", field, v, kernels.get(), name);
    writeStreamed(dir / "streamed.vdb", field, v, kernels.get(), name);
    const FccGrid::Ptr grid = readFccGrid(dir / "memory.vdb");
    int deepTiles = 0;
    for (auto it = grid->tree().cbeginValueOn(); it; ++it) deepTiles += it.getDepth() <= 1;  // level 2 (or the root's)
    EXPECT_GT(deepTiles, 0) << "the case covers tiles above the leaf level";
    EXPECT_GT(grid->tree().activeTileCount(), 1000u) << "and leaf-level tiles";
    test::expectSameFccFiles(dir / "memory.vdb", dir / "streamed.vdb");
    std::filesystem::remove(dir / "streamed.vdb");
    std::filesystem::remove(dir / "memory.vdb");
  }
}

TEST(SynthStreamed, LeavesHoldNoValuesBeforeOrAfterWriting) {
  // The grid's leaves are topology only; writing builds the values elsewhere. Archive's grid
  // statistics and delayed-load metadata must not allocate them (or crash on them).
  TempDir dir;
  initializeVdb();
  const SynthField synth = makeSynthField(SynthSpec{"sphere", glm::ivec3(48), 1});
  const FccBlockBuilder builder(*synth.field, BuildOptions{});
  const StreamedBuild built = buildFccGridStreamed(builder, StreamedBuildOptions{});
  describeSynthGrid(*built.grid, "sphere", synth, true, built.samples);
  auto allocated = [&] {
    size_t n = 0;
    for (auto leaf = built.grid->tree().cbeginLeaf(); leaf; ++leaf) n += !leaf->buffer().empty();
    return n;
  };
  ASSERT_GT(built.grid->tree().leafCount(), 100u);
  EXPECT_EQ(allocated(), 0u);
  writeVdbAtomically(dir / "s.vdb", openvdb::GridCPtrVec{built.grid, boundsGridOf(built.bounds, *built.grid)}, false);
  EXPECT_EQ(allocated(), 0u);
  EXPECT_EQ(readFccGrid(dir / "s.vdb")->activeVoxelCount(), built.grid->activeVoxelCount());
}

}  // namespace
}  // namespace fcc::io
