// Preprocessing drivers (which bricks need work, tiles, assembling the grids) and the C++/TBB
// reference of the per-brick work. The OpenCL kernels (kernels/preprocess.cl) do the same per-brick
// work; see sparse/BrickKernels.h.
#include "BrickBounds.h"

#include <openvdb/tools/Prune.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <limits>

#include "BrickKernels.h"
#include "Error.h"
#include "Lattice.h"
#include "PrefilterBricks.h"
#include "Spline.h"

namespace fcc {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using openvdb::Vec2f;
using openvdb::Vec4f;
using FccLeaf = FccTree::LeafNodeType;
static_assert(FccLeaf::DIM == kBrickPackedDim, "a brick is a leaf of the FCC tree");

constexpr int kHaloSide = kBrickPackedDim + 2;  // packed voxels of a brick and its one-voxel halo
constexpr size_t kBatchBricks = 8192;           // bricks per call into the kernels: bounds the memory
constexpr size_t kPrefilterBatchBricks = 1024;  // the prefilter's: 8 MiB of results, reused

Vec2f hullOf(const Vec4f& v) {
  return Vec2f(std::min(std::min(v[0], v[1]), std::min(v[2], v[3])), std::max(std::max(v[0], v[1]), std::max(v[2], v[3])));
}

Vec2f hullOf(const Vec2f& a, const Vec2f& b) { return Vec2f(std::min(a[0], b[0]), std::max(a[1], b[1])); }

Coord brickOfPacked(const Coord& packed) { return Coord(packed.x() >> 3, packed.y() >> 3, packed.z() >> 3); }
Coord packedOfBrick(const Coord& brick) { return Coord(brick.x() * kBrickPackedDim, brick.y() * kBrickPackedDim, brick.z() * kBrickPackedDim); }

// Marks bricks from `count` work items in parallel, each thread into a mask of its own (through an
// accessor: these are millions of bricks per slab of a large level set), merged at the end (a
// union of bit masks, node by node). mark(i, accessor) marks what item i marks.
template <class Mark>
openvdb::MaskTree markInParallel(std::size_t count, std::size_t grain, Mark&& mark) {
  tbb::enumerable_thread_specific<openvdb::MaskTree> masks;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, grain), [&](const tbb::blocked_range<size_t>& r) {
    openvdb::tree::ValueAccessor<openvdb::MaskTree> marked(masks.local());
    for (size_t i = r.begin(); i != r.end(); ++i) mark(i, marked);
  });
  openvdb::MaskTree all;
  for (openvdb::MaskTree& m : masks) all.topologyUnion(m);
  return all;
}

std::vector<Coord> activeCoords(const openvdb::MaskTree& mask) {
  std::vector<Coord> coords;
  coords.reserve(mask.activeVoxelCount());
  for (auto it = mask.cbeginValueOn(); it; ++it) coords.push_back(it.getCoord());
  return coords;
}

// The leaves' bricks and their 26 neighbours inside `region`: the bricks whose halo holds a leaf value.
std::vector<Coord> leafBricksDilated(const FccTree& tree, const CoordBBox& region) {
  std::vector<const FccLeaf*> leaves;
  tree.getNodes(leaves);
  return activeCoords(markInParallel(leaves.size(), 64, [&](size_t i, auto& marked) {
    const Coord b = brickOfPacked(leaves[i]->origin());
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          if (region.isInside(b.offsetBy(dx, dy, dz))) marked.setValueOn(b.offsetBy(dx, dy, dz));
  }));
}

// A tile of the FCC tree (a region of one constant Vec4 value) that differs from the background.
struct Tile {
  CoordBBox bricks;  // brick coordinates covered
  Vec4f value;
};

