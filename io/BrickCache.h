// The host cache of decoded bricks: a least-recently-used map from brick coordinates to decoded
// values, bounded in bytes (`--host-cache`). OpenVDB's tree stays the index only (io/BrickStore.h).
#pragma once

#include <glm/glm.hpp>

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "BrickStore.h"

namespace fcc::io {

// A decoded brick as the host cache keeps it: the 8^3 packed voxels x fastest, index (z * 8 + y) * 8 + x.
// BrickStore::readBrick gives OpenVDB's leaf order (z fastest); the cache transposes once, on
// insertion, so that io::assembleHaloBlock copies whole rows instead of single voxels.
struct CachedBrick {
  std::array<openvdb::Vec4f, kBrickPackedDim * kBrickPackedDim * kBrickPackedDim> voxels;
};

// What one brick contributes to a halo block: its cached leaf, or (no leaf) one value everywhere.
struct BrickContent {
  std::shared_ptr<const CachedBrick> leaf;
  openvdb::Vec4f constant{0.0f};
};

// Where io::assembleHaloBlock finds the bricks around a block.
class BrickValuesSource {
 public:
  virtual ~BrickValuesSource() = default;
  virtual BrickContent content(const glm::ivec3& brick) = 0;
};

class BrickCache : public BrickValuesSource {
 public:
  // Bytes one cached brick costs, with its bookkeeping.
  static constexpr std::size_t kBytesPerBrick = sizeof(CachedBrick) + 96;

  BrickCache(const BrickStore& store, std::size_t budgetBytes);

  // A brick's leaf from the cache or decoded now (and cached), or its constant value. Thread-safe; the
  // returned values stay valid while held, even if evicted meanwhile.
  BrickContent content(const glm::ivec3& brick) override;

  std::size_t budgetBytes() const { return budgetBytes_.load(std::memory_order_relaxed); }
  // A new budget, evicting least recently used bricks now if the cache holds more (the renderer gives
  // part of --host-cache to the coarser levels of a pyramid once it knows the file has them).
  void setBudgetBytes(std::size_t budgetBytes);
  std::size_t bytesUsed() const;
  uint64_t decodedCount() const { return decoded_.load(std::memory_order_relaxed); }  // bricks decoded so far
  uint64_t hitCount() const;

 private:
  // The cache is split by brick into shards, each its own LRU list under its own lock, so that the
  // loader's threads (27 lookups per halo block) do not queue on one mutex. Eviction is per shard:
  // each holds an equal share of the budget.
  std::shared_ptr<const CachedBrick> leafValues(const glm::ivec3& brick);  // cached, or decoded now
  struct Entry {
    std::shared_ptr<const CachedBrick> values;
    std::list<uint64_t>::iterator lru;
  };
  struct Shard {
    mutable std::mutex mutex;
    std::list<uint64_t> lru;  // most recent first
    std::unordered_map<uint64_t, Entry> entries;
    uint64_t hits = 0;  // under the shard's lock: one counter for all threads was a cache line they all wrote
  };
  Shard& shardOf(uint64_t key) { return shards_[(key * 0x9E3779B97F4A7C15ull) >> 54 & (shards_.size() - 1)]; }

  const BrickStore& store_;
  std::atomic<std::size_t> budgetBytes_;
  std::atomic<std::size_t> bricksPerShard_;
  std::vector<Shard> shards_;  // a power of two of them
  std::atomic<uint64_t> decoded_{0};
};

// A few bricks' contents held for a batch of halo blocks, in front of a cache: neighbouring blocks
// share most of their 27 bricks, and each lookup in the shared cache takes a lock that all loader
// threads contend for (and two tree probes for a brick without a leaf). Lookups return a reference,
// not a copy: copying the shared pointer 27 times a block moved reference counts that other loader
// threads' blocks touch too. Found through a small open-addressing table, not a scan of what is held.
// Not thread-safe: one a thread.
class BrickValuesMemo {
 public:
  explicit BrickValuesMemo(BrickValuesSource& source) : source_(source) { clear(); }
  // Valid until clear(), which a lookup may call when the memo is full, or makeRoom.
  const BrickContent& content(const glm::ivec3& brick);
  // Clears the memo now if `lookups` more could fill it: the contents of the next `lookups` lookups
  // then stay valid together.
  void makeRoom(std::size_t lookups) {
    if (held_.size() + lookups > kMaxHeld) clear();
  }
  void clear();

 private:
  static constexpr std::size_t kSlots = 512;         // a power of two
  static constexpr std::size_t kMaxHeld = kSlots / 2;  // then cleared: probes stay short
  BrickValuesSource& source_;
  std::vector<std::pair<glm::ivec3, BrickContent>> held_;
  std::array<int16_t, kSlots> slotHeld_{};  // index into held_, or -1
};

// The packed voxels [8b - 1, 8b + 9)^3 of brick b (the brick and the one-voxel halo its cells'
// stencils reach), x fastest, as four floats each: what one pool slot of the renderer holds.
inline constexpr int kHaloBlockDim = kBrickPackedDim + 2;
inline constexpr int kHaloBlockVoxels = kHaloBlockDim * kHaloBlockDim * kHaloBlockDim;
void assembleHaloBlock(const BrickStore& store, BrickValuesMemo& values, const glm::ivec3& brick, float* out);

}  // namespace fcc::io
