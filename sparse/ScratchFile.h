// An unnamed temporary file in the user's temp folder (TMPDIR), read and written at byte offsets from
// any thread. It is unlinked as soon as it is made: closing it, or the process dying, frees its space,
// and nothing is ever left behind. The streamed conversion's scratch files use it: the dense input
// re-tiled into slabs (io/SlabScratch.h) and pass 1's encoded leaves (EncodedLeafFile.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace fcc {

class ScratchFile {
 public:
  // `what` names the file in messages ("the slab scratch file"); `room` says how much room it needs
  // ("about the input's size"). Throws fcc::Error if TMPDIR names no folder or the file cannot be made.
  ScratchFile(std::string what, std::string room);
  ~ScratchFile();
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  // Claims `bytes` on disk now (where the file system supports it), so that a full disk says so
  // before any work is done: fcc::Error "no room".
  void reserve(uint64_t bytes);

  // The bytes the file system has free for this file's folder (statvfs), or 0 if it cannot say.
  uint64_t freeBytes() const;

  // fcc::Error naming the folder when reading fails or the file is shorter than asked for.
  void read(void* dst, size_t n, uint64_t offset) const;
  // fcc::Error naming the folder (a full disk says so, with `room`).
  void write(const void* src, size_t n, uint64_t offset) const;
  // The same without throwing: false (and the errno in `error`) when writing fails.
  bool tryWrite(const void* src, size_t n, uint64_t offset, int& error) const;

 private:
  std::string what_, room_;
  std::string dir_;
  int fd_ = -1;
};

}  // namespace fcc