std::vector<Tile> nonBackgroundTiles(const FccTree& tree) {
  std::vector<Tile> tiles;
  auto add = [&](std::vector<Tile>& out, const CoordBBox& packed, const Vec4f& value) {
    // Active or not, the background is the same constant spline as outside.
    if (value != tree.background()) out.push_back({CoordBBox(brickOfPacked(packed.min()), brickOfPacked(packed.max())), value});
  };
  // The root's and the upper internal nodes' tiles (few), then the lower internal nodes' (leaf-sized
  // tiles: a level set's inside is thousands of them; 4096 entries a node to look at) in parallel,
  // in node order.
  auto it = tree.cbeginValueAll();
  it.setMaxDepth(FccTree::ValueAllCIter::LEAF_DEPTH - 2);
  for (; it; ++it) add(tiles, it.getBoundingBox(), *it);
  using Lower = FccTree::RootNodeType::ChildNodeType::ChildNodeType;
  std::vector<const Lower*> nodes;
  tree.getNodes(nodes);
  std::vector<std::vector<Tile>> perNode(nodes.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, nodes.size(), 4), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t n = r.begin(); n != r.end(); ++n)
      for (auto v = nodes[n]->cbeginValueAll(); v; ++v)
        add(perNode[n], CoordBBox::createCube(v.getCoord(), int(FccLeaf::DIM)), *v);
  });
  for (const std::vector<Tile>& t : perNode) tiles.insert(tiles.end(), t.begin(), t.end());
  return tiles;
}

// Calls f(brick) for every brick within one brick of `box`'s boundary, inside or outside (the bricks
// whose halo sees both the tile and what surrounds it).
template <class F>
void forEachShellBrick(const CoordBBox& box, F&& f) {
  const CoordBBox outer = box.expandBy(1);
  auto onShell = [&](int v, int lo, int hi) { return v <= lo + 1 || v >= hi - 1; };
  for (int z = outer.min().z(); z <= outer.max().z(); ++z)
    for (int y = outer.min().y(); y <= outer.max().y(); ++y) {
      const bool yzShell = onShell(z, outer.min().z(), outer.max().z()) || onShell(y, outer.min().y(), outer.max().y());
      if (yzShell) {
        for (int x = outer.min().x(); x <= outer.max().x(); ++x) f(Coord(x, y, z));
      } else {
        for (int x : {outer.min().x(), outer.min().x() + 1, outer.max().x() - 1, outer.max().x()})
          if (x >= outer.min().x() && x <= outer.max().x()) f(Coord(x, y, z));
      }
    }
}

// Whether bricks `box` or their neighbours reach `region` (which may be CoordBBox::inf()).
bool touchesRegion(const CoordBBox& box, const CoordBBox& region) {
  CoordBBox near = region;  // grown by one brick where it is bounded (a slab is unbounded in y and z)
  for (int a = 0; a < 3; ++a) {
    if (near.min()[a] > std::numeric_limits<int>::min()) near.min()[a] -= 1;
    if (near.max()[a] < std::numeric_limits<int>::max()) near.max()[a] += 1;
  }
  return box.hasOverlap(near);
}

// The packed voxels [8b - 1, 8b + 9)^3 of brick b, read through a value accessor (leaves, tiles and
// the background alike): values[((pz * 10 + py) * 10 + px) * 4 + channel].
struct HaloBlock {
  glm::ivec3 packedOrigin;  // packed voxel of element 0
  float values[kHaloSide * kHaloSide * kHaloSide * 4];

  void gather(FccGrid::ConstAccessor& accessor, const Coord& brick) {
    packedOrigin = glm::ivec3(brick.x(), brick.y(), brick.z()) * kBrickPackedDim - 1;
    float* out = values;
    for (int z = 0; z < kHaloSide; ++z)
      for (int y = 0; y < kHaloSide; ++y)
        for (int x = 0; x < kHaloSide; ++x, out += 4) {
          const Vec4f& v = accessor.getValue(Coord(packedOrigin.x + x, packedOrigin.y + y, packedOrigin.z + z));
          for (int c = 0; c < 4; ++c) out[c] = v[c];
        }
  }
  // Whether every value of the 3^3 packed voxels around the one holding `corner` (its cell, all four
  // channels: what the OpenCL kernel tests per cell, so both skip the same cubes) is one value v. The
  // unit cube at `corner` reads a part of them (sites [corner - 1, corner + 2]^3), so the spline there
  // is v (partition of unity) and its bounds are (v, v) without computing BB-coefficients (air in
  // scans, a level set's inside and outside).
  bool cubeReadsOneValue(const glm::ivec3& corner, float& v) const {
    const glm::ivec3 cell = packedVoxelOfSite(corner) - packedOrigin;
    const glm::ivec3 lo = cell - 1, hi = cell + 1;
    v = values[((lo.z * kHaloSide + lo.y) * kHaloSide + lo.x) * 4];
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          const float* c = values + ((z * kHaloSide + y) * kHaloSide + x) * 4;
          if (c[0] != v || c[1] != v || c[2] != v || c[3] != v) return false;
        }
    return true;
  }
  // The value at FCC site ijk (which must lie in the block).
  float at(const glm::ivec3& ijk) const {
    const glm::ivec3 p = packedVoxelOfSite(ijk) - packedOrigin;
    return values[((p.z * kHaloSide + p.y) * kHaloSide + p.x) * 4 + channelOfSite(ijk)];
  }
};

