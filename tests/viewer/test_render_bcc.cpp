// The brick-paged raycaster on BCC datasets (viewer/BccBrickSource.h, shaders/march_bcc.glsl): the
// storage (two coset grids, sparse/BccGrids.h) puts every site where its index says; every BCC
// reconstruction of paper 002 on the device against the exact CPU reference raycaster
// (sparse/ReferenceRaycast.h) pixel by pixel, from two views that choose different stacks and shears;
// the image independent of the pool's size; and `render` on a BCC file.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "CartesianTestSupport.h"
#include "RenderTestSupport.h"
#include "io/VdbFile.h"
#include "sparse/BccGrids.h"
#include "sparse/BccShearedTrilinear.h"
#include "sparse/LatticeSamples.h"
#include "sparse/ReferenceRaycast.h"
#include "tests/tools/RunCommand.h"
#include "viewer/BccBrickSource.h"
#include "viewer/DatasetSummary.h"

namespace fcc {
namespace {

using test::GlSuite;
using test::TempDir;
using test::kBackground;
using test::kDim;
using test::wavy;

constexpr double kScale = 0.5;  // world units per BCC index unit
const openvdb::Vec3d kOrigin(-3.0, 1.0, 2.0);

bool inData(const glm::ivec3& x) {
  return glm::all(glm::greaterThanEqual(x, glm::ivec3(0))) && glm::all(glm::lessThan(x, glm::ivec3(kDim)));
}

// wavy() at the BCC sites of [0, kDim)^3, the background beyond.
void writeBccFile(const std::string& path) { test::writeBccFile(path, wavy, kScale, kOrigin); }

render::FrameImages renderBcc(const std::string& path, const std::string& reconstruction, const render::Camera& camera,
                              int width, int height, float iso, render::RenderOptions options = {},
                              render::FrameStats* stats = nullptr) {
  const render::BccBrickSource source(path, findReconstruction(reconstruction));
  options.iso = iso;
  return test::renderSource(source, camera, width, height, options, stats);
}

class RenderBcc : public GlSuite {};

// Coset voxel m holds site 2m (primary) or 2m + 1 (secondary) at that site's world position, and a
// decoded block puts each site where pool.glsl reads it.
TEST(BccStorage, CosetsHoldTheirSitesWhereTheIndexSays) {
  TempDir dir;
  const std::string path = dir / "wavy_bcc.vdb";
  writeBccFile(path);
  const render::BccBrickSource source(path, findReconstruction("barycentric"));
  const glm::dmat4& worldFromIndex = source.worldFromIndex();
  for (const glm::dvec3 x : {glm::dvec3(0.0), glm::dvec3(1.0), glm::dvec3(4.0, 6.0, 2.0), glm::dvec3(5.0, 7.0, 3.0)}) {
    const glm::dvec3 world(worldFromIndex * glm::dvec4(x, 1.0));
    const glm::dvec3 expected = kScale * x + glm::dvec3(kOrigin.x(), kOrigin.y(), kOrigin.z());
    EXPECT_LT(glm::length(world - expected), 1e-12) << x.x << ", " << x.y << ", " << x.z;
  }
  // The grids' own transforms, as any OpenVDB tool sees them.
  openvdb::io::File file(path);
  file.open();
  const openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  ASSERT_EQ(grids->size(), 2u);
  for (const auto& g : *grids) {
    const int coset = g->getName() == kBccSecondaryGridName ? 1 : 0;
    const openvdb::Vec3d world = g->transform().indexToWorld(openvdb::Coord(3, 5, 7));
    const glm::dvec3 expected = kScale * (2.0 * glm::dvec3(3, 5, 7) + double(coset)) + glm::dvec3(kOrigin.x(), kOrigin.y(), kOrigin.z());
    EXPECT_LT(glm::length(glm::dvec3(world.x(), world.y(), world.z()) - expected), 1e-12) << g->getName();
    EXPECT_EQ(g->metaValue<std::string>("lattice"), "bcc");
  }
  // Every site of a few bricks' blocks, at the place pool.glsl's coefficientAt reads it.
  std::vector<render::LoadedBrick> chunk;
  for (const glm::ivec3 b : {glm::ivec3(0), glm::ivec3(1, 2, 0), glm::ivec3(2, 2, 2), glm::ivec3(-1, 0, 1)})
    chunk.push_back(render::LoadedBrick{b, {}});
  source.decode(chunk);
  int checked = 0;
  for (const render::LoadedBrick& b : chunk) {
    ASSERT_EQ(b.halo.size(), render::slotBlockFloats(render::SlotBlock::BccPacked));
    for (int coset = 0; coset < 2; ++coset)
      for (int z = 0; z < render::kBccSlotDim; ++z)
        for (int y = 0; y < render::kBccSlotDim; ++y)
          for (int x = 0; x < render::kBccSlotDim; ++x) {
            const glm::ivec3 m = 8 * b.brick - render::kBccSlotLo + glm::ivec3(x, y, z);
            const glm::ivec3 site = 2 * m + coset;
            const float expected = inData(site) ? wavy(site) : kBackground;
            const std::size_t i = std::size_t(coset) * 1728 + (std::size_t(z) * 12 + y) * 12 + x;
            ASSERT_EQ(b.halo[i], expected) << "brick " << b.brick.x << "," << b.brick.y << "," << b.brick.z << " site "
                                           << site.x << "," << site.y << "," << site.z;
            ++checked;
          }
  }
  EXPECT_EQ(checked, 4 * 2 * 1728);
  // The ranges bound every site of each brick's block.
  int bricks = 0;
  source.forEachVaryingBrick([&](const glm::ivec3& brick, float lo, float hi) {
    ++bricks;
    std::vector<render::LoadedBrick> one{render::LoadedBrick{brick, {}}};
    source.decode(one);
    for (std::size_t i = 0; i < 2 * 1728; ++i) ASSERT_TRUE(lo <= one[0].halo[i] && one[0].halo[i] <= hi);
  });
  EXPECT_GT(bricks, 0);
}

// The panel's summary of a BCC source: each sampled brick's own sites (2 x 8^3: both cosets' voxels of
// the brick, not the halo), counted once, within the source's range.
TEST(BccStorage, SummaryCountsEachBricksOwnSites) {
  TempDir dir;
  const std::string path = dir / "wavy_bcc.vdb";
  writeBccFile(path);
  const render::BccBrickSource source(path, findReconstruction("barycentric"));
  const render::DatasetSummary s = render::summarizeSource(source, /*maxBricks=*/1000, /*bins=*/32);
  EXPECT_EQ(s.bricks, source.varyingBrickCount());
  EXPECT_EQ(s.bytes, s.bricks * 1024 * sizeof(float));
  EXPECT_EQ(s.histogramBricks, s.bricks) << "every brick sampled (fewer than maxBricks)";
  EXPECT_EQ(s.histogramValues, s.histogramBricks * 1024);
  double counted = 0.0;
  for (float c : s.histogram) counted += c;
  EXPECT_EQ(counted, double(s.histogramValues));
}

// A brick whose both cosets hold data throughout gets their range, without the background: data 0.5 on
// [0, 96)^3 of BCC index space (coset voxels [0, 48)), so coset brick 1's block [14, 34)^3 lies inside.
TEST(BccStorage, RangesLeaveTheBackgroundOutInsideTheData) {
  TempDir dir;
  const std::string path = dir / "constant_bcc.vdb";
  initializeVdb();
  const BccGrids grids = buildBccGrids(SiteBox{glm::ivec3(0), glm::ivec3(95)}, 2.0f, [](const glm::ivec3&) { return 0.5f; },
                                       *openvdb::math::Transform::createLinearTransform(1.0));
  io::writeVdbAtomically(path, openvdb::GridCPtrVec{grids.primary, grids.secondary}, /*overwrite=*/true);
  const render::BccBrickSource source(path, findReconstruction("barycentric"));
  int inside = 0, edge = 0;
  source.forEachVaryingBrick([&](const glm::ivec3& brick, float lo, float hi) {
    // BCC bricks 2..3 per axis lie in coset brick 1.
    if (glm::all(glm::greaterThanEqual(brick, glm::ivec3(2))) && glm::all(glm::lessThanEqual(brick, glm::ivec3(3)))) {
      ++inside;
      EXPECT_EQ(lo, 0.5f);
      EXPECT_EQ(hi, 0.5f);
    } else {
      ++edge;
      EXPECT_EQ(hi, 2.0f) << "a block that reaches beyond the data holds the background";
    }
  });
  EXPECT_EQ(inside, 8);
  EXPECT_GT(edge, 0);
}

// The device and the CPU reference on every BCC scheme, from a view down -z with positive shears and
// one mostly along +y with a negative shear (the stack schemes take both from the view).
TEST_F(RenderBcc, EveryReconstructionMatchesTheCpuReference) {
  TempDir dir;
  const std::string path = dir / "wavy_bcc.vdb";
  writeBccFile(path);
  const glm::dmat4 worldFromIndex = render::BccBrickSource(path, findReconstruction("barycentric")).worldFromIndex();
  const glm::dmat4 indexFromWorld = glm::inverse(worldFromIndex);
  // The CPU's sites: the data in a box padded with the background beyond every stencil's reach.
  const int pad = 8;
  LatticeSamples samples(Lattice::Bcc, glm::ivec3(-pad), glm::ivec3(kDim + 2 * pad), kBackground);
  samples.fill([](const glm::ivec3& x) { return inData(x) ? wavy(x) : kBackground; });
  const CellBounds bounds(samples);
  const float iso = 0.35f;
  const int w = 64, h = 56;

  const glm::dvec3 center(worldFromIndex * glm::dvec4(24.0, 24.0, 24.0, 1.0));
  for (const glm::dvec3 offset : {glm::dvec3(30.0, 22.0, 36.0), glm::dvec3(-14.0, -44.0, 20.0)}) {
    render::Camera camera;
    camera.lookat = center;
    camera.eye = center + offset;
    camera.fovYDegrees = 35.0;
    const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
    const glm::vec3 forwardIndex(glm::dmat3(indexFromWorld) * frame.forward);
    const glm::ivec3 params = spline::bcc_sheared_params_for_view(forwardIndex);
    for (const char* name : {"barycentric", "sheared-trilinear", "bilinear-spatial", "bilinear"}) {
      SCOPED_TRACE(std::string(name) + ", stack axis " + std::to_string(params.x) + ", shears " + std::to_string(params.y) +
                   " " + std::to_string(params.z));
      const render::FrameImages gpu = renderBcc(path, name, camera, w, h, iso);
      const std::unique_ptr<Reconstruction> recon = makeReconstruction(name);
      recon->setView(forwardIndex);
      test::expectReferenceIsosurface(std::string(name) + " (axis " + std::to_string(params.x) + ", shears " + std::to_string(params.y) + " " +
                                          std::to_string(params.z) + ")",
                                      gpu, camera, indexFromWorld, kScale, *recon, samples.accessor(), bounds, iso);
    }
  }
}

// Out of core: a pool of a few slots gives the image of an unbounded one, bit for bit.
TEST_F(RenderBcc, SmallPoolGivesTheSameImage) {
  TempDir dir;
  const std::string path = dir / "wavy_bcc.vdb";
  writeBccFile(path);
  const glm::dmat4 worldFromIndex = render::BccBrickSource(path, findReconstruction("barycentric")).worldFromIndex();
  render::Camera camera;
  camera.lookat = glm::dvec3(worldFromIndex * glm::dvec4(24.0, 24.0, 24.0, 1.0));
  camera.eye = camera.lookat + glm::dvec3(45.0, 35.0, 40.0);
  for (const char* name : {"barycentric", "sheared-trilinear"}) {
    SCOPED_TRACE(name);
    test::expectSixSlotsGiveTheSameImage(render::BccBrickSource(path, findReconstruction(name)), camera, 48, 48, 0.35f);
  }
}

}  // namespace
}  // namespace fcc
