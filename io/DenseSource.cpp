#include "DenseSource.h"

#include <algorithm>

#include "sparse/Error.h"

namespace fcc::io {
namespace {

// Voxels read per step: the values grow by at most this much beyond what the file turned out to hold.
constexpr uint64_t kStepVoxels = uint64_t(1) << 20;

}  // namespace

void DenseSource::readStored(uint64_t, uint64_t, void*) { throw Error("internal: this source has no stored samples"); }

DenseVolume readAllVoxels(DenseSource& source) {
  DenseVolume volume = source.geometry();
  const uint64_t total = source.voxelCount();
  for (uint64_t done = 0; done < total;) {
    const uint64_t n = std::min(kStepVoxels, total - done);
    if (volume.values.capacity() < done + n)  // double, but never past the voxel count
      volume.values.reserve(size_t(std::min(total, std::max(done + n, 2 * uint64_t(volume.values.capacity())))));
    volume.values.resize(size_t(done + n));
    source.read(done, n, volume.values.data() + done);
    done += n;
  }
  source.finish();
  return volume;
}

}  // namespace fcc::io
