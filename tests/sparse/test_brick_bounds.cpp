// The preprocessing reference (sparse/BrickBounds.cpp) and the bounds hierarchy: bounds are
// conservative per cube and per brick (also at bricks beside leaves and tiles), equal the reduced
// spline::cubeBounds, and the hierarchy's counts follow the brick intervals.
#include <gtest/gtest.h>

#include <random>

#include "BrickTestData.h"
#include "sparse/BBDomainPoints.h"
#include "sparse/BoundsHierarchy.h"
#include "sparse/BrickBounds.h"
#include "sparse/BrickKernels.h"
#include "sparse/Error.h"
#include "sparse/FccSampler.h"

namespace fcc {
namespace {

using openvdb::Coord;
using openvdb::Vec2f;

// float round-off of a value against the scaled BB-coefficients (as in test_spline's bounds test).
constexpr float kTol = 1e-6f;

TEST(BrickBounds, ConservativeAtAMillionPoints) {
  const FccGrid::Ptr grid = test::randomBrickGrid(7);
  const BoundsGrid::Ptr bounds = computeBrickBounds(*grid);
  std::vector<Coord> varying;
  for (auto it = bounds->cbeginValueOn(); it; ++it)
    if (it.isVoxelValue()) varying.push_back(it.getCoord());
  ASSERT_GT(varying.size(), 50u);
  // Half the points in bricks where the spline varies, half anywhere around the data (tiles, the
  // background, the borders between them); each within half a unit of its brick's box.
  const openvdb::CoordBBox around(Coord(-18, -2, -18), Coord(8, 17, 4));
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> inBrick(-0.5f, 16.5f);
  const FccSampler sampler(*grid, false);
  auto coefficientAt = [&](const glm::ivec3& ijk) { return sampler.coefficient(ijk); };
  auto boundsAt = bounds->getConstAccessor();
  int withoutLeaf = 0;
  for (int i = 0; i < 1000000; ++i) {
    Coord brick;
    if (i & 1) {
      brick = varying[rng() % varying.size()];
    } else {
      const Coord d = around.dim();
      brick = around.min().offsetBy(int(rng() % d.x()), int(rng() % d.y()), int(rng() % d.z()));
    }
    const glm::vec3 xyz = glm::vec3(brick.x(), brick.y(), brick.z()) * float(kBrickSites) +
                          glm::vec3(inBrick(rng), inBrick(rng), inBrick(rng));
    const float v = sampler.evaluateIndex(xyz).value;
    const spline::FccRange cube = spline::cubeBounds(glm::ivec3(glm::floor(xyz)), coefficientAt);
    ASSERT_GE(v, cube.lo - kTol) << "cube at " << xyz.x << " " << xyz.y << " " << xyz.z;
    ASSERT_LE(v, cube.hi + kTol) << "cube at " << xyz.x << " " << xyz.y << " " << xyz.z;
    const glm::ivec3 b = glm::ivec3(glm::floor(xyz / float(kBrickSites)));
    const Vec2f range = boundsAt.getValue(Coord(b.x, b.y, b.z));
    ASSERT_GE(v, range[0] - kTol) << "brick " << Coord(b.x, b.y, b.z) << " at " << xyz.x << " " << xyz.y << " " << xyz.z;
    ASSERT_LE(v, range[1] + kTol) << "brick " << Coord(b.x, b.y, b.z) << " at " << xyz.x << " " << xyz.y << " " << xyz.z;
    withoutLeaf += grid->tree().probeConstLeaf(Coord(b.x * 8, b.y * 8, b.z * 8)) == nullptr;
  }
  EXPECT_GT(withoutLeaf, 100000) << "points in tiles, the background and beside leaves were tried";
}

TEST(BrickBounds, EqualReducedCubeBounds) {
  // Also with a zero background and sparse leaves: the reference skips cubes that read only zeros.
  for (const float background : {test::kBrickTestBackground, 0.0f}) {
  const FccGrid::Ptr grid = test::randomBrickGrid(8, background == 0.0f ? 0.3f : 0.8f, background);
  const FccSampler sampler(*grid, false);
  auto coefficientAt = [&](const glm::ivec3& ijk) { return sampler.coefficient(ijk); };
  const std::vector<Coord> bricks = {Coord(0, 0, 0), Coord(3, 0, 0), Coord(-1, 5, -3), Coord(-8, 4, 1), Coord(7, 2, 1),
                                     Coord(6, 1, 0), Coord(5, 1, 0)};
  std::vector<Vec2f> out;
  makeReferenceBrickKernels()->bounds(*grid, bricks, out);
  for (size_t i = 0; i < bricks.size(); ++i) {
    float lo = INFINITY, hi = -INFINITY;
    for (int z = 0; z < kBrickSites; ++z)
      for (int y = 0; y < kBrickSites; ++y)
        for (int x = 0; x < kBrickSites; ++x) {
          const spline::FccRange r = spline::cubeBounds(
              glm::ivec3(bricks[i].x(), bricks[i].y(), bricks[i].z()) * kBrickSites + glm::ivec3(x, y, z), coefficientAt);
          lo = std::min(lo, r.lo);
          hi = std::max(hi, r.hi);
        }
    EXPECT_EQ(out[i][0], lo) << bricks[i] << " background " << background;
    EXPECT_EQ(out[i][1], hi) << bricks[i] << " background " << background;
  }
  }
}

TEST(BrickBounds, GridFollowsTheContract) {
  const FccGrid::Ptr grid = test::randomBrickGrid(9);
  grid->setName("density");
  grid->setTransform(openvdb::math::Transform::createLinearTransform(0.5));
  const BoundsGrid::Ptr bounds = computeBrickBounds(*grid);
  EXPECT_EQ(bounds->getName(), boundsGridName("density"));
  EXPECT_EQ(bounds->metaValue<std::string>(meta::kBoundsOf), "density");
  EXPECT_EQ(bounds->background(), Vec2f(test::kBrickTestBackground));
  EXPECT_NEAR(bounds->voxelSize().x(), 0.5 * kBrickSites, 1e-12);
  for (auto it = bounds->cbeginValueOn(); it; ++it) EXPECT_LT((*it)[0], (*it)[1]) << it.getCoord();
  // Far inside the level-2 tile the spline is its constant value; the tile's one-brick neighbour with
  // unequal channels varies over them.
  EXPECT_EQ(bounds->tree().getValue(Coord(-8, 8, -8)), Vec2f(0.5f));
  EXPECT_FALSE(bounds->tree().isValueOn(Coord(-8, 8, -8)));
  EXPECT_TRUE(bounds->tree().isValueOn(Coord(-8, 4, 1)));
  EXPECT_EQ(bounds->tree().getValue(Coord(-8, 4, 1)), Vec2f(-0.5f, 0.75f));
  // Far from everything: the background.
  EXPECT_EQ(bounds->tree().getValue(Coord(100, 100, 100)), Vec2f(test::kBrickTestBackground));
  EXPECT_THROW(
      {
        grid->insertMeta(meta::kValues, openvdb::StringMetadata(kValuesSamples));
        computeBrickBounds(*grid);
      },
      ValueError);
}

TEST(BBDomainPoints, DistinctPointsOfTheCell) {
  // 23 per unit cube; every BB-coefficient is a convex combination (weights sum to FCC_CUBIC_DENOM).
  const auto points = spline::bbDomainPointsOfCell();
  EXPECT_EQ(points.size(), 184u);
  for (const auto& p : points) {
    float sum = 0.0f;
    for (const auto& t : p.terms) {
      EXPECT_GT(t.weight, 0.0f);
      sum += t.weight;
    }
    EXPECT_EQ(sum, FCC_CUBIC_DENOM);
  }
}

TEST(BoundsHierarchy, CountsFollowTheBrickIntervals) {
  initializeVdb();
  auto bounds = BoundsGrid::create(Vec2f(0.0f));
  // Bricks in two level-1 nodes of one level-2 node, and one in another level-2 node.
  bounds->tree().setValueOn(Coord(0, 0, 0), Vec2f(0.0f, 1.0f));
  bounds->tree().setValueOn(Coord(1, 0, 0), Vec2f(2.0f, 3.0f));
  bounds->tree().setValueOn(Coord(16, 0, 0), Vec2f(0.5f, 2.5f));
  bounds->tree().setValueOn(Coord(512, 0, 0), Vec2f(5.0f, 6.0f));
  bounds->tree().setValueOff(Coord(2, 0, 0), Vec2f(0.5f));  // constant: no surface, not counted
  const BoundsHierarchy h(*bounds);
  EXPECT_EQ(h.total().bricks, 4u);
  EXPECT_EQ(h.total().nodes1, 3u);
  EXPECT_EQ(h.total().nodes2, 2u);
  EXPECT_EQ(h.root(), Vec2f(0.0f, 6.0f));
  EXPECT_EQ(h.nodes(1).at(Coord(0, 0, 0)), Vec2f(0.0f, 3.0f));
  auto kept = h.kept(0.75f);
  EXPECT_EQ(kept.bricks, 2u);  // (0,0,0) and (16,0,0)
  EXPECT_EQ(kept.nodes1, 2u);
  EXPECT_EQ(kept.nodes2, 1u);
  kept = h.kept(1.5f);  // between the bricks of node (0,0,0): the node keeps it, no brick does
  EXPECT_EQ(kept.bricks, 1u);
  EXPECT_EQ(kept.nodes1, 2u);
  kept = h.kept(5.5f);
  EXPECT_EQ(kept.bricks, 1u);
  EXPECT_EQ(kept.nodes1, 1u);
  EXPECT_EQ(kept.nodes2, 1u);
  kept = h.kept(7.0f);
  EXPECT_EQ(kept.bricks + kept.nodes1 + kept.nodes2, 0u);
  // An active tile counts every brick it covers.
  bounds->tree().addTile(1, Coord(1024, 0, 0), Vec2f(0.0f, 1.0f), true);
  EXPECT_EQ(BoundsHierarchy(*bounds).total().bricks, 4u + 512u);
}

}  // namespace
}  // namespace fcc
