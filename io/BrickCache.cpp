#include "BrickCache.h"

#include <cstring>

namespace fcc::io {
namespace {

uint64_t brickKey(const glm::ivec3& b) {
  // 21 bits per axis covers +-2^20 bricks = +-2^24 packed voxels, beyond any grid that fits a disk.
  const auto u = [](int v) { return uint64_t(uint32_t(v) & 0x1FFFFFu); };
  return u(b.x) | (u(b.y) << 21) | (u(b.z) << 42);
}

// Shards: enough that 16+ loader threads, each touching 27 bricks a block, rarely meet on one lock
// (64 were too few on the H200 machine), few enough that each keeps a useful share of a small budget
// (at least 64 bricks a shard).
std::size_t shardCountFor(std::size_t budgetBricks) {
  std::size_t n = 1;
  while (n < 1024 && budgetBricks / (2 * n) >= 64) n *= 2;
  return n;
}
}  // namespace

BrickCache::BrickCache(const BrickStore& store, std::size_t budgetBytes)
    : store_(store),
      budgetBytes_(budgetBytes),
      shards_(shardCountFor(budgetBytes / kBytesPerBrick)) {
  bricksPerShard_ = budgetBytes / kBytesPerBrick / shards_.size();
}

void BrickCache::setBudgetBytes(std::size_t budgetBytes) {
  budgetBytes_ = budgetBytes;
  const std::size_t perShard = budgetBytes / kBytesPerBrick / shards_.size();
  bricksPerShard_ = perShard;
  for (Shard& shard : shards_) {
    std::lock_guard<std::mutex> lock(shard.mutex);
    while (!shard.lru.empty() && shard.entries.size() > perShard) {
      shard.entries.erase(shard.lru.back());
      shard.lru.pop_back();
    }
  }
}

BrickContent BrickCache::content(const glm::ivec3& brick) {
  BrickContent c;
  if (store_.hasLeaf(brick)) c.leaf = leafValues(brick);
  else c.constant = store_.constantValue(brick);
  return c;
}

std::shared_ptr<const CachedBrick> BrickCache::leafValues(const glm::ivec3& brick) {
  const uint64_t key = brickKey(brick);
  Shard& shard = shardOf(key);
  {
    std::lock_guard<std::mutex> lock(shard.mutex);
    auto it = shard.entries.find(key);
    if (it != shard.entries.end()) {
      shard.lru.splice(shard.lru.begin(), shard.lru, it->second.lru);
      ++shard.hits;
      return it->second.values;
    }
  }
  // Not make_shared: it would zero the 8 KB (Vec4f's default constructor is defaulted) to overwrite them.
  std::shared_ptr<CachedBrick> values(new CachedBrick);
  {
    // Decoding happens outside the lock; then leaf order (z fastest) to rows (x fastest).
    thread_local BrickValues leafOrder;
    store_.readBrick(brick, leafOrder);
    constexpr int D = kBrickPackedDim;
    for (int x = 0; x < D; ++x)
      for (int y = 0; y < D; ++y)
        for (int z = 0; z < D; ++z) values->voxels[(z * D + y) * D + x] = leafOrder[(x * D + y) * D + z];
  }
  decoded_.fetch_add(1, std::memory_order_relaxed);
  std::lock_guard<std::mutex> lock(shard.mutex);
  auto [it, inserted] = shard.entries.try_emplace(key);
  if (!inserted) return it->second.values;  // another thread decoded it meanwhile
  shard.lru.push_front(key);
  it->second = Entry{values, shard.lru.begin()};
  while (!shard.lru.empty() && shard.entries.size() > bricksPerShard_) {
    shard.entries.erase(shard.lru.back());
    shard.lru.pop_back();
  }
  return values;
}

uint64_t BrickCache::hitCount() const {
  uint64_t hits = 0;
  for (const Shard& shard : shards_) {
    std::lock_guard<std::mutex> lock(shard.mutex);
    hits += shard.hits;
  }
  return hits;
}

std::size_t BrickCache::bytesUsed() const {
  std::size_t bricks = 0;
  for (const Shard& shard : shards_) {
    std::lock_guard<std::mutex> lock(shard.mutex);
    bricks += shard.entries.size();
  }
  return bricks * kBytesPerBrick;
}

void BrickValuesMemo::clear() {
  held_.clear();
  held_.reserve(kMaxHeld);
  slotHeld_.fill(-1);
}

const BrickContent& BrickValuesMemo::content(const glm::ivec3& brick) {
  std::size_t slot = (brickKey(brick) * 0x9E3779B97F4A7C15ull) >> 40 & (kSlots - 1);
  for (;; slot = (slot + 1) & (kSlots - 1)) {
    const int16_t i = slotHeld_[slot];
    if (i < 0) break;
    if (held_[std::size_t(i)].first == brick) return held_[std::size_t(i)].second;
  }
  if (held_.size() == kMaxHeld) {
    clear();
    return content(brick);
  }
  slotHeld_[slot] = int16_t(held_.size());
  held_.emplace_back(brick, source_.content(brick));
  return held_.back().second;
}

namespace {

// One neighbour brick's part of a block row: its leaf's row (x fastest), or its constant value.
struct RowSource {
  const openvdb::Vec4f* leaf = nullptr;  // the brick's voxels, or null for `constant`
  openvdb::Vec4f constant{0.0f};
};

RowSource rowSourceOf(const BrickContent& content) {
  return content.leaf ? RowSource{content.leaf->voxels.data(), openvdb::Vec4f(0.0f)} : RowSource{nullptr, content.constant};
}

// `count` voxels of a block row from `source`, starting at voxel (lx, ly, lz) of its brick. Sizes are
// constants at every call, so the copies are inlined moves, not library calls.
template <int kCount>
inline void copyRow(const RowSource& source, int lx, int ly, int lz, float* dst) {
  constexpr int D = kBrickPackedDim;
  if (source.leaf) {
    std::memcpy(dst, source.leaf[(lz * D + ly) * D + lx].asPointer(), kCount * 4 * sizeof(float));
  } else {
    for (int i = 0; i < kCount; ++i) std::memcpy(dst + 4 * i, source.constant.asPointer(), 4 * sizeof(float));
  }
}

}  // namespace

void assembleHaloBlock(const BrickStore& /*store*/, BrickValuesMemo& source, const glm::ivec3& brick, float* out) {
  constexpr int D = kBrickPackedDim, H = kHaloBlockDim;
  static_assert(sizeof(openvdb::Vec4f) == 4 * sizeof(float), "Vec4f packs four floats");
  // Block voxel (x, y, z) is packed voxel 8b - 1 + (x, y, z). Each block row (y, z) is one voxel of the
  // -x neighbour's last column, 8 of the middle brick's row, one of the +x neighbour's first column;
  // the three bricks are the same for every row of a (ny, nz) neighbour pair: 9 pairs of 27 lookups.
  for (int nz = -1; nz <= 1; ++nz)
    for (int ny = -1; ny <= 1; ++ny) {
      const int zLo = nz < 0 ? 0 : (nz == 0 ? 1 : D + 1), zHi = nz < 0 ? 1 : (nz == 0 ? D + 1 : H);
      const int yLo = ny < 0 ? 0 : (ny == 0 ? 1 : D + 1), yHi = ny < 0 ? 1 : (ny == 0 ? D + 1 : H);
      // The memo clears itself only here, not between the three lookups: their contents stay held.
      source.makeRoom(3);
      const RowSource left = rowSourceOf(source.content(brick + glm::ivec3(-1, ny, nz)));
      const RowSource middle = rowSourceOf(source.content(brick + glm::ivec3(0, ny, nz)));
      const RowSource right = rowSourceOf(source.content(brick + glm::ivec3(1, ny, nz)));
      for (int z = zLo; z < zHi; ++z)
        for (int y = yLo; y < yHi; ++y) {
          // In the neighbour (ny, nz): packed voxel (y, z) - 1 - 8 n.
          const int ly = (y - 1) - ny * D, lz = (z - 1) - nz * D;
          float* row = out + 4 * ((z * H + y) * H);
          copyRow<1>(left, D - 1, ly, lz, row);
          copyRow<D>(middle, 0, ly, lz, row + 4);
          copyRow<1>(right, 0, ly, lz, row + 4 * (D + 1));
        }
    }
}

}  // namespace fcc::io
