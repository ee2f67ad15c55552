#include "ByteSource.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <limits>

#include "sparse/Error.h"

namespace fcc::io {
namespace {

// zlib's own input buffer; larger than its 8 KiB default so inflating a big volume makes fewer syscalls.
constexpr unsigned kGzipBufferBytes = 256 * 1024;
constexpr size_t kScratchBytes = 64 * 1024;

[[noreturn]] void failErrno(const std::string& path, const char* what, int error) {
  throw InputError(path + ": " + what + ": " + std::strerror(error));
}

}  // namespace

ByteSource::ByteSource(std::string path, uint64_t offset, Compression compression) : path_(std::move(path)) {
  const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) failErrno(path_, "cannot open", errno);
  struct stat info {};
  if (::fstat(fd, &info) != 0 || S_ISDIR(info.st_mode)) {
    const int error = S_ISDIR(info.st_mode) ? EISDIR : errno;
    ::close(fd);
    failErrno(path_, "cannot open", error);
  }
  if (offset > uint64_t(std::numeric_limits<off_t>::max()) || ::lseek(fd, off_t(offset), SEEK_SET) < 0) {
    const int error = errno;
    ::close(fd);
    failErrno(path_, "cannot seek to the data", error);
  }

  // Peek at the magic through the descriptor, then seek back: both the plain and the gzip reader start at
  // `offset`.
  bool useGzip = compression == Compression::Gzip;
  if (compression != Compression::Plain) {
    unsigned char magic[3] = {0, 0, 0};
    const ssize_t got = ::pread(fd, magic, sizeof magic, off_t(offset));
    const bool hasMagic = got == 3 && magic[0] == 0x1f && magic[1] == 0x8b && magic[2] == 0x08;
    if (compression == Compression::Gzip && !hasMagic) {
      ::close(fd);
      throw InputError(path_ + ": expected gzip data at byte " + std::to_string(offset) +
                       " but it does not start with the gzip magic 1f 8b 08");
    }
    useGzip = hasMagic;
  }

  if (useGzip) {
    gz_ = ::gzdopen(fd, "rb");
    if (gz_ == nullptr) {
      ::close(fd);
      throw InputError(path_ + ": cannot start inflating gzip data: out of memory");
    }
    ::gzbuffer(gz_, kGzipBufferBytes);
  } else {
    plain_ = ::fdopen(fd, "rb");
    if (plain_ == nullptr) {
      const int error = errno;
      ::close(fd);
      failErrno(path_, "cannot open", error);
    }
    if (S_ISREG(info.st_mode)) knownSize_ = uint64_t(info.st_size) > offset ? uint64_t(info.st_size) - offset : 0;
  }
}

ByteSource::~ByteSource() {
  if (gz_ != nullptr) ::gzclose(gz_);
  if (plain_ != nullptr) std::fclose(plain_);
}

void ByteSource::failGzip() const {
  int code = Z_OK;
  const char* message = ::gzerror(gz_, &code);
  if (code == Z_ERRNO) failErrno(path_, "read error", errno);
  if (code == Z_BUF_ERROR)
    throw InputError(path_ + ": truncated gzip data: the stream ends after " + std::to_string(position_) +
                     " decompressed bytes, before its end marker");
  // gzerror prefixes the stream's name, which for gzdopen is "<fd:N>": the path is named already.
  std::string detail = message != nullptr ? message : "unknown zlib error";
  if (detail.rfind("<fd:", 0) == 0 && detail.find(": ") != std::string::npos) detail.erase(0, detail.find(": ") + 2);
  throw InputError(path_ + ": corrupt gzip data: " + detail);
}

size_t ByteSource::read(void* dst, size_t n) {
  auto* out = static_cast<unsigned char*>(dst);
  size_t total = 0;
  if (plain_ != nullptr) {
    total = std::fread(out, 1, n, plain_);
    if (total < n && std::ferror(plain_)) failErrno(path_, "read error", errno);
  } else {
    // gzread takes an unsigned length and returns an int: feed it pieces below INT_MAX.
    while (total < n) {
      const unsigned piece = unsigned(std::min<size_t>(n - total, size_t(1) << 30));
      const int got = ::gzread(gz_, out + total, piece);
      if (got < 0) failGzip();
      total += size_t(got);
      if (unsigned(got) < piece) {
        // A short read is the end of the data only if zlib saw a complete stream; it reports truncation
        // (Z_BUF_ERROR) and corruption only through gzerror.
        int code = Z_OK;
        ::gzerror(gz_, &code);
        if (code != Z_OK) {
          position_ += total;
          failGzip();
        }
        break;
      }
    }
  }
  position_ += total;
  return total;
}

uint64_t ByteSource::skip(uint64_t n) {
  unsigned char scratch[kScratchBytes];
  uint64_t skipped = 0;
  while (skipped < n) {
    const size_t want = size_t(std::min<uint64_t>(n - skipped, sizeof scratch));
    const size_t got = read(scratch, want);
    skipped += got;
    if (got < want) break;
  }
  return skipped;
}

uint64_t ByteSource::drain() {
  unsigned char scratch[kScratchBytes];
  uint64_t drained = 0;
  for (;;) {
    const size_t got = read(scratch, sizeof scratch);
    drained += got;
    if (got < sizeof scratch) return drained;
  }
}

bool ByteSource::readLine(std::string& line, size_t maxLength) {
  line.clear();
  const uint64_t start = position_;
  char c = 0;
  bool any = false;
  while (read(&c, 1) == 1) {
    any = true;
    if (c == '\n') break;
    if (line.size() == maxLength)
      throw InputError(path_ + ": text line at byte " + std::to_string(start) + " is longer than " +
                       std::to_string(maxLength) + " bytes; this is not a text header");
    line += c;
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return any;
}

}  // namespace fcc::io
