#include "CartesianBrickStore.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <array>
#include <map>

#include "UserCache.h"
#include "VdbFile.h"
#include "WorldFromIndex.h"
#include "VdbLeafReader.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

constexpr int kLeafDim = 8;
constexpr int kLeavesPerBrick = CartesianBrickStore::kBrickSites / kLeafDim;  // 2 along each axis

// The leaf-sized boxes (by origin, in leaf units) a brick's block touches: 16 b - 2 .. 16 b + 17 spans
// leaves 2 b - 1 .. 2 b + 2.
template <class Visit>
void forEachBlockLeaf(const glm::ivec3& brick, Visit&& visit) {
  for (int lz = -1; lz <= kLeavesPerBrick; ++lz)
    for (int ly = -1; ly <= kLeavesPerBrick; ++ly)
      for (int lx = -1; lx <= kLeavesPerBrick; ++lx)
        visit(glm::ivec3(kLeavesPerBrick * brick.x + lx, kLeavesPerBrick * brick.y + ly, kLeavesPerBrick * brick.z + lz));
}

}  // namespace

CartesianBrickStore::CartesianBrickStore(const std::string& path, const std::string& gridName, bool cacheRanges)
    : path_(path) {
  const std::vector<std::string> types{"Tree_float_5_4_3"};
  guardLeafRead(path, gridName, types);
  try {
    reader_ = std::make_shared<VdbLeafReader>(path, gridName, types);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path + ": OpenVDB cannot read it: " + e.what());
  }
  grid_ = openvdb::gridPtrCast<openvdb::FloatGrid>(reader_->grid());
  if (!grid_) throw InputError(path + ": grid '" + reader_->gridName() + "' is not a float grid");
  background_ = grid_->background();
  levelSet_ = grid_->getGridClass() == openvdb::GRID_LEVEL_SET;
  worldFromIndex_ = affineWorldFromIndex(grid_->transform(), path);
  // Bricks touched by data: every brick whose block reaches a leaf or a tile of another value.
  openvdb::CoordBBox box;  // empty until expanded
  // Brick b's block [16 b - 2, 16 b + 17] meets the voxels [lo, hi] when
  // ceil((lo - 17) / 16) <= b <= floor((hi + 2) / 16), per axis.
  auto grow = [&](const openvdb::CoordBBox& voxels) {
    for (int a = 0; a < 2; ++a) {
      const openvdb::Coord& v = a == 0 ? voxels.min() : voxels.max();
      const int shift = a == 0 ? -(kBlockDim - kBlockLo - 1) : kBlockLo;
      auto brickOf = [&](int x) {
        const double q = double(x + shift) / kBrickSites;
        return int(a == 0 ? std::ceil(q) : std::floor(q));
      };
      box.expand(openvdb::Coord(brickOf(v.x()), brickOf(v.y()), brickOf(v.z())));
    }
  };
  for (auto it = grid_->tree().cbeginLeaf(); it; ++it) grow(it->getNodeBoundingBox());
  // Tiles only: the iterator stops above the leaves (their voxels are covered by the leaves' boxes).
  auto tiles = grid_->tree().cbeginValueAll();
  tiles.setMaxDepth(openvdb::FloatTree::ValueAllCIter::LEAF_DEPTH - 1);
  for (; tiles; ++tiles)
    if (*tiles != background_) grow(tiles.getBoundingBox());
  activeBrickBox_ = box;
  // What the ranges depend on besides the file and the grid: how bricks and their blocks are cut.
  if (cacheRanges)
    rangeCacheKey_ = cartesianRangeCacheKey(path, reader_->gridName(),
                                            "bricks " + std::to_string(kBrickSites) + ", blocks from -" +
                                                std::to_string(kBlockLo) + " of " + std::to_string(kBlockDim) + " points, leaf slabs " +
                                                std::to_string(kBlockLo));
}

CartesianBrickStore::~CartesianBrickStore() = default;

void CartesianBrickStore::worldBounds(glm::dvec3& lo, glm::dvec3& hi) const {
  openvdb::CoordBBox voxels = grid_->evalActiveVoxelBoundingBox();
  if (voxels.empty()) voxels = openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(0));
  worldBoxOfIndexBox(worldFromIndex_, glm::dvec3(voxels.min().x(), voxels.min().y(), voxels.min().z()),
                     glm::dvec3(voxels.max().x(), voxels.max().y(), voxels.max().z()), lo, hi);
}

float CartesianBrickStore::constantAt(const openvdb::Coord& origin) const {
  // Only where no leaf exists: getValue reads a tile or the background and loads nothing.
  return grid_->tree().getValue(origin);
}

