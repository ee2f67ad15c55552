#include "BrickLoader.h"

#include <tbb/global_control.h>

#include <algorithm>

namespace fcc::render {
namespace {
// Most bricks a loader thread takes at once (512 KB of blocks): a chunk's halo blocks share one memo
// of cache look-ups (io::BrickValuesMemo), so larger chunks look up fewer bricks a block. H200, blobs
// 2048^3, `bench bricks --bricks 400000`, cache->blocks: 8: 449 k bricks/s, 32: 820 k (same run); 16:
// 523 k, 64: 504 k (a second run; the memo holds 256 bricks, which 64 overflow); full turn 23.2 -> 24.3 fps.
constexpr std::size_t kChunk = 32;
}  // namespace

BrickLoader::BrickLoader(const BrickSource& source, std::size_t maxReady)
    : BrickLoader(std::vector<const BrickSource*>{&source}, maxReady) {}

BrickLoader::BrickLoader(std::vector<const BrickSource*> sources, std::size_t maxReady)
    : sources_(std::move(sources)), maxReady_(std::max<std::size_t>(maxReady, 1)) {
  // As many as TBB may use (all cores, or what a tbb::global_control allows).
  const int threads = std::max<int>(1, int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
  for (int i = 0; i < threads; ++i) threads_.emplace_back([this] { work(); });
}

BrickLoader::~BrickLoader() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  work_.notify_all();
  for (std::thread& t : threads_) t.join();
}

std::size_t BrickLoader::KeyHash::operator()(const LevelBrick& b) const {
  // 21 bits per axis: brick coordinates of any grid OpenVDB can index (2^31 voxels / 8 per brick).
  const auto u = [](int v) { return uint64_t(uint32_t(v) & 0x1FFFFFu); };
  return std::hash<uint64_t>()((u(b.brick.x) | (u(b.brick.y) << 21) | (u(b.brick.z) << 42)) ^ (uint64_t(b.level) << 59));
}

void BrickLoader::request(const std::vector<glm::ivec3>& bricks) {
  std::vector<LevelBrick> level0;
  level0.reserve(bricks.size());
  for (const glm::ivec3& b : bricks) level0.push_back(LevelBrick{b, 0});
  request(level0);
}

void BrickLoader::request(const std::vector<LevelBrick>& bricks) {
  bool any = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const LevelBrick& b : bricks)
      if (held_.insert(b).second) {
        queued_.push_back(b);
        any = true;
      }
  }
  if (any) work_.notify_all();
}

void BrickLoader::cancelQueued() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const LevelBrick& b : queued_) held_.erase(b);
  queued_.clear();
  done_.notify_all();
}

std::vector<LoadedBrick> BrickLoader::take(std::size_t max, bool wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (wait) {
    // A whole batch, not the first chunk: waking the caller for every chunk caps the stream at the
    // rate one thread wakes up (about 170 k bricks/s on the H200 machine, whatever the cores).
    waitFor_ = std::min(max, maxReady_);
    done_.wait(lock, [&] { return error_ || ready_.size() >= waitFor_ || (queued_.empty() && decoding_ == 0); });
    waitFor_ = 0;
  }
  if (error_) std::rethrow_exception(error_);
  // Threads wait for room only when the ready and decoding blocks reach maxReady_: wake them then.
  const bool wasFull = ready_.size() + decoding_ >= maxReady_;
  std::vector<LoadedBrick> out;
  while (!ready_.empty() && out.size() < max) {
    held_.erase(LevelBrick{ready_.front().brick, ready_.front().level});
    out.push_back(std::move(ready_.front()));
    ready_.pop_front();
  }
  if (!out.empty() && wasFull) work_.notify_all();  // room in ready_ again
  return out;
}

std::size_t BrickLoader::pending() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return queued_.size() + decoding_ + ready_.size();
}

uint64_t BrickLoader::loadedCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return loaded_;
}

void BrickLoader::recycle(std::vector<LoadedBrick>&& taken) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::size_t keep = maxReady_ + threads_.size() * kChunk;  // what can be in use at once
  for (LoadedBrick& b : taken)
    if (spare_.size() < keep && !b.halo.empty()) spare_.push_back(std::move(b.halo));
  taken.clear();
}

void BrickLoader::work() {
  std::vector<LoadedBrick> chunk;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      work_.wait(lock, [&] { return stop_ || (!error_ && !queued_.empty() && ready_.size() + decoding_ < maxReady_); });
      if (stop_) return;
      // Small requests are spread over the threads; large ones go kChunk at a time.
      const std::size_t share = std::max<std::size_t>(1, queued_.size() / threads_.size());
      const std::size_t n = std::min({kChunk, share, maxReady_ - ready_.size() - decoding_});
      chunk.resize(n);
      for (LoadedBrick& b : chunk) {
        b.brick = queued_.front().brick;
        b.level = queued_.front().level;
        queued_.pop_front();
        if (!spare_.empty()) {
          b.halo = std::move(spare_.back());
          spare_.pop_back();
        }
      }
      decoding_ += n;
    }
    decodeChunk(chunk);
  }
}

void BrickLoader::decodeChunk(std::vector<LoadedBrick>& chunk) {
  std::exception_ptr error;
  try {
    if (sources_.size() == 1) {
      sources_[0]->decode(chunk);
    } else {  // a pyramid: each level's bricks through its own source, the chunk's order kept
      for (std::size_t level = 0; level < sources_.size(); ++level) {
        std::vector<LoadedBrick> part;
        for (LoadedBrick& b : chunk)
          if (std::size_t(b.level) == level) part.push_back(std::move(b));
        if (part.empty()) continue;
        sources_[level]->decode(part);
        std::size_t next = 0;
        for (LoadedBrick& b : chunk)
          if (std::size_t(b.level) == level) b = std::move(part[next++]);
      }
    }
  } catch (...) {
    error = std::current_exception();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    decoding_ -= chunk.size();
    if (error) {
      if (!error_) error_ = error;
      for (const LoadedBrick& b : chunk) held_.erase(LevelBrick{b.brick, b.level});
    } else {
      for (LoadedBrick& b : chunk) ready_.push_back(std::move(b));
      loaded_ += chunk.size();
    }
    chunk.clear();
    if (!error && ready_.size() < waitFor_ && !(queued_.empty() && decoding_ == 0)) return;  // the taker waits on
  }
  done_.notify_all();
}

}  // namespace fcc::render
