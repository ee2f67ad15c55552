// The coarser levels of an FCC file's level-of-detail pyramid (docs/FORMAT.md, "The pyramid"), opened
// for the raycaster: level k's grid "<level 0's name>.lod<k>" as an io::BrickStore and an FccBrickSource
// (RenderOptions::coarserLevels). A file without a pyramid has none.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "FccBrickSource.h"
#include "io/BrickStore.h"

namespace fcc::render {

class PyramidLevels {
 public:
  // Levels 1, 2, ... of level0's file, as many as the file holds (at most kMaxLodLevels - 1 are kept).
  // Each coarser level gets a host cache of its own, out of the total `hostCacheBytes` (--host-cache):
  // level k hostCacheBytes / 8^k, its share of the data (a level has about an eighth of the bricks of
  // the one below), all of them together under a seventh; level 0 keeps the rest (hostCacheBytes()
  // says how much the levels took). InputError (one line) for a level whose transform is not level
  // 0's scaled by 2^k.
  PyramidLevels(const io::BrickStore& level0, std::size_t hostCacheBytes);
  ~PyramidLevels();

  std::size_t size() const { return sources_.size(); }  // coarser levels (0: no pyramid)
  std::vector<const BrickSource*> sources() const;      // level 1 first
  const io::BrickStore& store(std::size_t i) const { return *stores_[i]; }  // level i + 1's
  std::size_t hostCacheBytes() const { return hostCacheBytes_; }  // the coarser levels' budgets together
  std::size_t builtForHostBytes() const { return builtFor_; }      // the total they were shared out of

 private:
  std::vector<std::unique_ptr<io::BrickStore>> stores_;
  std::vector<std::unique_ptr<FccBrickSource>> sources_;
  std::size_t hostCacheBytes_ = 0, builtFor_ = 0;
};

}  // namespace fcc::render