class ReferenceBrickKernels : public BrickKernels {
 public:
  std::string describe() const override { return "reference (C++/TBB)"; }

  void bounds(const FccGrid& coefficients, const std::vector<Coord>& bricks, std::vector<Vec2f>& out) override {
    const auto start = std::chrono::steady_clock::now();
    out.resize(bricks.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, bricks.size(), 4), [&](const tbb::blocked_range<size_t>& r) {
      auto accessor = coefficients.getConstAccessor();
      auto block = std::make_unique<HaloBlock>();
      auto coefficientAt = [&](const glm::ivec3& ijk) { return block->at(ijk); };
      for (size_t i = r.begin(); i != r.end(); ++i) {
        block->gather(accessor, bricks[i]);
        const glm::ivec3 siteOrigin = glm::ivec3(bricks[i].x(), bricks[i].y(), bricks[i].z()) * kBrickSites;
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        for (int z = 0; z < kBrickSites; ++z)
          for (int y = 0; y < kBrickSites; ++y)
            for (int x = 0; x < kBrickSites; ++x) {
              const glm::ivec3 corner = siteOrigin + glm::ivec3(x, y, z);
              float constant;
              if (block->cubeReadsOneValue(corner, constant)) {
                lo = std::min(lo, constant);
                hi = std::max(hi, constant);
                continue;
              }
              const spline::FccRange b = spline::cubeBounds(corner, coefficientAt);
              lo = std::min(lo, b.lo);
              hi = std::max(hi, b.hi);
            }
        out[i] = Vec2f(lo, hi);
      }
    });
    computeSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  // Vectorised over channel planes (sparse/PrefilterBricks.h), bit for bit spline::prefilterAt per site.
  void prefilter(const FccGrid& samples, const std::vector<Coord>& bricks, std::vector<Vec4f>& out) override {
    const auto start = std::chrono::steady_clock::now();
    out.resize(bricks.size() * FccLeaf::SIZE);
    prefilterBricks(samples, bricks, out.data());
    computeSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  // Each leaf built from its results while they are in the computing thread's cache.
  void prefilterLeaves(const FccGrid& samples, const std::vector<Coord>& bricks, std::vector<FccLeaf*>& leaves) override {
    const auto start = std::chrono::steady_clock::now();
    const Vec4f background = samples.background();
    leaves.assign(bricks.size(), nullptr);
    prefilterBricks(samples, bricks, [&](std::size_t i, const Vec4f* values) {
      leaves[i] = makeCoefficientLeaf(bricks[i], values, background);
    });
    computeSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
};

BrickKernels& orReference(BrickKernels* kernels, std::unique_ptr<BrickKernels>& own) {
  if (kernels) return *kernels;
  own = makeReferenceBrickKernels();
  return *own;
}

}  // namespace

void BrickKernels::prefilterLeaves(const FccGrid& samples, const std::vector<Coord>& bricks, std::vector<FccLeaf*>& leaves) {
  // Batches of kPrefilterBatchBricks: their results (8 KiB a brick) are reused from batch to batch
  // instead of fresh memory for all (page faults and zeroing were a third of the C++ path's time).
  leaves.assign(bricks.size(), nullptr);
  std::vector<Vec4f> results;
  const Vec4f background = samples.background();
  for (size_t first = 0; first < bricks.size(); first += kPrefilterBatchBricks) {
    const std::vector<Coord> batch(bricks.begin() + first, bricks.begin() + std::min(bricks.size(), first + kPrefilterBatchBricks));
    prefilter(samples, batch, results);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, batch.size(), 16), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t i = r.begin(); i != r.end(); ++i)
        leaves[first + i] = makeCoefficientLeaf(batch[i], results.data() + i * FccLeaf::SIZE, background);
    });
  }
}

