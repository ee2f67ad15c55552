#include "ScratchFile.h"

#include <fcntl.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "Error.h"

namespace fcc {
namespace {

std::string tempDir(const std::string& what, const std::string& room) {
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  if (ec) {
    const char* named = std::getenv("TMPDIR");
    throw Error(std::string("TMPDIR=") + (named ? named : "") + ": no folder for " + what + " (" + ec.message() +
                "); set TMPDIR to a writable folder with room for " + room);
  }
  return dir.string();
}

}  // namespace

ScratchFile::ScratchFile(std::string what, std::string room)
    : what_(std::move(what)), room_(std::move(room)), dir_(tempDir(what_, room_)) {
  std::string name = dir_ + "/fccvdb-scratch-XXXXXX";
  fd_ = ::mkstemp(name.data());
  if (fd_ < 0) throw Error(dir_ + ": cannot create " + what_ + ": " + std::strerror(errno) + "; set TMPDIR to a writable folder");
  ::unlink(name.c_str());  // anonymous from now on
}

ScratchFile::~ScratchFile() {
  if (fd_ >= 0) ::close(fd_);
}

void ScratchFile::reserve(uint64_t bytes) {
  const int claimed = ::posix_fallocate(fd_, 0, off_t(bytes));
  if (claimed == ENOSPC || claimed == EFBIG)
    throw Error(dir_ + ": no room for " + what_ + " of " + std::to_string(bytes) + " bytes (" + room_ +
                "); set TMPDIR to a folder with room");
}

uint64_t ScratchFile::freeBytes() const {
  struct statvfs fs {};
  if (::fstatvfs(fd_, &fs) != 0) return 0;
  return uint64_t(fs.f_bavail) * uint64_t(fs.f_frsize);
}

void ScratchFile::read(void* dst, size_t n, uint64_t offset) const {
  auto* out = static_cast<char*>(dst);
  for (size_t got = 0; got < n;) {
    const ssize_t r = ::pread(fd_, out + got, n - got, off_t(offset + got));
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0)
      throw Error(dir_ + ": cannot read back " + what_ + ": " + (r < 0 ? std::strerror(errno) : "it is shorter than written"));
    got += size_t(r);
  }
}

bool ScratchFile::tryWrite(const void* src, size_t n, uint64_t offset, int& error) const {
  const auto* in = static_cast<const char*>(src);
  for (size_t put = 0; put < n;) {
    const ssize_t w = ::pwrite(fd_, in + put, n - put, off_t(offset + put));
    if (w < 0 && errno == EINTR) continue;
    if (w < 0) {
      error = errno;
      return false;
    }
    put += size_t(w);
  }
  return true;
}

void ScratchFile::write(const void* src, size_t n, uint64_t offset) const {
  int error = 0;
  if (!tryWrite(src, n, offset, error))
    throw Error(dir_ + ": cannot write " + what_ + " (" + room_ + "): " + std::strerror(error) +
                "; set TMPDIR to a folder with room");
}

}  // namespace fcc
