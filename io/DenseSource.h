// A Cartesian volume read on demand: its geometry at once, its samples as runs of voxels in file
// order (x fastest, then y, then z) when asked, so a volume larger than memory can be converted
// (io/SlabScratch.h re-tiles it for the x-slabs the FCC output is built in). The readers of
// DenseVolume.h are these sources read whole (readAllVoxels).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "DenseVolume.h"

namespace fcc::io {

class DenseSource {
 public:
  virtual ~DenseSource() = default;

  // dims, spacing, origin, direction; `values` stays empty.
  const DenseVolume& geometry() const { return geometry_; }
  uint64_t voxelCount() const {
    return uint64_t(geometry_.dims.x) * uint64_t(geometry_.dims.y) * uint64_t(geometry_.dims.z);
  }

  // The `count` voxels from voxel `first` on (index i + X (j + Y k)), as float, into `out`.
  // InputError (one line, naming the file) where the data ends early or is corrupt. Reading forward
  // is cheapest: compressed data can only be read forward, and going back restarts it.
  virtual void read(uint64_t first, uint64_t count, float* out) = 0;

  // How the voxels are stored when read() only converts them to float (raw, NRRD, NIfTI-1): their
  // type and the scale read() applies (value * first + second, in float). A slab scratch then keeps
  // them as stored (1 to 8 bytes a voxel, not float's 4) and converts them when it reads them back.
  // Empty for sources that deliver floats (ITK's).
  struct Stored {
    ScalarType type = ScalarType::F32;
    std::optional<std::pair<float, float>> scale;
  };
  virtual std::optional<Stored> stored() const { return std::nullopt; }
  // The `count` voxels from voxel `first` as stored, in this machine's byte order, into `out`
  // (stored()'s type, unscaled). Only where stored() is set.
  virtual void readStored(uint64_t first, uint64_t count, void* out);

  // Once every voxel was read: checks what follows them (a gzip stream's trailer, bytes a raw file
  // must not have), so a damaged file is refused the same whether it was read whole or in slabs.
  virtual void finish() {}

 protected:
  DenseVolume geometry_;
};

// The sources of the formats DenseVolume.h reads, with the same checks: a file whose size is known
// is refused at opening if it is too short (or, for raw, of any other size); gzip data when it ends.
std::unique_ptr<DenseSource> openRaw(const std::string& path, const RawLayout& layout);
std::unique_ptr<DenseSource> openNrrd(const std::string& path);
std::unique_ptr<DenseSource> openNifti(const std::string& path);
// Through ITK (io/ItkReader.cpp): a DICOM series one slice file at a time, a MetaImage by ITK's
// streaming (an IORegion of slices). Compressed MetaImage data cannot be read in part (ITK inflates
// all of it for any region): it is read whole, once, and held.
std::unique_ptr<DenseSource> openDicom(const std::string& path);
std::unique_ptr<DenseSource> openMetaImage(const std::string& path);

// Every voxel of `source` in memory. The values grow as data arrives (never past the voxel count),
// so a header that claims more than its file holds cannot make a large allocation.
DenseVolume readAllVoxels(DenseSource& source);

}  // namespace fcc::io
