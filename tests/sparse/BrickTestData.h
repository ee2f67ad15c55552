// A small random FCC grid for the preprocessing tests: a cluster of touching leaves, isolated leaves,
// one-brick tiles (touching leaves and alone), a level-2 tile (16^3 bricks) beside a leaf, and a
// non-zero background.
#pragma once

#include <openvdb/openvdb.h>

#include <random>

#include "sparse/FccGrid.h"

namespace fcc::test {

constexpr float kBrickTestBackground = 0.125f;

inline FccGrid::Ptr randomBrickGrid(uint32_t seed, float activeFraction = 0.8f, float background = kBrickTestBackground) {
  initializeVdb();
  auto grid = FccGrid::create(openvdb::Vec4f(background));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f), unit(0.0f, 1.0f);
  auto& tree = grid->tree();
  auto fillBrick = [&](const openvdb::Coord& brick) {
    const openvdb::Coord o(brick.x() * 8, brick.y() * 8, brick.z() * 8);
    for (int z = 0; z < 8; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
          if (unit(rng) < activeFraction)
            tree.setValueOn(o.offsetBy(x, y, z), openvdb::Vec4f(value(rng), value(rng), value(rng), value(rng)));
  };
  // A 3x2x2 cluster of touching bricks, and bricks alone (also at negative coordinates).
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 3; ++x) fillBrick(openvdb::Coord(x, y, z));
  fillBrick(openvdb::Coord(6, 1, 0));
  fillBrick(openvdb::Coord(-4, -3, 2));
  fillBrick(openvdb::Coord(2, 5, -3));
  // One-brick tiles (level 1): touching the cluster, and alone; one with unequal channels.
  tree.addTile(1, openvdb::Coord(3 * 8, 0, 0), openvdb::Vec4f(0.9f), true);
  tree.addTile(1, openvdb::Coord(-8 * 8, 4 * 8, 1 * 8), openvdb::Vec4f(-0.5f, 0.25f, 0.75f, -0.125f), true);
  // A level-2 tile (128^3 packed voxels): bricks [-16, -1] x [0, 15] x [-16, -1] hold 0.5; the
  // cluster touches its corner, the leaf at brick (0, 5, -3) its face.
  fillBrick(openvdb::Coord(0, 5, -3));
  tree.addTile(2, openvdb::Coord(-128, 0, -128), openvdb::Vec4f(0.5f), true);
  return grid;
}

}  // namespace fcc::test
