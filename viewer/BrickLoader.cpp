#include "BrickLoader.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace fcc::render {
namespace {
constexpr std::size_t kBatch = 64;  // bricks decoded in parallel per round (1 MB of blocks)
}  // namespace

BrickLoader::BrickLoader(const io::BrickStore& store, io::BrickCache& cache, std::size_t maxReady)
    : store_(store), cache_(cache), maxReady_(std::max<std::size_t>(maxReady, 1)), thread_([this] { run(); }) {}

BrickLoader::~BrickLoader() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  work_.notify_all();
  thread_.join();
}

uint64_t BrickLoader::key(const glm::ivec3& b) {
  // 21 bits per axis: brick coordinates of any grid OpenVDB can index (2^31 voxels / 8 per brick).
  const auto u = [](int v) { return uint64_t(uint32_t(v) & 0x1FFFFFu); };
  return u(b.x) | (u(b.y) << 21) | (u(b.z) << 42);
}

void BrickLoader::request(const std::vector<glm::ivec3>& bricks) {
  bool any = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const glm::ivec3& b : bricks)
      if (held_.insert(key(b)).second) {
        queued_.push_back(b);
        any = true;
      }
  }
  if (any) work_.notify_one();
}

void BrickLoader::cancelQueued() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const glm::ivec3& b : queued_) held_.erase(key(b));
  queued_.clear();
  done_.notify_all();
}

std::vector<LoadedBrick> BrickLoader::take(std::size_t max, bool wait) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (wait) done_.wait(lock, [&] { return error_ || !ready_.empty() || (queued_.empty() && decoding_ == 0); });
  if (error_) std::rethrow_exception(error_);
  std::vector<LoadedBrick> out;
  while (!ready_.empty() && out.size() < max) {
    held_.erase(key(ready_.front().brick));
    out.push_back(std::move(ready_.front()));
    ready_.pop_front();
  }
  if (!out.empty()) work_.notify_one();  // room in ready_ again
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

void BrickLoader::run() {
  std::vector<LoadedBrick> batch;
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      work_.wait(lock, [&] { return stop_ || (!queued_.empty() && ready_.size() < maxReady_); });
      if (stop_) return;
      const std::size_t n = std::min({kBatch, queued_.size(), maxReady_ - ready_.size()});
      batch.resize(n);
      for (std::size_t i = 0; i < n; ++i) {
        batch[i].brick = queued_.front();
        queued_.pop_front();
      }
      decoding_ = n;
    }
    std::exception_ptr error;
    try {
      tbb::parallel_for(std::size_t(0), batch.size(), [&](std::size_t i) {
        batch[i].halo.resize(std::size_t(io::kHaloBlockVoxels) * 4);
        io::assembleHaloBlock(store_, cache_, batch[i].brick, batch[i].halo.data());
      });
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (error) {
        error_ = error;
        for (const LoadedBrick& b : batch) held_.erase(key(b.brick));
        decoding_ = 0;
        batch.clear();
        done_.notify_all();
        return;
      }
      for (LoadedBrick& b : batch) ready_.push_back(std::move(b));
      loaded_ += batch.size();
      decoding_ = 0;
      batch.clear();
    }
    done_.notify_all();
  }
}

}  // namespace fcc::render
