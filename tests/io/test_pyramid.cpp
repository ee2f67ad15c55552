// The level-of-detail pyramid (io/FccPyramid.h) by its properties: the site filter is the spline's own
// value at a site; constant and linear fields are reproduced at every level; every level's bounds hold
// every value its spline takes; the coarsest level is a few bricks; level 0 is copied bit for bit and a
// reader without a grid name opens it whatever the grids' order; memory holds a window, not a level.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "io/BrickStore.h"
#include "io/FccPyramid.h"
#include "io/FinerSplineField.h"
#include "io/SynthFile.h"
#include "io/VdbFile.h"
#include "io/VdbLeafReader.h"
#include "sparse/FccSampler.h"
#include "sparse/Spline.h"
#include "sparse/StreamedBuild.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

using test::TempDir;

// f(ijk) = a + g . ijk over a box of sites (the background outside): constant when g = 0.
class AffineField final : public SampleField {
 public:
  AffineField(float a, const glm::vec3& g, int sites) : a_(a), g_(g), sites_(sites) {}
  float value(const glm::dvec3& xyz) const { return float(double(a_) + glm::dot(glm::dvec3(g_), xyz)); }
  float sample(const glm::ivec3& ijk) const override {
    return bounds().contains(ijk) ? value(glm::dvec3(ijk)) : background();
  }
  SiteBox bounds() const override { return {glm::ivec3(0), glm::ivec3(sites_ - 1)}; }
  float background() const override { return 0.0f; }

 private:
  float a_;
  glm::vec3 g_;
  int sites_;
};

// Level 0 of `field` as synth writes it (streamed, with bounds), named "field".
void writeLevel0(const std::string& path, const SampleField& field, bool half = false) {
  initializeVdb();
  const FccBlockBuilder builder(field, BuildOptions{});
  StreamedBuildOptions options;
  options.half = half;
  const StreamedBuild built = buildFccGridStreamed(builder, options);
  built.grid->setName("field");
  FccProvenance p;
  p.mode = "test";
  p.sampleMin = built.samples.min;
  p.sampleMax = built.samples.max;
  setFccMetadata(*built.grid, p);
  writeVdbAtomically(path, openvdb::GridCPtrVec{built.grid, boundsGridOf(built.bounds, *built.grid)}, true);
}

FccGrid::Ptr readLevel(const std::string& path, int level) {
  return readFccGrid(path, level == 0 ? "field" : lodGridName("field", level));
}

TEST(Pyramid, SiteFilterIsTheSplineAtASite) {
  // M_fcc at the lattice's sites: 1/2 at 0, 1/24 at the 12 nearest neighbours, 0 elsewhere. Checked
  // against the spline's evaluation on random coefficients.
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  auto coefficient = [&](const glm::ivec3& ijk) {
    std::mt19937 local(uint32_t((ijk.x * 73856093) ^ (ijk.y * 19349663) ^ (ijk.z * 83492791)));
    return std::uniform_real_distribution<float>(-1.0f, 1.0f)(local);
  };
  for (int i = 0; i < 200; ++i) {
    glm::ivec3 site(int(u(rng) * 20), int(u(rng) * 20), int(u(rng) * 20));
    if (!spline::isFccSite(site)) site.x += 1;
    float neighbourSum = 0.0f;
    for (int n = 0; n < 12; ++n) neighbourSum += coefficient(site + spline::fcc_neighbour_offset(n));
    const float filtered = splineAtSite(coefficient(site), neighbourSum);
    const float evaluated = spline::evaluate(glm::vec3(site), coefficient);
    EXPECT_NEAR(filtered, evaluated, 1e-5f) << "site " << site.x << "," << site.y << "," << site.z;
  }
}

// Levels of an affine field reproduce it wherever the field's edge does not reach: each level's
// samples read the finer spline one site around, its prefilter one more and its spline two, so the
// edge reaches at most kEdgeSites sites of a level into the data (m_k <= m_(k-1)/2 + 4 < 8).
constexpr int kEdgeSites = 8;
// Rounding: a few float operations a level on values of magnitude up to ~3.
constexpr float kAffineTolerance = 2e-5f;

