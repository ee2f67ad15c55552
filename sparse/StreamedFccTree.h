// An FCC tree that holds only its topology and builds its leaves' values while it is written: the
// second pass of the streamed build (StreamedBuild.h). Its leaves have no value buffers (OpenVDB's
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

#include "FccBlockBuilder.h"
#include "FccGrid.h"

namespace fcc {

class StreamedFccTree final : public FccTree {
 public:
  using Ptr = openvdb::SharedPtr<StreamedFccTree>;

  // `builder` (and the field it reads) must outlive the tree; `progress`, if not null, reports the
  // writing and can interrupt it.
  StreamedFccTree(const FccBlockBuilder& builder, openvdb::util::NullInterrupter* progress);

  // Rebuilds and writes every leaf; throws fcc::Error if a rebuilt leaf's mask is not its
  // topology's (a builder that is not deterministic) or if interrupted.
  void writeBuffers(std::ostream& os, bool saveFloatAsHalf = false) const override;

  // The memory of the tree as built in memory: what Archive records as file_mem_bytes.
  openvdb::Index64 memUsage() const override;

 private:
  FccBlockBuilder builder_;
  openvdb::util::NullInterrupter* progress_;
};

}  // namespace fcc
