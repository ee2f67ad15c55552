// The renderer's loader thread: decodes requested bricks into pool-slot blocks (BrickSource::decode:
// for FCC data through the host cache) away from the frame loop, so neither the viewer's UI nor a frame's GPU work waits on
// the file. The frame loop queues bricks with request() and collects finished ones with take();
// bricks already queued, being decoded or waiting to be taken are not queued twice. At most
// `maxReady` finished blocks wait to be taken (the thread pauses meanwhile), which bounds the host
// memory the loader adds to the host cache's budget.
//
// Decoding is a stream, not rounds: one loader thread per core (TBB's concurrency) takes small chunks
// of the queue, and each chunk's blocks are ready as soon as that chunk is done. Blocks given back
// with recycle() are reused, so a steady stream allocates (and page-faults) nothing.
#pragma once

#include <glm/glm.hpp>

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <unordered_set>
#include <vector>

#include "BrickSource.h"

namespace fcc::render {

class BrickLoader {
 public:
  BrickLoader(const BrickSource& source, std::size_t maxReady);
  // A pyramid: sources[k] decodes level k's bricks (all give the same SlotBlock).
  BrickLoader(std::vector<const BrickSource*> sources, std::size_t maxReady);
  ~BrickLoader();  // waits for the chunks in progress; queued requests are dropped
  BrickLoader(const BrickLoader&) = delete;
  BrickLoader& operator=(const BrickLoader&) = delete;

  // Queues bricks, in order, skipping ones the loader already holds in any state.
  void request(const std::vector<glm::ivec3>& bricks);  // level 0's
  void request(const std::vector<LevelBrick>& bricks);
  // Drops the queued requests not yet started (the view changed; what is decoding still arrives).
  void cancelQueued();
  // Up to `max` finished bricks, in the order they finished. With `wait`, blocks until `max` (or
  // maxReady) are finished or nothing is left to decode. Rethrows what decoding threw (a file that fails to read).
  std::vector<LoadedBrick> take(std::size_t max, bool wait);
  // Gives taken blocks' memory back for reuse (the bricks themselves are forgotten).
  void recycle(std::vector<LoadedBrick>&& taken);
  // Bricks queued, decoding or waiting to be taken.
  std::size_t pending() const;
  uint64_t loadedCount() const;  // bricks decoded into blocks since construction

 private:
  void work();  // one loader thread
  void decodeChunk(std::vector<LoadedBrick>& chunk);
  struct KeyHash {
    std::size_t operator()(const LevelBrick& b) const;
  };

  std::vector<const BrickSource*> sources_;
  const std::size_t maxReady_;
  mutable std::mutex mutex_;
  std::condition_variable work_;   // requests queued, room in ready_, or stopping
  std::condition_variable done_;   // a chunk finished
  std::deque<LevelBrick> queued_;
  std::size_t decoding_ = 0;  // bricks in chunks being decoded
  std::size_t waitFor_ = 0;   // ready bricks a blocked take() waits for (0: none waits)
  std::deque<LoadedBrick> ready_;
  std::vector<std::vector<float>> spare_;  // recycled halo blocks
  std::unordered_set<LevelBrick, KeyHash> held_;  // queued, decoding and ready bricks
  uint64_t loaded_ = 0;
  std::exception_ptr error_;  // the first decoding failure, for take() to rethrow
  bool stop_ = false;
  std::vector<std::thread> threads_;  // last: they start once the members above exist
};

}  // namespace fcc::render