void expectReproducedAtEveryLevel(const AffineField& field, int sites, const std::string& what) {
  TempDir dir;
  const std::string path = dir / "f.vdb";
  writeLevel0(path, field);
  const PyramidSummary summary = addPyramid(path, PyramidOptions{});
  ASSERT_GE(summary.levels.size(), 4u) << what;
  const FccGrid::Ptr level0 = readLevel(path, 0);
  int levelsChecked = 0;
  for (const PyramidLevel& l : summary.levels) {
    const FccGrid::Ptr grid = readLevel(path, l.level);
    const FccSampler sampler(*grid, false);
    const int scale = 1 << l.level;
    const int lo = kEdgeSites, hi = (sites - 1) / scale - kEdgeSites;  // level-k index range clear of the edge
    if (lo > hi) continue;
    ++levelsChecked;
    // Level k's index point p is level 0's 2^k p: the transforms say so.
    const openvdb::Vec3d p(lo + 0.3, lo + 1.7, hi - 0.2);
    EXPECT_TRUE(grid->transform().indexToWorld(p).eq(level0->transform().indexToWorld(p * double(scale)), 1e-9))
        << what << " level " << l.level;
    std::mt19937 rng(l.level);
    std::uniform_real_distribution<float> u{float(lo), float(hi)};
    for (int i = 0; i < 300; ++i) {
      const glm::vec3 xyz(u(rng), u(rng), u(rng));
      const float got = sampler.evaluateIndex(xyz).value;
      const float want = field.value(glm::dvec3(xyz) * double(scale));
      ASSERT_NEAR(got, want, kAffineTolerance)
          << what << ": level " << l.level << " at index (" << xyz.x << ", " << xyz.y << ", " << xyz.z
          << ") = level 0's (" << xyz.x * scale << ", " << xyz.y * scale << ", " << xyz.z * scale << ")";
    }
  }
  EXPECT_GE(levelsChecked, 3) << what;
}

TEST(Pyramid, ConstantFieldIsReproducedAtEveryLevel) {
  constexpr int kSites = 192;
  expectReproducedAtEveryLevel(AffineField(1.25f, glm::vec3(0.0f), kSites), kSites, "constant 1.25");
}

TEST(Pyramid, LinearFieldIsReproducedAtEveryLevel) {
  constexpr int kSites = 192;
  const glm::vec3 g(0.004f, -0.007f, 0.0125f);
  expectReproducedAtEveryLevel(AffineField(0.5f, g, kSites), kSites, "linear 0.5 + (0.004, -0.007, 0.0125) . ijk");
}

// Every level's bounds grid holds every value its spline takes in each brick, and the coarsest level
// fits in a few bricks; level 0 is the input's grid bit for bit.
TEST(Pyramid, BoundsAreConservativeAtEveryLevelAndTheCoarsestIsAFewBricks) {
  TempDir dir;
  const std::string original = dir / "o.vdb", path = dir / "p.vdb";
  SynthOptions synth;
  synth.spec.kind = "blobs";
  synth.spec.dims = glm::ivec3(160);
  writeSynthFile(original, synth);
  PyramidOptions options;
  options.output = path;
  const PyramidSummary summary = addPyramid(original, options);
  ASSERT_GE(summary.levels.size(), 3u);
  EXPECT_LE(summary.levels.back().brickBox, kMaxCoarsestBricks);
  EXPECT_LE(summary.levels.back().bricks, kMaxCoarsestBricks);
  for (size_t k = 1; k < summary.levels.size(); ++k)
    EXPECT_GT(summary.levels[k - 1].brickBox, kMaxCoarsestBricks) << "level " << k << " was one too many";

  for (const PyramidLevel& l : summary.levels) {
    const FccWithBounds level = readFccGridWithBounds(path, l.grid);
    ASSERT_TRUE(level.bounds) << l.grid;
    const FccSampler sampler(*level.grid, false);
    const auto bounds = level.bounds->getConstAccessor();
    // The bricks with data and their neighbours, plus a ring beyond: every point must lie in its brick's bounds.
    openvdb::CoordBBox bricks = level.bounds->evalActiveVoxelBoundingBox();
    bricks.expand(1);
    std::mt19937 rng(uint32_t(l.level));
    std::uniform_real_distribution<float> u(0.0f, 16.0f);
    size_t points = 0;
    for (auto b = bricks.begin(); b; ++b) {
      const openvdb::Vec2f range = bounds.getValue(*b);
      const float slack = 1e-5f * std::max(1.0f, std::abs(range[1]) + std::abs(range[0]));
      for (int i = 0; i < 12; ++i, ++points) {
        const glm::vec3 xyz = glm::vec3((*b).x(), (*b).y(), (*b).z()) * 16.0f + glm::vec3(u(rng), u(rng), u(rng));
        const float s = sampler.evaluateIndex(xyz).value;
        ASSERT_GE(s, range[0] - slack) << l.grid << " brick " << *b << " at (" << xyz.x << ", " << xyz.y << ", " << xyz.z << ")";
        ASSERT_LE(s, range[1] + slack) << l.grid << " brick " << *b << " at (" << xyz.x << ", " << xyz.y << ", " << xyz.z << ")";
      }
    }
    EXPECT_GT(points, 100u) << l.grid;
  }

  // Level 0: the same metadata but the level count, tiles, masks and values bit for bit.
  const FccWithBounds before = readFccGridWithBounds(original), after = readFccGridWithBounds(path);
  EXPECT_EQ(after.grid->getName(), "blobs");
  EXPECT_EQ(after.grid->metaValue<int32_t>(meta::kLodLevels), int32_t(summary.levels.size()));
  EXPECT_TRUE(before.grid->tree().hasSameTopology(after.grid->tree()));
  for (auto leaf = before.grid->tree().cbeginLeaf(); leaf; ++leaf) {
    const auto* other = after.grid->tree().probeConstLeaf(leaf->origin());
    ASSERT_TRUE(other);
    ASSERT_EQ(std::memcmp(leaf->buffer().data(), other->buffer().data(), sizeof(openvdb::Vec4f) * leaf->SIZE), 0)
        << "leaf at " << leaf->origin();
  }
  ASSERT_TRUE(after.bounds);
  EXPECT_TRUE(before.bounds->tree().hasSameTopology(after.bounds->tree()));
  for (auto v = before.bounds->cbeginValueAll(); v; ++v)
    ASSERT_EQ(after.bounds->tree().getValue(v.getCoord()), *v) << v.getCoord();
}

