// The voxels of a raw, NRRD or NIfTI-1 file as a DenseSource: samples of one ScalarType stored from
// a byte offset on, as stored (read with pread, any run in any order) or in a gzip stream (read
// forward; a run before the last one restarts the stream, which the slab re-tiling never asks for).
#pragma once

#include <functional>
#include <memory>
#include <optional>

#include "ByteSource.h"
#include "DenseSource.h"
#include "sparse/Error.h"

namespace fcc::io {

struct StoredVoxels {
  std::string path;              // the file holding the data
  uint64_t fileOffset = 0;       // where the bytes as stored (or the gzip stream) start
  bool gzip = false;             // the bytes from fileOffset on are a gzip stream
  uint64_t skipBytes = 0;        // bytes (decompressed, for gzip) between fileOffset and the first voxel
  ScalarType type = ScalarType::U8;
  bool bigEndian = false;
  // value * slope + intercept (in float, as NIfTI's scl_slope/scl_inter) when set.
  std::optional<std::pair<float, float>> scale;
  // Bytes after the last voxel are an error (raw: the layout would be wrong); checked by finish().
  bool exactEnd = false;
  // The reader's one-line message for data that ends early: `holds` is the position reached, in
  // bytes from fileOffset (decompressed, for gzip), as the reader counts it.
  std::function<InputError(uint64_t holds)> sizeError;
};

// `geometry`'s dims give the voxel count; the caller has checked a plain file's size already.
std::unique_ptr<DenseSource> openStoredVoxels(const DenseVolume& geometry, StoredVoxels stored);

}  // namespace fcc::io