bool CartesianBrickStore::readLeaf(size_t i, float* values) const {
  leavesRead_.fetch_add(1, std::memory_order_relaxed);
  try {
    reader_->readLeaf(i, values);
    return true;
  } catch (const InputError& e) {  // the leaf's bytes failed our checks: never trusted (io/Damage.h)
    damageLog_.record(i, e.what());
    return false;
  }
}

void CartesianBrickStore::readBlock(const glm::ivec3& brick, float* out) const {
  readBox(brick * kBrickSites - kBlockLo, glm::ivec3(kBlockDim), out);
}

void CartesianBrickStore::readBox(const glm::ivec3& boxMin, const glm::ivec3& dims, float* out) const {
  std::array<float, 512> leafValues;
  const auto at = [&](int x, int y, int z) { return out + (std::ptrdiff_t(z) * dims.y + y) * dims.x + x; };
  const glm::ivec3 firstLeaf = glm::ivec3(glm::floor(glm::vec3(boxMin) / float(kLeafDim)));
  const glm::ivec3 lastLeaf = glm::ivec3(glm::floor(glm::vec3(boxMin + dims - 1) / float(kLeafDim)));
  for (int lz = firstLeaf.z; lz <= lastLeaf.z; ++lz)
    for (int ly = firstLeaf.y; ly <= lastLeaf.y; ++ly)
      for (int lx = firstLeaf.x; lx <= lastLeaf.x; ++lx) {
        const glm::ivec3 leaf(lx, ly, lz);
        const openvdb::Coord origin(leaf.x * kLeafDim, leaf.y * kLeafDim, leaf.z * kLeafDim);
        // The part of this leaf inside the box, in box coordinates: [lo, hi).
        const glm::ivec3 leafMin = leaf * kLeafDim - boxMin;
        const glm::ivec3 lo = glm::max(leafMin, glm::ivec3(0)), hi = glm::min(leafMin + kLeafDim, dims);
        if (glm::any(glm::greaterThanEqual(lo, hi))) continue;
        const std::optional<size_t> index = reader_->leafIndexAt(origin);
        // No leaf: a tile's value or the background; a damaged leaf: the background (a hole).
        if (!index || !readLeaf(*index, leafValues.data())) {
          const float v = index ? background_ : constantAt(origin);
          for (int z = lo.z; z < hi.z; ++z)
            for (int y = lo.y; y < hi.y; ++y) std::fill(at(lo.x, y, z), at(hi.x, y, z), v);
          continue;
        }
        // OpenVDB's order: x << 6 | y << 3 | z
        for (int z = lo.z; z < hi.z; ++z)
          for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) {
              const glm::ivec3 l = glm::ivec3(x, y, z) - leafMin;
              *at(x, y, z) = leafValues[(l.x << 6) | (l.y << 3) | l.z];
            }
      }
}

