// Reading and writing .vdb files. Debian's OpenVDB 10.0.1 can crash or hang on corrupt files, so every
// file is first read once in a process of its own with a time limit (guardVdbFile, guardLeafRead)
// before this process trusts it.
#pragma once

#include <openvdb/openvdb.h>

#include <string>
#include <vector>

#include "sparse/BrickBounds.h"
#include "sparse/FccGrid.h"

namespace fcc::io {

// How much of a file the guard reads: all of it, or (for out-of-core use, where leaf buffers are read
// later on demand) the metadata, the trees' topology and the buffers of every grid but the FCC grids.
enum class GuardDepth { Everything, Topology };

// The guard: OpenVDB's parsing of `path` runs first in a fresh process, the fccvdb-guard executable
// (io/guard_main.cpp), spawned with a time limit; its crash, hang or failure becomes an InputError
// naming the file, and only then does this process parse the file itself. Spawned, not forked: a fork
// of this threaded process copies every lock another thread holds (TBB's, the allocator's), and a
// child that needs one waits forever (docs/RELIABILITY.md, bug 5).
//
// fccvdb-guard is looked for in $FCCVDB_GUARD if set, else beside this process's executable, else at
// the path the build put it; not found is an Error naming where it looked (the file is not at fault).

// Throws InputError naming the file if it is missing, not a .vdb, or if OpenVDB fails, crashes or
// takes longer than the time limit while reading it (to `depth`) in the guard.
void guardVdbFile(const std::string& path, GuardDepth depth = GuardDepth::Everything);

// The same guard around what an out-of-core open parses through OpenVDB: VdbLeafReader's topology read
// of grid `gridName` (empty: the first grid of one of `treeTypes`) and, if `boundsName` is not empty,
// that grid read whole (BrickStore's bounds grid).
void guardLeafRead(const std::string& path, const std::string& gridName, const std::vector<std::string>& treeTypes,
                   const std::string& boundsName = {});

struct GridInfo {
  std::string name;
  std::string type;
  bool fcc = false;
};

// Names and types of the grids in a (guarded) .vdb file.
std::vector<GridInfo> listGrids(const std::string& path);

// The FCC grid `gridName` (empty: the first FCC grid) of a .vdb file, fully read. InputError if the
// file has none: the message says to run `fccvdb convert`.
FccGrid::Ptr readFccGrid(const std::string& path, const std::string& gridName = {});

// An FCC grid with the bounds grid stored beside it (null when the file has none: files written
// before bounds existed), read in one pass.
struct FccWithBounds {
  FccGrid::Ptr grid;
  BoundsGrid::Ptr bounds;
};
FccWithBounds readFccGridWithBounds(const std::string& path, const std::string& gridName = {});

// Among grids already read from `path` (named in errors): the FCC grid `gridName` (empty: the first
// FCC grid; InputError if none), and the bounds grid of FCC grid `fccName` (null if none).
FccGrid::Ptr findFccGrid(const std::string& path, const openvdb::GridPtrVec& grids, const std::string& gridName);
BoundsGrid::Ptr findBoundsGrid(const openvdb::GridPtrVec& grids, const std::string& fccName);

// The bounds grid of FCC grid `fccGridName` in a (guarded) .vdb file; null if there is none.
BoundsGrid::Ptr readBoundsGrid(const std::string& path, const std::string& fccGridName);

// The float grid `gridName` (empty: the first float grid), for conversion. Half-stored grids read as float.
openvdb::FloatGrid::Ptr readFloatGrid(const std::string& path, const std::string& gridName = {});

// File-level metadata and grids, written to a temporary file and renamed (AtomicOutput).
void writeVdbAtomically(const std::string& path, const openvdb::GridCPtrVec& grids, bool overwrite,
                        const std::string& inputPath = {});

}  // namespace fcc::io
