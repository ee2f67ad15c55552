// The Cartesian bricks' value ranges (io/CartesianBrickStore.h: one pass over every leaf of a grid)
// kept in the user cache folder (io/UserCache.h), so a later open of the same grid of the same file
// reads them instead of the leaves. A cache file is trusted only when it is whole and its key — the
// source's canonical path, size and modification time, the grid's name and the ranges' geometry —
// is the one asked for; anything else is no cache (the caller recomputes and rewrites it). Layout:
// docs/FORMAT.md, "The Cartesian bricks' ranges in the user cache". No OpenVDB here.
#pragma once

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace fcc::io {

// One brick's (min, max) over its block's values (CartesianBrickStore::BrickRange).
struct CartesianBrickRange {
  glm::ivec3 brick;
  float lo, hi;
};

// Everything the ranges of grid `gridName` of `sourcePath` depend on, as text (stored in the cache file
// and compared whole on reading; its hash names the file). `geometry` names how ranges are taken (brick
// and block sizes). Empty when the source cannot be stat'ed (then nothing is cached).
std::string cartesianRangeCacheKey(const std::string& sourcePath, const std::string& gridName, const std::string& geometry);

// The cache file for `key` in folder `dir`: DIR/SOURCENAME-HASH.ccranges.
std::string cartesianRangeCachePath(const std::string& dir, const std::string& sourcePath, const std::string& key);

// The ranges cached in `file` under `key`, in the order they were written, each brick inside the
// inclusive box [boxLo, boxHi]; nullopt for a missing file or one that is truncated, garbled, of another
// key or version, or holds a brick outside the box or out of order (never a throw, never a crash).
std::optional<std::vector<CartesianBrickRange>> readCartesianRangeCache(const std::string& file, const std::string& key,
                                                                       const glm::ivec3& boxLo, const glm::ivec3& boxHi);

// Writes `ranges` (bricks in strictly increasing (z, y, x) order) under `key` to `file` atomically
// (io/AtomicOutput.h: a temporary file renamed into place). OutputError when it cannot.
void writeCartesianRangeCache(const std::string& file, const std::string& key, const std::vector<CartesianBrickRange>& ranges);

}  // namespace fcc::io