// Half floats: the copy keeps the same halves, the levels are stored as halves too.
TEST(Pyramid, HalfFilesStayHalf) {
  TempDir dir;
  const std::string path = dir / "h.vdb";
  SynthOptions synth;
  synth.spec.kind = "sphere";
  synth.spec.dims = glm::ivec3(72);
  synth.half = true;
  writeSynthFile(path, synth);
  const FccGrid::Ptr before = readFccGrid(path);
  addPyramid(path, PyramidOptions{});
  const FccGrid::Ptr after = readFccGrid(path);
  for (auto leaf = before->tree().cbeginLeaf(); leaf; ++leaf) {
    const auto* other = after->tree().probeConstLeaf(leaf->origin());
    ASSERT_TRUE(other);
    ASSERT_EQ(std::memcmp(leaf->buffer().data(), other->buffer().data(), sizeof(openvdb::Vec4f) * leaf->SIZE), 0);
  }
  for (const VdbGridEntry& g : VdbLeafReader::listGrids(path)) {
    if (g.type == kFccTreeTypeName) {
      EXPECT_TRUE(g.half) << g.name;
    }
  }
}

// Readers that open "the first FCC grid" open level 0 even when a level comes first in the file.
TEST(Pyramid, ReadersWithoutAGridNameOpenLevel0InAnyOrder) {
  TempDir dir;
  const std::string path = dir / "p.vdb", reversed = dir / "r.vdb";
  SynthOptions synth;
  synth.spec.kind = "sphere";
  synth.spec.dims = glm::ivec3(96);
  writeSynthFile(path, synth);
  addPyramid(path, PyramidOptions{});
  openvdb::io::File file(path);
  file.open(false);
  openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  openvdb::GridCPtrVec backwards(grids->rbegin(), grids->rend());
  ASSERT_TRUE(isLodGridName(backwards.front()->getName()) || isLodGridName(backwards[1]->getName()));
  writeVdbAtomically(reversed, backwards, true);
  EXPECT_EQ(BrickStore(reversed).index().getName(), "sphere");
  EXPECT_EQ(readFccGrid(reversed)->getName(), "sphere");
  EXPECT_EQ(readFccGridWithBounds(reversed).bounds->metaValue<std::string>(meta::kBoundsOf), "sphere");
  EXPECT_FALSE(isLodGridName("sphere"));
  EXPECT_FALSE(isLodGridName("x.lod"));
  EXPECT_FALSE(isLodGridName("x.lodz"));
  EXPECT_TRUE(isLodGridName("x.lod12"));
}

// The finer level is read a window at a time: at most a few slabs of its bricks are decoded at once.
TEST(Pyramid, FinerLevelIsHeldAWindowAtATime) {
  TempDir dir;
  const std::string path = dir / "s.vdb";
  SynthOptions synth;
  synth.spec.kind = "sphere";  // dense: every block a leaf
  synth.spec.dims = glm::ivec3(256);
  writeSynthFile(path, synth);
  const BrickStore store(path);
  const FinerSplineField field(store);
  const FccBlockBuilder builder(field, BuildOptions{});
  const StreamedBuild built = buildFccGridStreamed(builder, StreamedBuildOptions{});
  const size_t finerBricks = store.index().tree().leafCount();
  ASSERT_GE(finerBricks, 4000u);
  EXPECT_GE(field.bricksDecoded(), finerBricks) << "every finer brick is read";
  // A slab of level-1 blocks reads 2 finer slabs and a site either side: 4 slabs of 16 here.
  EXPECT_LE(field.maxBricksResident(), finerBricks * 4 / 16 + 16)
      << "held at once: " << field.maxBricksResident() << " of " << finerBricks;
  EXPECT_GT(built.grid->tree().leafCount(), 0u);
}

}  // namespace
}  // namespace fcc::io
