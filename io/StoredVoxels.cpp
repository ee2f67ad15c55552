#include "StoredVoxels.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <vector>

#include "SampleDecoding.h"

namespace fcc::io {
namespace {

// Bytes read per step: large enough that the per-call cost vanishes, small enough to stay in cache.
constexpr size_t kChunkBytes = size_t(1) << 20;

class StoredVoxelSource final : public DenseSource {
 public:
  StoredVoxelSource(const DenseVolume& geometry, StoredVoxels stored)
      : stored_(std::move(stored)), sampleBytes_(scalarTypeSize(stored_.type)) {
    geometry_ = geometry;
    geometry_.values.clear();
    if (!stored_.gzip) {
      fd_ = ::open(stored_.path.c_str(), O_RDONLY | O_CLOEXEC);
      if (fd_ < 0) throw InputError(stored_.path + ": cannot open: " + std::strerror(errno));
      struct stat info {};
      if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) {
        ::close(fd_);
        throw InputError(stored_.path + ": not a regular file; uncompressed voxels are read where a slab needs them, "
                                        "so they must be in a file");
      }
    }
  }
  ~StoredVoxelSource() override {
    if (fd_ >= 0) ::close(fd_);
  }

  void read(uint64_t first, uint64_t count, float* out) override {
    readChunks(first, count, [&](const uint8_t* bytes, uint64_t done, uint64_t n) {
      decodeSamples(bytes, size_t(n), stored_.type, stored_.bigEndian, out + done);
      if (stored_.scale)
        for (uint64_t i = done; i < done + n; ++i) out[i] = out[i] * stored_.scale->first + stored_.scale->second;
    });
  }

  std::optional<Stored> stored() const override { return Stored{stored_.type, stored_.scale}; }

  void readStored(uint64_t first, uint64_t count, void* out) override {
    auto* dst = static_cast<uint8_t*>(out);
    const bool swap = stored_.bigEndian != hostIsBigEndian() && sampleBytes_ > 1;
    readChunks(first, count, [&](const uint8_t* bytes, uint64_t done, uint64_t n) {
      uint8_t* at = dst + done * sampleBytes_;
      std::copy_n(bytes, n * sampleBytes_, at);
      if (swap)
        for (uint64_t i = 0; i < n; ++i) std::reverse(at + i * sampleBytes_, at + (i + 1) * sampleBytes_);
    });
  }

  void finish() override {
    if (!stored_.gzip) return;  // a plain file's size was checked when it was opened
    seekStream(voxelCount());
    // Reaches the gzip trailer (CRC and length), which a reader stopping at the last voxel would not.
    const uint64_t extra = stream_->drain();
    if (stored_.exactEnd && extra > 0) throw stored_.sizeError(stream_->position());
  }

 private:
  // Reads the voxels [first, first + count) a chunk at a time: use(bytes, voxels done before, voxels).
  template <class Use>
  void readChunks(uint64_t first, uint64_t count, Use&& use) {
    std::vector<uint8_t> chunk(std::min<uint64_t>(kChunkBytes, std::max<uint64_t>(count, 1) * sampleBytes_));
    const uint64_t perChunk = chunk.size() / sampleBytes_;
    if (stored_.gzip) seekStream(first);
    for (uint64_t done = 0; done < count;) {
      const uint64_t n = std::min(perChunk, count - done);
      const size_t bytes = size_t(n * sampleBytes_);
      if (stored_.gzip) {
        if (stream_->read(chunk.data(), bytes) < bytes) throw stored_.sizeError(stream_->position());
        nextVoxel_ += n;
      } else {
        readPlain(stored_.skipBytes + (first + done) * sampleBytes_, chunk.data(), bytes);
      }
      use(chunk.data(), done, n);
      done += n;
    }
  }

  // pread of a plain file whose size was checked: falling short means it changed since.
  void readPlain(uint64_t offsetFromData, uint8_t* dst, size_t bytes) const {
    size_t got = 0;
    while (got < bytes) {
      const ssize_t n = ::pread(fd_, dst + got, bytes - got, off_t(stored_.fileOffset + offsetFromData + got));
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) throw InputError(stored_.path + ": read error: " + std::strerror(errno));
      if (n == 0) throw stored_.sizeError(offsetFromData + got);
      got += size_t(n);
    }
  }

  // Puts the gzip stream at voxel `voxel`: forward by decompressing, back by starting again.
  void seekStream(uint64_t voxel) {
    if (!stream_ || voxel < nextVoxel_) {
      stream_ = std::make_unique<ByteSource>(stored_.path, stored_.fileOffset, Compression::Gzip);
      if (stream_->skip(stored_.skipBytes) < stored_.skipBytes) throw stored_.sizeError(stream_->position());
      nextVoxel_ = 0;
    }
    const uint64_t skip = (voxel - nextVoxel_) * sampleBytes_;
    if (stream_->skip(skip) < skip) throw stored_.sizeError(stream_->position());
    nextVoxel_ = voxel;
  }

  StoredVoxels stored_;
  size_t sampleBytes_;
  int fd_ = -1;
  std::unique_ptr<ByteSource> stream_;  // gzip: where the last read ended
  uint64_t nextVoxel_ = 0;
};

}  // namespace

std::unique_ptr<DenseSource> openStoredVoxels(const DenseVolume& geometry, StoredVoxels stored) {
  return std::make_unique<StoredVoxelSource>(geometry, std::move(stored));
}

}  // namespace fcc::io
