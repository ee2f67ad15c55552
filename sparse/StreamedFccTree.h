// An FCC tree that holds only its topology and builds its leaves' values while it is written: the
// second pass of the streamed build (StreamedBuild.h), which copies the leaves pass 1 kept encoded
// (EncodedLeafFile.h) and rebuilds only the others. Its leaves have no value buffers (OpenVDB's
// PartialCreate leaves, ~100 bytes each instead of 8 KiB); tiles and masks are as the in-memory
// builder makes them.
//
// Writing a grid, OpenVDB's Archive calls Grid::writeTopology (masks and tiles: no leaf values), then
// Grid::writeBuffers -> TreeBase::writeBuffers, virtual, which this tree overrides: it rebuilds the
// leaves (FccBlockBuilder, in parallel batches) in the order the tree's own writeBuffers would visit
// them (root children by key, internal children by mask bit: the order of cbeginLeaf), encodes
// each with LeafNode::writeBuffers into a buffer of its own (in parallel, with the stream's
// compression flags and background) and writes the buffers in that order, so the bytes are those
// of the in-memory grid. Archive's grid
// statistics read masks and memUsage, which this tree reports as if its leaves were loaded. Nothing
// but writing it (io::writeVdbAtomically) may read its values: they are not there.
#pragma once

#include <openvdb/util/NullInterrupter.h>

#include <memory>

#include "EncodedLeafFile.h"
#include "FccBlockBuilder.h"
#include "FccGrid.h"

namespace fcc {

class StreamedFccTree final : public FccTree {
 public:
  using Ptr = openvdb::SharedPtr<StreamedFccTree>;

  // `builder` (and the field it reads) must outlive the tree; `progress`, if not null, reports the
  // writing and can interrupt it.
  StreamedFccTree(const FccBlockBuilder& builder, openvdb::util::NullInterrupter* progress);

  // Leaves pass 1 kept, encoded (finished): writeBuffers copies those it can instead of rebuilding them.
  void useEncodedLeaves(std::shared_ptr<const EncodedLeafFile> kept) { kept_ = std::move(kept); }
  // Of the last writeBuffers: leaves copied from the kept ones, and leaves rebuilt.
  size_t leavesCopied() const { return copied_; }
  size_t leavesRebuilt() const { return rebuilt_; }

  // Rebuilds (or copies, see above) and writes every leaf; throws fcc::Error if a rebuilt leaf's mask is not its
  // topology's (a builder that is not deterministic) or if interrupted.
  void writeBuffers(std::ostream& os, bool saveFloatAsHalf = false) const override;

  // The memory of the tree as built in memory: what Archive records as file_mem_bytes.
  openvdb::Index64 memUsage() const override;

 private:
  FccBlockBuilder builder_;
  openvdb::util::NullInterrupter* progress_;
  std::shared_ptr<const EncodedLeafFile> kept_;
  mutable size_t copied_ = 0, rebuilt_ = 0;
};

}  // namespace fcc