std::unique_ptr<BrickKernels> makeReferenceBrickKernels() { return std::make_unique<ReferenceBrickKernels>(); }

Vec2f boundsBackground(const Vec4f& fccBackground) { return hullOf(fccBackground); }

void computeBrickBoundsIn(const FccGrid& coefficients, const CoordBBox& region, BrickKernels& kernels,
                          openvdb::Vec2STree& tree) {
  const FccTree& fccTree = coefficients.tree();
  // Constant regions first, then the bricks at their borders, then the exact bricks, each
  // overwriting what came before where they overlap.
  const std::vector<Coord> exact = leafBricksDilated(fccTree, region);
  const std::vector<Tile> tiles = nonBackgroundTiles(fccTree);
  {
    // Most tiles are one brick (a uniform leaf): set through an accessor, the rest filled.
    openvdb::tree::ValueAccessor<openvdb::Vec2STree> single(tree);
    for (const Tile& t : tiles) {
      const Vec2f b = hullOf(t.value);
      CoordBBox inside = t.bricks;
      inside.intersect(region);
      if (inside.empty()) continue;
      if (inside.volume() == 1) {
        if (b[0] < b[1]) single.setValueOn(inside.min(), b);
        else single.setValueOff(inside.min(), b);
      } else {
        tree.fill(inside, b, b[0] < b[1]);
        single.clear();  // a fill may replace nodes the accessor holds
      }
    }
  }
  // After the fills (an accessor caches nodes a fill may replace).
  openvdb::tree::ValueAccessor<openvdb::Vec2STree> bounds(tree);
  auto set = [&](const Coord& brick, const Vec2f& b) {
    if (b[0] < b[1]) bounds.setValueOn(brick, b);
    else bounds.setValueOff(brick, b);
  };
  if (!tiles.empty()) {
    openvdb::MaskTree exactMask;
    {
      openvdb::tree::ValueAccessor<openvdb::MaskTree> marked(exactMask);
      for (const Coord& b : exact) marked.setValueOn(b);
    }
    // The border bricks, each once (neighbouring tiles share most of theirs: a level set's inside is
    // thousands of leaf-sized tiles), from the tiles that reach the region.
    using ExactAccessor = openvdb::tree::ValueAccessor<const openvdb::MaskTree>;
    tbb::enumerable_thread_specific<ExactAccessor> isExact([&] { return ExactAccessor(exactMask); });
    const std::vector<Coord> borderBricks = activeCoords(markInParallel(tiles.size(), 256, [&](size_t i, auto& marked) {
      if (!touchesRegion(tiles[i].bricks, region)) return;
      ExactAccessor& exactHere = isExact.local();
      forEachShellBrick(tiles[i].bricks, [&](const Coord& brick) {
        if (region.isInside(brick) && !exactHere.isValueOn(brick)) marked.setValueOn(brick);
      });
    }));
    std::vector<Vec2f> borderBounds(borderBricks.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, borderBricks.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
      openvdb::tree::ValueAccessor<const FccTree> values(fccTree);
      for (size_t i = r.begin(); i != r.end(); ++i) {
        // No leaf in the neighbourhood: each neighbour brick is one constant value (a tile, or the
        // background), and the spline is a convex combination of them.
        Vec2f b(std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity());
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
              b = hullOf(b, hullOf(values.getValue(packedOfBrick(borderBricks[i].offsetBy(dx, dy, dz)))));
        borderBounds[i] = b;
      }
    });
    for (size_t i = 0; i < borderBricks.size(); ++i) set(borderBricks[i], borderBounds[i]);
  }
  std::vector<Vec2f> results;
  for (size_t first = 0; first < exact.size(); first += kBatchBricks) {
    const std::vector<Coord> batch(exact.begin() + first, exact.begin() + std::min(exact.size(), first + kBatchBricks));
    kernels.bounds(coefficients, batch, results);
    kernels.bricksDone += batch.size();
    for (size_t i = 0; i < batch.size(); ++i) set(batch[i], results[i]);
  }
}

