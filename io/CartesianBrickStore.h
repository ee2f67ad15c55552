// A Cartesian float grid (.vdb: fog volume or level set) opened out of core for direct rendering with a
// CC reconstruction of the layer (sparse/CcTrilinear.h, sparse/CcTricubic.h): its topology in memory,
// leaf values read on demand by our own reader (VdbLeafReader: pread, validated, nothing mapped).
//
// Bricks are 16^3 units of index space, as the FCC store's are (2 x 2 x 2 leaves of 8^3 voxels here),
// so the renderer's page table, residency and node skipping work in the same units for every lattice.
// A brick's block is the grid's values at the 20^3 points [16 b - 2, 16 b + 18)^3: every stencil of the
// CC reconstructions for the cells of the brick (-1 .. +2) and one more layer for the bounds.
#pragma once

#include <glm/glm.hpp>
#include <openvdb/openvdb.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "CartesianRangeCache.h"
#include "Damage.h"

namespace fcc::io {

class VdbLeafReader;

class CartesianBrickStore {
 public:
  static constexpr int kBrickSites = 16;  // index units along a brick's edge
  static constexpr int kBlockLo = 2;      // the block starts this far before the brick
  static constexpr int kBlockDim = 20;    // and is this many points along each axis
  static constexpr int kBlockPoints = kBlockDim * kBlockDim * kBlockDim;

  // Opens `gridName` (empty: the first float grid) of `path`: OpenVDB parses its topology first in the
  // guard's process (io/VdbFile.h). InputError (one line) for a file without a float grid or with a
  // transform that is not affine. `cacheRanges`: brickRanges() keeps the ranges in the user cache folder
  // (io/CartesianRangeCache.h) and reads them from there on a later open of the same grid and file.
  explicit CartesianBrickStore(const std::string& path, const std::string& gridName = {}, bool cacheRanges = false);
  ~CartesianBrickStore();

  const std::string& path() const { return path_; }
  float background() const { return background_; }
  bool levelSet() const { return levelSet_; }
  // worldFromIndex of the grid's index space (an affine map), column-vector convention.
  const glm::dmat4& worldFromIndex() const { return worldFromIndex_; }
  // The bricks whose block is not all the background (they touch a leaf or a tile of another value),
  // as an inclusive box of brick coordinates; empty for a grid of the background alone.
  const openvdb::CoordBBox& activeBrickBox() const { return activeBrickBox_; }
  // World-space bounding box of the active voxels (topology only: no leaf is read).
  void worldBounds(glm::dvec3& lo, glm::dvec3& hi) const;

  // The block of brick b, x fastest: out[(z * 20 + y) * 20 + x] is the value at 16 b - 2 + (x, y, z).
  // Thread-safe. A damaged leaf reads as the background (see damage()).
  void readBlock(const glm::ivec3& brick, float* out) const;
  // The grid's values at the points [boxMin, boxMin + dims), x fastest (dims.x * dims.y * dims.z floats).
  // Thread-safe. A damaged leaf reads as the background (see damage()).
  void readBox(const glm::ivec3& boxMin, const glm::ivec3& dims, float* out) const;

  // Per-brick (min, max) of every value of its block, for the bricks of activeBrickBox() whose block is
  // not all the background: conservative bounds of every CC reconstruction without prefilter (each is a
  // convex combination of the block's values). Reads every leaf once, in parallel; a damaged leaf
  // counts as the background there too, so a range holds what readBlock gives.
  using BrickRange = CartesianBrickRange;
  std::vector<BrickRange> computeBrickRanges() const;

  // computeBrickRanges()'s ranges, computed once for this store (thread-safe; every later call returns
  // the same vector). With `cacheRanges`, first looked for in the user cache under the file's path, size,
  // modification time and grid name: a whole, matching cache file is read instead of the leaves; else
  // they are computed and the cache file is written (atomically; not for a file that showed damage, whose
  // every open meets and reports it again; a folder that cannot be written only costs the pass again).
  const std::vector<BrickRange>& brickRanges() const;
  enum class RangesFrom { NotYet, Leaves, Cache };
  RangesFrom rangesFrom() const;
  // The cache file brickRanges() reads and writes; empty without `cacheRanges` or when the source
  // cannot be stat'ed.
  std::string rangeCacheFile() const;

  // The damaged leaves met so far (io/Damage.h, unit "leaf"): never trusted, each reads as the
  // background everywhere — its brick's block and its neighbours' — so it renders as a hole, and is
  // recorded once with its message ("FILE: leaf at (x, y, z) is damaged: WHAT"). Thread-safe.
  Damage damage() const { return damageLog_.damage(); }
  // Leaf buffers decoded so far, by every call (what tests count).
  uint64_t leavesRead() const { return leavesRead_.load(std::memory_order_relaxed); }

 private:
  // The value every voxel of the leaf-sized box at `origin` has when there is no leaf there.
  float constantAt(const openvdb::Coord& origin) const;
  // Leaf i's 512 values (OpenVDB's order) into `values`; false, with the damage recorded, when its bytes
  // are damaged (then `values` is unspecified).
  bool readLeaf(size_t i, float* values) const;

  std::string path_;
  std::shared_ptr<const VdbLeafReader> reader_;
  openvdb::FloatGrid::Ptr grid_;  // topology only: leaf buffers stay out of core
  float background_ = 0.0f;
  bool levelSet_ = false;
  glm::dmat4 worldFromIndex_{1.0};
  openvdb::CoordBBox activeBrickBox_;
  mutable DamageLog damageLog_{"leaf"};  // by leaf index
  mutable std::atomic<uint64_t> leavesRead_{0};
  std::string rangeCacheKey_;  // io/CartesianRangeCache.h's key of this grid; empty: no caching
  mutable std::mutex rangesMutex_;
  mutable std::optional<std::vector<BrickRange>> ranges_;
  mutable RangesFrom rangesFrom_ = RangesFrom::NotYet;
};

}  // namespace fcc::io
