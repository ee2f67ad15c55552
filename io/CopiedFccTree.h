// An FCC grid copied out of core from a file into another while it is written: a tree that holds
// nothing itself (not even a copy of the topology: a top-level node of a Vec4f tree is 512 KiB) and
// answers for the source's tree instead: OpenVDB's Archive writes its topology (the source's own
// writeTopology) and statistics from the source, then its writeBuffers reads each leaf from the source
// (BrickStore: validated, pread) and writes it, in batches in the tree's order. `fccvdb pyramid`
// rewrites a file with level 0 and its levels this way without holding any grid: the values written
// are the values read (half floats stay the same halves), so the copy renders exactly as the original.
// Nothing but writing it (io::writeVdbAtomically) may use it: it has no nodes.
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
  void writeTopology(std::ostream& os, bool saveFloatAsHalf = false) const override;
  // What Archive records (file_bbox_*, file_voxel_count, file_mem_bytes as if loaded), from the source.
  openvdb::Index64 memUsage() const override;
  bool evalActiveVoxelBoundingBox(openvdb::CoordBBox& bbox) const override;
  bool evalActiveVoxelDim(openvdb::Coord& dim) const override;
  bool evalLeafBoundingBox(openvdb::CoordBBox& bbox) const override;
  bool evalLeafDim(openvdb::Coord& dim) const override;
  openvdb::Index32 leafCount() const override;
  openvdb::Index32 nonLeafCount() const override;
  openvdb::Index64 activeVoxelCount() const override;
  openvdb::Index64 inactiveVoxelCount() const override;
  openvdb::Index64 activeLeafVoxelCount() const override;
  openvdb::Index64 inactiveLeafVoxelCount() const override;
  openvdb::Index64 activeTileCount() const override;

 private:
  const BrickStore& source_;
  openvdb::util::NullInterrupter* progress_;
};

// The source's FCC grid (metadata, transform, name, half flag) over a CopiedFccTree.
FccGrid::Ptr copiedFccGrid(const BrickStore& source, openvdb::util::NullInterrupter* progress);

}  // namespace fcc::io
