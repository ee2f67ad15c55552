// Any input as an FCC .vdb file: `render`, `view` and `bench render` take whatever `convert` takes. An
// FCC .vdb is used as it is; anything else is converted once into the user's cache folder and reused
// while the source (path, size, modification time) and the conversion's flags stay the same. The cache
// is bounded in bytes, least recently used first out (io/UserCache.h). Without the cache (--no-cache),
// the conversion goes to a temporary file removed with this object.
#pragma once

#include <openvdb/util/NullInterrupter.h>

#include <cstdint>
#include <string>

#include "Convert.h"
#include "UserCache.h"  // the folder and its bound, shared with the Cartesian ranges' cache

namespace fcc::io {

// True if `path` is a .vdb holding an FCC grid (from its grid descriptors alone).
bool holdsFccGrid(const std::string& path);

class FccInput {
 public:
  enum class Origin { Direct, CacheHit, Converted, Temporary };

  // `options` are convert's (raw layout, mode, ...); their output and overwrite fields are ignored.
  // `progress` shows the conversion. `say` (if not null) gets the one line telling the user what
  // happens (converting, reusing); it is not called for an FCC input.
  FccInput(const std::string& input, const ConvertOptions& options, bool useCache,
           openvdb::util::NullInterrupter* progress, void (*say)(const std::string&) = nullptr);
  ~FccInput();
  FccInput(const FccInput&) = delete;
  FccInput& operator=(const FccInput&) = delete;

  const std::string& path() const { return path_; }  // the FCC .vdb to open
  Origin origin() const { return origin_; }

 private:
  std::string path_;
  Origin origin_ = Origin::Direct;
};

}  // namespace fcc::io
