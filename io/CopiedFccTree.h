// An FCC grid copied out of core from a file into another while it is written: a tree of the source's
// topology alone (its leaves have no value buffers) whose writeBuffers reads each leaf from the source
// (BrickStore: validated, pread) and writes it, in batches in the tree's order. `fccvdb pyramid`
// rewrites a file with level 0 and its levels this way without holding any grid: the values written
// are the values read (half floats stay the same halves), so the copy renders exactly as the original.
#pragma once

#include <openvdb/util/NullInterrupter.h>

#include "BrickStore.h"
#include "sparse/FccGrid.h"

namespace fcc::io {

class CopiedFccTree final : public FccTree {
 public:
  // `source` (which must outlive the tree) gives the topology and the values; `progress`, if not
  // null, reports the writing and can interrupt it.
  CopiedFccTree(const BrickStore& source, openvdb::util::NullInterrupter* progress);

  // Reads and writes every leaf; InputError (the source's damage line) if a leaf is damaged.
  void writeBuffers(std::ostream& os, bool saveFloatAsHalf = false) const override;
  openvdb::Index64 memUsage() const override;  // as if loaded: what Archive records as file_mem_bytes

 private:
  const BrickStore& source_;
  openvdb::util::NullInterrupter* progress_;
};

// The source's FCC grid (metadata, transform, name, half flag) over a CopiedFccTree.
FccGrid::Ptr copiedFccGrid(const BrickStore& source, openvdb::util::NullInterrupter* progress);

}  // namespace fcc::io