std::vector<CartesianBrickStore::BrickRange> CartesianBrickStore::computeBrickRanges() const {
  // A block takes all of its 2 x 2 x 2 middle leaves but only two layers of the leaves around them
  // (16 b - 2 .. 16 b - 1 is the top of leaf 2 b - 1, 16 b + 16 .. 16 b + 17 the bottom of leaf 2 b + 2).
  // So each leaf's values are reduced once (in parallel) to seven ranges: all of it, and its two-layer
  // slabs at either end of each axis; a leaf partly in a block contributes the intersection of the
  // ranges of the slabs it shares with the block (the values there lie in each of them), which keeps
  // the bricks next to a thin shell of data from being listed for data that is not in their block.
  constexpr int kSlab = kBlockLo;
  const size_t leaves = reader_->leafCount();
  struct LeafRanges {
    glm::vec2 all, low[3], high[3];
  };
  std::vector<LeafRanges> leafRanges(leaves);
  tbb::parallel_for(size_t(0), leaves, [&](size_t i) {
    std::array<float, 512> values;
    // A damaged leaf reads as the background here as in readBox, so the ranges hold what blocks hold.
    if (!readLeaf(i, values.data())) values.fill(background_);  // OpenVDB's order: x << 6 | y << 3 | z
    const float inf = std::numeric_limits<float>::infinity();
    LeafRanges r;
    r.all = glm::vec2(inf, -inf);
    for (int a = 0; a < 3; ++a) r.low[a] = r.high[a] = r.all;
    auto add = [](glm::vec2& range, float v) { range = glm::vec2(std::min(range.x, v), std::max(range.y, v)); };
    for (int n = 0; n < 512; ++n) {
      const int c[3] = {n >> 6, (n >> 3) & 7, n & 7};
      add(r.all, values[n]);
      for (int a = 0; a < 3; ++a) {
        if (c[a] < kSlab) add(r.low[a], values[n]);
        if (c[a] >= kLeafDim - kSlab) add(r.high[a], values[n]);
      }
    }
    leafRanges[i] = r;
  });
  std::vector<BrickRange> ranges;
  if (activeBrickBox_.empty()) return ranges;
  // One layer of bricks a task (a 2048^3 grid's box holds 2 M bricks), concatenated in z order.
  const int zFirst = activeBrickBox_.min().z(), layers = activeBrickBox_.max().z() - zFirst + 1;
  std::vector<std::vector<BrickRange>> byLayer(static_cast<std::size_t>(layers));
  tbb::parallel_for(0, layers, [&](int layer) {
    const int bz = zFirst + layer;
    std::vector<BrickRange>& out = byLayer[std::size_t(layer)];
    for (int by = activeBrickBox_.min().y(); by <= activeBrickBox_.max().y(); ++by)
      for (int bx = activeBrickBox_.min().x(); bx <= activeBrickBox_.max().x(); ++bx) {
        const glm::ivec3 brick(bx, by, bz);
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        bool varies = false;
        forEachBlockLeaf(brick, [&](const glm::ivec3& leaf) {
          const openvdb::Coord origin(leaf.x * kLeafDim, leaf.y * kLeafDim, leaf.z * kLeafDim);
          glm::vec2 r;
          if (const std::optional<size_t> index = reader_->leafIndexAt(origin)) {
            const LeafRanges& l = leafRanges[*index];
            r = l.all;
            for (int a = 0; a < 3; ++a) {
              const int rel = leaf[a] - kLeavesPerBrick * brick[a];  // -1 .. 2
              const glm::vec2 slab = rel < 0 ? l.high[a] : (rel >= kLeavesPerBrick ? l.low[a] : l.all);
              r = glm::vec2(std::max(r.x, slab.x), std::min(r.y, slab.y));
            }
          } else {
            r = glm::vec2(constantAt(origin));
          }
          if (r.x != background_ || r.y != background_) varies = true;
          lo = std::min(lo, r.x);
          hi = std::max(hi, r.y);
        });
        if (varies) out.push_back({brick, lo, hi});
      }
  });
  for (const std::vector<BrickRange>& layer : byLayer) ranges.insert(ranges.end(), layer.begin(), layer.end());
  return ranges;
}

std::string CartesianBrickStore::rangeCacheFile() const {
  return rangeCacheKey_.empty() ? std::string() : cartesianRangeCachePath(conversionCacheDir(), path_, rangeCacheKey_);
}

CartesianBrickStore::RangesFrom CartesianBrickStore::rangesFrom() const {
  std::lock_guard<std::mutex> lock(rangesMutex_);
  return rangesFrom_;
}

const std::vector<CartesianBrickStore::BrickRange>& CartesianBrickStore::brickRanges() const {
  std::lock_guard<std::mutex> lock(rangesMutex_);
  if (ranges_) return *ranges_;
  const std::string file = rangeCacheFile();
  if (!file.empty()) {
    const openvdb::CoordBBox& b = activeBrickBox_;  // empty: lo > hi, and only an empty list is valid
    const glm::ivec3 lo(b.min().x(), b.min().y(), b.min().z()), hi(b.max().x(), b.max().y(), b.max().z());
    if (std::optional<std::vector<BrickRange>> cached = readCartesianRangeCache(file, rangeCacheKey_, lo, hi)) {
      touchCacheFile(file);  // used now: the last to be evicted
      ranges_ = std::move(cached);
      rangesFrom_ = RangesFrom::Cache;
      return *ranges_;
    }
  }
  ranges_ = computeBrickRanges();
  rangesFrom_ = RangesFrom::Leaves;
  // A damaged file's ranges are not kept: each open then meets its damage again, and reports it.
  if (!file.empty() && !damageLog_.any()) {
    try {
      const std::string dir = conversionCacheDir();
      std::filesystem::create_directories(dir);
      writeCartesianRangeCache(file, rangeCacheKey_, *ranges_);
      boundCacheFolder(dir, file);
    } catch (const std::exception&) {
      // The cache only saves the pass over the leaves: a folder that cannot be written costs it again
      // next time, and this open has its ranges.
    }
  }
  return *ranges_;
}

}  // namespace fcc::io
