// Pass 1's leaves, kept as the output file will hold them, so that pass 2 of the streamed build
// (StreamedFccTree::writeBuffers) copies their bytes instead of building every leaf a second time
// (decoding its source, sampling, the prefilter) and compressing it: on a large level set pass 2 was
// a fifth of the conversion, nearly all of it that rebuild.
//
// Each leaf is encoded with LeafNode::writeBuffers into a stream carrying the compression flags and
// background the file's stream will carry (what that call reads of its stream), and its bytes go to an
// unnamed scratch file in TMPDIR (ScratchFile.h); memory holds only the index (24 bytes a leaf). Pass 2
// uses a kept leaf only if its stream's flags, background and half setting are those it was encoded
// with, and its mask (the first bytes written) is the topology's; any other leaf is rebuilt, as before.
// The scratch takes at most half the disk's free space (when made) or `maxBytes`: beyond, leaves are
// simply not kept. So a full disk costs time, never the conversion.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "FccGrid.h"
#include "ScratchFile.h"

namespace fcc {

// The bytes LeafNode::writeBuffers writes for `leaf` to a stream with these compression flags and
// background (io::setDataCompression, io::setGridBackgroundValuePtr), as float or half.
std::string encodeLeaf(const FccTree::LeafNodeType& leaf, uint32_t compression, const void* background, bool half);

class EncodedLeafFile {
 public:
  using Leaf = FccTree::LeafNodeType;

  // The settings the leaves are encoded with; `maxBytes` caps the scratch (0: half the free space).
  EncodedLeafFile(uint32_t compression, const openvdb::Vec4f& background, bool half, uint64_t maxBytes = 0);

  // Encodes and keeps `leaf` (not once the cap is reached, or if the scratch cannot be written).
  // Thread-safe; not after finish().
  void add(const Leaf& leaf);

  // Sorts the index; after the last add() and before any read().
  void finish();

  // Whether leaves kept here may be written to a stream with these settings.
  bool suits(uint32_t compression, const void* background, bool half) const;

  // The bytes of the leaf at `origin` into `bytes`; false if it was not kept. Thread-safe.
  bool read(const openvdb::Coord& origin, std::string& bytes) const;

 private:
  struct Entry {
    openvdb::Coord origin;
    uint32_t size = 0;
    uint64_t offset = 0;
  };
  uint32_t compression_;
  openvdb::Vec4f background_;
  bool half_;
  ScratchFile file_;
  uint64_t maxBytes_;
  std::atomic<uint64_t> next_{0};      // the next leaf's offset in the scratch
  std::atomic<bool> stopped_{false};   // the cap was reached or a write failed: keep no more
  tbb::enumerable_thread_specific<std::vector<Entry>> added_;
  std::vector<Entry> index_;           // sorted by origin, after finish()
};

}  // namespace fcc
