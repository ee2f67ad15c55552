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
      hits_.fetch_add(1, std::memory_order_relaxed);
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

void assembleHaloBlock(const BrickStore& /*store*/, BrickValuesMemo& source, const glm::ivec3& brick, float* out) {
  constexpr int D = kBrickPackedDim, H = kHaloBlockDim;
  static_assert(sizeof(openvdb::Vec4f) == 4 * sizeof(float), "Vec4f packs four floats");
  // The 27 bricks the block touches: the centre and its neighbours (only their border layer is used).
  for (int nz = -1; nz <= 1; ++nz)
    for (int ny = -1; ny <= 1; ++ny)
      for (int nx = -1; nx <= 1; ++nx) {
        const glm::ivec3 n(nx, ny, nz);
        // Block coordinates covered by this neighbour: [lo, hi) per axis.
        glm::ivec3 lo, hi;
        for (int a = 0; a < 3; ++a) {
          lo[a] = n[a] < 0 ? 0 : (n[a] == 0 ? 1 : D + 1);
          hi[a] = n[a] < 0 ? 1 : (n[a] == 0 ? D + 1 : H);
        }
        const BrickContent& content = source.content(brick + n);
        const int run = hi.x - lo.x;
        // Block voxel (x, y, z) is packed voxel 8b - 1 + (x, y, z); in the neighbour, (x, y, z) - 1 - 8n.
        const int lx = lo.x - 1 - n.x * D;
        for (int z = lo.z; z < hi.z; ++z)
          for (int y = lo.y; y < hi.y; ++y) {
            float* dst = out + 4 * ((z * H + y) * H + lo.x);
            if (content.leaf) {
              const int ly = (y - 1) - n.y * D, lz = (z - 1) - n.z * D;
              std::memcpy(dst, content.leaf->voxels[(lz * D + ly) * D + lx].asPointer(), size_t(run) * 4 * sizeof(float));
            } else {
              for (int i = 0; i < run; ++i) std::memcpy(dst + 4 * i, content.constant.asPointer(), 4 * sizeof(float));
            }
          }
      }
}

}  // namespace fcc::io
