// Sequential reading of a file's bytes, as stored or inflated from gzip, for the volume readers. Every
// failure (missing file, read error, corrupt or truncated gzip) is an fcc::InputError whose message starts
// with the path, so readers never deal with errno or zlib codes themselves.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

struct gzFile_s;  // zlib's stream type; zlib.h stays out of the readers' includes

namespace fcc::io {

enum class Compression {
  Plain,   // the bytes as stored
  Gzip,    // a gzip stream (one or more members); data without the gzip magic is an error
  Detect,  // gzip when the bytes start with the gzip magic 1f 8b 08, plain otherwise
};

class ByteSource {
 public:
  // Opens `path` at byte `offset` of the file as stored; the compression applies from there on (an attached
  // NRRD's gzip stream begins after its text header). InputError if the file cannot be opened or read.
  ByteSource(std::string path, uint64_t offset, Compression compression);
  ~ByteSource();
  ByteSource(const ByteSource&) = delete;
  ByteSource& operator=(const ByteSource&) = delete;

  const std::string& path() const { return path_; }
  bool gzip() const { return gz_ != nullptr; }
  // Bytes from the start offset to the end of a plain regular file, known before reading anything so that
  // readers can refuse a short file before allocating. Unknown for gzip: its size shows only by inflating.
  std::optional<uint64_t> knownSize() const { return knownSize_; }
  // Bytes delivered so far (decompressed bytes for gzip), counted from the start offset.
  uint64_t position() const { return position_; }

  // Reads up to n bytes into dst; fewer only where the data ends.
  size_t read(void* dst, size_t n);
  // Skips up to n bytes; returns how many there were.
  uint64_t skip(uint64_t n);
  // Reads to the end and returns how many bytes were left. For gzip this also checks the CRC and length
  // trailer, which a reader that stops after the last voxel would otherwise never reach.
  uint64_t drain();
  // Reads one '\n'-terminated line (without the '\n' and a '\r' before it) into `line`; false at the end of
  // the data. InputError if the line is longer than maxLength: a binary file is not a text header.
  bool readLine(std::string& line, size_t maxLength);

 private:
  [[noreturn]] void failGzip() const;

  std::string path_;
  std::FILE* plain_ = nullptr;
  gzFile_s* gz_ = nullptr;
  std::optional<uint64_t> knownSize_;
  uint64_t position_ = 0;
};

}  // namespace fcc::io
