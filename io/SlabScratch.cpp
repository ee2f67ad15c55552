#include "SlabScratch.h"

#include <tbb/parallel_for.h>

#include <algorithm>

#include "SampleDecoding.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

// Slices read from the source at once: runs into each slab of a few KiB at least, and little memory.
constexpr uint64_t kSliceGroupBytes = uint64_t(16) << 20;
// Values one task of transformAlongZ holds (whole z-lines of a few rows of one slab).
constexpr uint64_t kZLinesBytes = uint64_t(8) << 20;

}  // namespace

SlabScratch::SlabScratch(DenseSource& source, const SliceTransform& inSlices, openvdb::util::NullInterrupter* progress)
    : dims_(source.geometry().dims) {
  // Values a transform changes are floats; others stay as stored, a quarter of float's size for u8.
  const std::optional<DenseSource::Stored> stored = inSlices ? std::nullopt : source.stored();
  if (stored) {
    type_ = stored->type;
    scale_ = stored->scale;
  }
  elementBytes_ = scalarTypeSize(type_);
  for (int x = 0; x < dims_.x; x += kSlabWidth) {
    Slab slab;
    slab.x0 = std::max(0, x - kHalo);
    slab.width = std::min(dims_.x - 1, x + kSlabWidth - 1 + kHalo) - slab.x0 + 1;
    slab.offset = bytes_;
    bytes_ += uint64_t(slab.width) * uint64_t(dims_.y) * uint64_t(dims_.z) * elementBytes_;
    slabs_.push_back(slab);
  }
  file_ = std::make_unique<ScratchFile>("the slab scratch file", "18/16 of the input's voxels");
  file_->reserve(bytes_);  // a full disk says so before the source is read

  const uint64_t sliceVoxels = uint64_t(dims_.x) * uint64_t(dims_.y);
  const int group = int(std::clamp<uint64_t>(kSliceGroupBytes / (sliceVoxels * elementBytes_), 1, uint64_t(dims_.z)));
  // Bytes from operator new: aligned for floats.
  std::vector<uint8_t> slices(size_t(sliceVoxels) * size_t(group) * elementBytes_);
  if (progress) progress->start("reading the input into slabs");
  for (int z0 = 0; z0 < dims_.z; z0 += group) {
    const int count = std::min(group, dims_.z - z0);
    const uint64_t first = uint64_t(z0) * sliceVoxels, n = uint64_t(count) * sliceVoxels;
    if (stored) {
      source.readStored(first, n, slices.data());
    } else {
      source.read(first, n, reinterpret_cast<float*>(slices.data()));
      if (inSlices) inSlices(reinterpret_cast<float*>(slices.data()), count);
    }
    // Slab s's rows of these slices are one run of its file region.
    tbb::parallel_for(size_t(0), slabs_.size(), [&](size_t s) {
      const Slab& slab = slabs_[s];
      const size_t rowBytes = size_t(slab.width) * elementBytes_;
      std::vector<uint8_t> run(size_t(count) * size_t(dims_.y) * rowBytes);
      uint8_t* dst = run.data();
      for (int z = 0; z < count; ++z)
        for (int y = 0; y < dims_.y; ++y)
          dst = std::copy_n(slices.data() + ((size_t(z) * dims_.y + y) * dims_.x + slab.x0) * elementBytes_, rowBytes, dst);
      file_->write(run.data(), run.size(), runOffset(slab, 0, z0));
    });
    if (progress && progress->wasInterrupted(int(100.0 * double(z0 + count) / double(dims_.z))))
      throw Error("interrupted");
  }
  source.finish();
  if (progress) progress->end();
}

SlabScratch::~SlabScratch() = default;

void SlabScratch::transformAlongZ(const std::function<void(float*, int, ptrdiff_t, int, ptrdiff_t)>& alongZ) {
  if (type_ != ScalarType::F32 || scale_) throw Error("internal: a slab scratch of stored samples transformed");
  tbb::parallel_for(size_t(0), slabs_.size(), [&](size_t s) {
    const Slab& slab = slabs_[s];
    const uint64_t lineBytes = uint64_t(dims_.z) * uint64_t(slab.width) * sizeof(float);
    const int rows = int(std::clamp<uint64_t>(kZLinesBytes / lineBytes, 1, uint64_t(dims_.y)));
    std::vector<float> block(size_t(rows) * size_t(slab.width) * size_t(dims_.z));
    for (int y0 = 0; y0 < dims_.y; y0 += rows) {
      // The rows [y0, y0 + n) of every z: one run each, the lines side by side.
      const int n = std::min(rows, dims_.y - y0);
      const size_t run = size_t(n) * size_t(slab.width);
      for (int z = 0; z < dims_.z; ++z) file_->read(block.data() + z * run, run * sizeof(float), runOffset(slab, y0, z));
      alongZ(block.data(), dims_.z, ptrdiff_t(run), int(run), 1);
      for (int z = 0; z < dims_.z; ++z) file_->write(block.data() + z * run, run * sizeof(float), runOffset(slab, y0, z));
    }
  });
}

void SlabScratch::read(const SiteBox& voxels, float* out) const {
  const glm::ivec3 size = voxels.dim();
  thread_local std::vector<uint8_t> run;
  for (int x = voxels.min.x; x <= voxels.max.x;) {
    // The slab holding x and the most columns after it.
    const Slab& slab = slabs_[std::min(size_t((x + kHalo) / kSlabWidth), slabs_.size() - 1)];
    const int xEnd = std::min(voxels.max.x, slab.x0 + slab.width - 1);
    const size_t columns = size_t(xEnd - x + 1);
    run.resize(size_t(size.y) * size_t(slab.width) * elementBytes_);
    for (int z = voxels.min.z; z <= voxels.max.z; ++z) {
      file_->read(run.data(), run.size(), runOffset(slab, voxels.min.y, z));
      for (int y = 0; y < size.y; ++y) {
        const uint8_t* src = run.data() + (size_t(y) * slab.width + size_t(x - slab.x0)) * elementBytes_;
        float* dst = out + (size_t(z - voxels.min.z) * size.y + y) * size.x + (x - voxels.min.x);
        // As DenseSource::read converts them: the same float, the same scale, the same bits.
        decodeSamples(src, columns, type_, hostIsBigEndian(), dst);
        if (scale_)
          for (size_t i = 0; i < columns; ++i) dst[i] = dst[i] * scale_->first + scale_->second;
      }
    }
    x = xEnd + 1;
  }
}

}  // namespace fcc::io
