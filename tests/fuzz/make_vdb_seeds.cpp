// Writes the seed corpus of fuzz_vdb_leaf_reader: small .vdb files (one root child each, a few leaves)
// covering what the reader distinguishes — float and Vec4f trees, every compression, half storage, every
// kind of inactive values (compression metadata 0 to 6), tiles at each level, a grid without leaves, a
// grid of another type and an instanced grid. Usage: fuzz_make_vdb_seeds FOLDER (make_seeds.py runs it).
#include <openvdb/openvdb.h>

#include <cstdio>
#include <string>

#include "sparse/BrickBounds.h"
#include "sparse/FccGrid.h"

namespace {

namespace vio = openvdb::io;
using openvdb::Coord;

template <class V>
V valueOf(float v);
template <>
float valueOf<float>(float v) {
  return v;
}
template <>
openvdb::Vec4f valueOf<openvdb::Vec4f>(float v) {
  return openvdb::Vec4f(v, -v, 0.5f * v, 1.0f);
}

// Leaves whose inactive voxels need each compression metadata value, a full and an empty leaf, and a
// tile at each internal level; all inside one root child (each costs 8 KiB of masks in the file).
template <class GridT>
typename GridT::Ptr grid(const std::string& name, float background, int leaves) {
  using V = typename GridT::ValueType;
  auto g = GridT::create(valueOf<V>(background));
  g->setName(name);
  auto& tree = g->tree();
  const V bg = valueOf<V>(background), minusBg = valueOf<V>(-background), seven = valueOf<V>(7.0f);
  for (int kind = 0; kind < leaves; ++kind) {
    auto* leaf = tree.touchLeaf(Coord(8 * kind, 8 * (kind % 3), 0));
    for (openvdb::Index n = 0; n < 512; ++n) {
      const bool active = kind == 7 || (kind != 8 && n % 5 == 0);
      V inactive = bg;
      switch (kind % 9) {
        case 1: inactive = minusBg; break;
        case 2: inactive = seven; break;
        case 3: inactive = n % 2 ? bg : minusBg; break;
        case 4: inactive = n % 2 ? bg : seven; break;
        case 5: inactive = n % 2 ? valueOf<V>(5.0f) : seven; break;
        case 6: inactive = valueOf<V>(float(n % 3)); break;
        default: break;
      }
      leaf->setValueOnly(n, active ? valueOf<V>(float(n % 17) - 8.0f) : inactive);
      leaf->setActiveState(n, active);
    }
  }
  tree.addTile(1, Coord(1024, 0, 0), valueOf<V>(3.0f), true);
  tree.addTile(2, Coord(2048, 0, 0), valueOf<V>(-4.0f), false);
  return g;
}

void write(const std::string& path, const openvdb::GridPtrVec& grids, uint32_t compression, bool half) {
  for (const auto& g : grids) g->setSaveFloatAsHalf(half);
  vio::File file(path);
  file.setCompression(compression);
  file.write(grids);
  file.close();
  std::printf("%s\n", path.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s FOLDER\n", argv[0]);
    return 2;
  }
  fcc::initializeVdb();
  const std::string dir = argv[1];
  const uint32_t mask = vio::COMPRESS_ACTIVE_MASK;
  using openvdb::FloatGrid;
  write(dir + "/float_blosc.vdb", {grid<FloatGrid>("density", 0.0f, 9)}, vio::COMPRESS_BLOSC | mask, false);
  write(dir + "/float_zip_half.vdb", {grid<FloatGrid>("density", 1.5f, 9)}, vio::COMPRESS_ZIP | mask, true);
  write(dir + "/float_plain.vdb", {grid<FloatGrid>("density", 2.0f, 2)}, vio::COMPRESS_NONE | mask, false);
  write(dir + "/float_zip_nomask.vdb", {grid<FloatGrid>("density", 2.0f, 2)}, vio::COMPRESS_ZIP, false);
  write(dir + "/float_blosc_half_nomask.vdb", {grid<FloatGrid>("d", 0.5f, 2)}, vio::COMPRESS_BLOSC, true);
  write(dir + "/vec4_blosc.vdb", {grid<fcc::FccGrid>("fcc", 0.0f, 3)}, vio::COMPRESS_BLOSC | mask, false);
  write(dir + "/vec4_plain_half.vdb", {grid<fcc::FccGrid>("fcc", 1.0f, 2)}, vio::COMPRESS_NONE | mask, true);
  write(dir + "/vec4_zip.vdb", {grid<fcc::FccGrid>("fcc", 0.25f, 2)}, vio::COMPRESS_ZIP | mask, false);
  // A grid without leaves, a grid of a type the reader refuses (the bounds grid's Vec2f), a float grid.
  {
    auto empty = FloatGrid::create(1.0f);
    empty->setName("empty");
    auto bounds = fcc::BoundsGrid::create();
    bounds->setName("bounds");
    bounds->tree().setValue(Coord(1, 2, 3), openvdb::Vec2f(-1.0f, 1.0f));
    write(dir + "/three_grids.vdb", {empty, bounds, grid<FloatGrid>("density", 0.0f, 1)}, vio::COMPRESS_BLOSC | mask,
          false);
  }
  // Two grids sharing one tree: OpenVDB writes the second as an instance of the first.
  {
    auto parent = grid<FloatGrid>("parent", 0.0f, 1);
    auto instance = parent->copy();
    instance->setName("instance");
    write(dir + "/instanced.vdb", {parent, instance}, vio::COMPRESS_BLOSC | mask, false);
  }
  return 0;
}
