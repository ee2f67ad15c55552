// The user's cache folder, shared by what fccvdb keeps between runs: Cartesian inputs converted to FCC
// (io/ConversionCache.h, `NAME-KEY.vdb`) and the Cartesian bricks' value ranges
// (io/CartesianRangeCache.h, `NAME-KEY.ccranges`). One bound in bytes for both, least recently used
// out: a file's modification time is when it was last used.
#pragma once

#include <cstdint>
#include <string>

namespace fcc::io {

// The cache folder: $FCCVDB_CACHE_DIR, else $XDG_CACHE_HOME/fccvdb, else $HOME/.cache/fccvdb.
std::string conversionCacheDir();
// Its bound in bytes: $FCCVDB_CACHE_MAX_MIB (MiB), default 20 GiB.
uint64_t conversionCacheMaxBytes();

// Marks a cache file as used now (its modification time, which eviction orders by).
void touchCacheFile(const std::string& path);
// Removes the least recently used cache files of `dir` (conversions and range files; nothing else
// there) until it holds at most conversionCacheMaxBytes(); never `keep`.
void boundCacheFolder(const std::string& dir, const std::string& keep);

}  // namespace fcc::io
