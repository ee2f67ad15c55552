// A dense volume re-tiled into x-slabs in an unnamed scratch file, so the streamed build can read it
// slab by slab (its passes walk x: pass 1 one slab after another, pass 2 the tree's order) while the
// file it comes from is stored x fastest, z slowest: a slab of an x-fastest file is a few bytes of
// every row, so reading slabs from it would read each of its pages once per slab.
//
// The source is read once, front to back (the only order gzip allows), a few slices at a time; each
// group of slices goes to the slabs as contiguous runs. Slab s holds voxels x in [16s - 1, 16s + 16]
// (a block's 16 sites and the one-site halo its prefilter reads, so a subsampled block reads one
// slab), stored z slowest, then y, then x: as the source stores them (DenseSource::stored(): 1 to 8
// bytes a voxel, converted to float when read back) or as float (ITK's sources, and values changed
// by a transform). Any box is then read with one pread per slab and z. The file is unlinked at once:
// nothing is left behind, even after a crash. Disk: 18/16 of a voxel's size per voxel, in the user's
// temp dir (TMPDIR).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <openvdb/util/NullInterrupter.h>

#include "DenseSource.h"
#include "sparse/SampleField.h"
#include "sparse/ScratchFile.h"

namespace fcc::io {

class SlabScratch {
 public:
  static constexpr int kSlabWidth = 16;  // voxels along x: the sites of an output block
  static constexpr int kHalo = 1;        // columns a slab repeats of each neighbour

  // Whole z-slices [z0, z0 + count) in memory, x fastest, changed in place before they are stored.
  using SliceTransform = std::function<void(float* slices, int count)>;

  // Reads every voxel of `source` (then its finish()), applying `inSlices` if set (then the slabs
  // hold floats). `progress`, if not null, reports the slices read and can interrupt (fcc::Error).
  explicit SlabScratch(DenseSource& source, const SliceTransform& inSlices = {},
                       openvdb::util::NullInterrupter* progress = nullptr);
  ~SlabScratch();
  SlabScratch(const SlabScratch&) = delete;
  SlabScratch& operator=(const SlabScratch&) = delete;

  const glm::ivec3& dims() const { return dims_; }
  uint64_t bytes() const { return bytes_; }

  // `alongZ(lines, n, stride, count, lineStride)` on every z-line of the volume (n = dims.z values,
  // `stride` apart; `count` lines at once, `lineStride` apart), in place: the B-spline prefilter's
  // last axis, which no group of slices holds whole. Only for slabs of floats (made with a transform).
  void transformAlongZ(const std::function<void(float*, int, ptrdiff_t, int, ptrdiff_t)>& alongZ);

  // The voxels of `voxels` (inside the volume) into `out`, x fastest. Thread-safe.
  void read(const SiteBox& voxels, float* out) const;

 private:
  struct Slab {
    int x0 = 0, width = 0;  // the columns it holds
    uint64_t offset = 0;    // bytes into the file
  };
  uint64_t runOffset(const Slab& slab, int y, int z) const {
    return slab.offset + ((uint64_t(z) * uint64_t(dims_.y) + uint64_t(y)) * uint64_t(slab.width)) * elementBytes_;
  }

  glm::ivec3 dims_{0};
  ScalarType type_ = ScalarType::F32;                  // of the values in the file, in this machine's byte order
  std::optional<std::pair<float, float>> scale_;      // applied when they are read back (DenseSource::Stored)
  size_t elementBytes_ = sizeof(float);
  std::vector<Slab> slabs_;
  uint64_t bytes_ = 0;
  std::unique_ptr<ScratchFile> file_;
};

}  // namespace fcc::io
