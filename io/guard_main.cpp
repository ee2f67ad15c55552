// fccvdb-guard: OpenVDB's parsing of a possibly damaged .vdb, in a process of its own. The guard in
// io/VdbFile.cpp spawns it (posix_spawn: no fork of the threaded caller, so no lock is copied held)
// with a time limit and turns its crash, hang or failure into an InputError naming the file.
//
//   fccvdb-guard file everything|topology PATH
//       every grid read (topology: the metadata, every tree's topology and the buffers of every grid
//       but the FCC grids), then every tree walked once.
//   fccvdb-guard leaves PATH GRID TYPE[,TYPE...] [--bounds BOUNDSGRID]
//       what an out-of-core open parses through OpenVDB: VdbLeafReader's topology read of GRID (empty:
//       the first grid of one of the types) and, with --bounds, that grid read whole.
//
// Exit status 0: read; 3: OpenVDB (or our reader) threw, the one-line message on stdout; 2: a command
// line the guard does not understand (the caller's bug, not the file's); a crash is a signal.
#include <openvdb/openvdb.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "io/VdbLeafReader.h"
#include "sparse/BrickBounds.h"
#include "sparse/FccGrid.h"

namespace {

// Every tile and every leaf of a tree, visited one after the other: a tree that reads but is
// inconsistent fails here. Serial: one pass over the nodes needs no worker threads.
struct WalkTree {
  template <class GridT>
  void operator()(const GridT& grid) const {
    using TreeT = typename GridT::TreeType;
    openvdb::Index64 count = 0;
    auto tile = grid.tree().cbeginValueAll();
    tile.setMaxDepth(TreeT::ValueAllCIter::LEAF_DEPTH - 1);  // tiles only: leaves are walked below
    for (; tile; ++tile) count += tile.isValueOn();
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) count += leaf->onVoxelCount();
    (void)count;
  }
};

// The grid types whose trees are walked: OpenVDB's own and ours (the FCC grid, the bounds grid).
using WalkedGridTypes = openvdb::GridTypes::Append<fcc::FccGrid, fcc::BoundsGrid>;

void checkFile(const std::string& path, bool topologyOnly) {
  openvdb::io::File file(path);
  file.setCopyMaxBytes(0);
  file.open(topologyOnly);  // everything: no delayed loading, every byte is read now
  openvdb::GridPtrVecPtr grids = file.getGrids();
  for (const auto& g : *grids) {
    if (topologyOnly && !fcc::isFccGrid(*g)) g->baseTree().readNonresidentBuffers();
    g->apply<WalkedGridTypes>(WalkTree{});
  }
  file.close();
}

void checkLeaves(const std::string& path, const std::string& gridName, const std::vector<std::string>& types,
                 const std::string& boundsName) {
  fcc::io::VdbLeafReader probe(path, gridName, types, /*indexLeaves=*/false);
  if (boundsName.empty()) return;
  // As BrickStore reads it: the whole file opened without delayed loading, the one grid read.
  openvdb::io::File file(path);
  file.setCopyMaxBytes(0);
  file.open(/*delayLoad=*/false);
  (void)file.readGrid(boundsName);
  file.close();
}

std::vector<std::string> splitCommas(const std::string& s) {
  std::vector<std::string> parts;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t comma = s.find(',', begin);
    parts.push_back(s.substr(begin, comma - begin));
    if (comma == std::string::npos) return parts;
    begin = comma + 1;
  }
}

int usage() {
  std::printf("fccvdb-guard: usage: fccvdb-guard file everything|topology PATH | "
              "fccvdb-guard leaves PATH GRID TYPE[,TYPE...] [--bounds BOUNDSGRID]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.size() == 3 && args[0] == "file" && (args[1] == "everything" || args[1] == "topology")) {
      fcc::initializeVdb();
      checkFile(args[2], args[1] == "topology");
    } else if ((args.size() == 4 || (args.size() == 6 && args[4] == "--bounds")) && args[0] == "leaves") {
      fcc::initializeVdb();
      checkLeaves(args[1], args[2], splitCommas(args[3]), args.size() == 6 ? args[5] : std::string());
    } else {
      return usage();
    }
  } catch (const std::exception& e) {
    std::printf("%s\n", e.what());
    return 3;
  } catch (...) {
    std::printf("unknown error\n");
    return 3;
  }
  return 0;
}