BoundsGrid::Ptr boundsGridOf(const openvdb::Vec2STree::Ptr& tree, const FccGrid& fcc) {
  auto grid = BoundsGrid::create(tree);
  grid->setName(boundsGridName(fcc.getName()));
  auto xform = fcc.transform().copy();
  xform->preScale(double(kBrickSites));
  grid->setTransform(xform);
  grid->insertMeta(meta::kBoundsOf, openvdb::StringMetadata(fcc.getName()));
  return grid;
}

BoundsGrid::Ptr computeBrickBounds(const FccGrid& coefficients, BrickKernels* kernelsOrNull) {
  if (storesSamples(coefficients))
    throw ValueError("grid '" + coefficients.getName() + "' stores raw samples: prefilter it before computing bounds");
  std::unique_ptr<BrickKernels> own;
  auto tree = std::make_shared<openvdb::Vec2STree>(boundsBackground(coefficients.background()));
  computeBrickBoundsIn(coefficients, CoordBBox::inf(), orReference(kernelsOrNull, own), *tree);
  openvdb::tools::prune(*tree);
  return boundsGridOf(tree, coefficients);
}

FccGrid::Ptr prefilterGrid(const FccGrid& samples, BrickKernels* kernelsOrNull, const CoordBBox& region) {
  std::unique_ptr<BrickKernels> own;
  BrickKernels& kernels = orReference(kernelsOrNull, own);
  const FccTree& in = samples.tree();
  const Vec4f background = in.background();
  FccGrid::Ptr grid = openvdb::gridPtrCast<FccGrid>(samples.copyGridWithNewTree());
  grid->insertMeta(meta::kValues, openvdb::StringMetadata(kValuesCoefficients));
  FccTree& out = grid->tree();

  // Inside a tile, away from its border, every site sees the tile's values only.
  std::vector<Coord> work = leafBricksDilated(in, region);
  const std::vector<Tile> tiles = nonBackgroundTiles(in);
  if (!tiles.empty()) {
    openvdb::MaskTree workMask;
    for (const Coord& b : work) workMask.setValueOn(b);
    for (const Tile& t : tiles) {
      Vec4f v;
      for (int c = 0; c < 4; ++c)
        v[c] = spline::prefilterAt(siteOfChannel(glm::ivec3(0), c), [&](const glm::ivec3& ijk) { return t.value[channelOfSite(ijk)]; });
      CoordBBox inside = t.bricks;
      inside.intersect(region);
      if (!inside.empty())
        out.fill(CoordBBox(packedOfBrick(inside.min()), packedOfBrick(inside.max()).offsetBy(kBrickPackedDim - 1)), v,
                 v != background);
      forEachShellBrick(t.bricks, [&](const Coord& brick) {
        if (region.isInside(brick)) workMask.setValueOn(brick);
      });
    }
    work.clear();
    for (auto it = workMask.cbeginValueOn(); it; ++it) work.push_back(it.getCoord());
  }

  std::vector<FccLeaf*> leaves;
  for (size_t first = 0; first < work.size(); first += kBatchBricks) {
    const std::vector<Coord> batch(work.begin() + first, work.begin() + std::min(work.size(), first + kBatchBricks));
    kernels.prefilterLeaves(samples, batch, leaves);
    kernels.bricksDone += batch.size();
    // Added to the tree (which is not thread-safe) in order.
    for (size_t i = 0; i < batch.size(); ++i) {
      if (leaves[i]) {
        out.addLeaf(leaves[i]);
      } else if (out.getValue(packedOfBrick(batch[i])) != background || out.isValueOn(packedOfBrick(batch[i]))) {
        out.addLeaf(new FccLeaf(packedOfBrick(batch[i]), background, false));  // a background brick inside a tile's region
      }
    }
  }
  openvdb::tools::prune(out);
  return grid;
}

FccGrid::ConstPtr valuesAsStored(const FccGrid::ConstPtr& grid) {
  if (!grid->saveFloatAsHalf()) return grid;
  FccGrid::Ptr rounded = grid->deepCopy();
  roundAsStoredHalf(rounded->tree().beginValueAll(), rounded->background());
  return rounded;
}

FccGrid::ConstPtr coefficientsOf(const FccGrid::ConstPtr& grid, BrickKernels* kernels) {
  if (!storesSamples(*grid)) return grid;
  return prefilterGrid(*grid, kernels);
}

}  // namespace fcc
