// The FCC grid of a sample field and its bounds, built for writing in bounded memory: the grid the
// in-memory builder (FccBuilder.h) makes, followed by computeBrickBounds (BrickBounds.h), without
// ever holding the grid's values.
//
// Pass 1 (here) builds the blocks slab by slab along x and keeps, of each leaf, only its active mask
// (a StreamedFccTree), plus the sample range; the bounds of a slab's bricks are computed from a
// window of the slabs they read (FccSlabWindow.h): one either side, two for raw samples, whose
// coefficients read one more. Pass 2 happens while the grid is written: its tree copies each leaf pass 1
// kept encoded in a scratch file, and rebuilds any other (StreamedFccTree.h). Memory: the topology (~100 bytes a leaf), the bounds, and a few slabs.
#pragma once

#include <openvdb/util/NullInterrupter.h>

#include "BrickBounds.h"
#include "FccBlockBuilder.h"
#include "FccGrid.h"
#include "SampleField.h"

namespace fcc {

class BrickKernels;

struct StreamedBuildOptions {
  bool half = false;              // the grid is saved as half floats: bounds of the rounded values
  BrickKernels* kernels = nullptr;  // bounds (and prefilter for raw samples); null: the C++ reference
  // Pass 1 keeps its leaves encoded in a scratch file (EncodedLeafFile.h) for pass 2 to copy, at most
  // this many bytes (0: half the temp folder's free space); off: pass 2 rebuilds every leaf.
  bool keepLeaves = true;
  uint64_t keepLeavesMaxBytes = 0;
};

struct StreamedBuild {
  // Topology only, saveFloatAsHalf set, transform identity; write it (io::writeVdbAtomically) while
  // the builder's field lives. The caller names it and sets metadata and transform.
  FccGrid::Ptr grid;
  // The bounds grid's tree, pruned: boundsGridOf(bounds, *grid) once the grid is named.
  openvdb::Vec2STree::Ptr bounds;
  SampleSummary samples;  // range and histogram of the samples V over the field's bounds
  // Wall seconds of pass 1's stages (what `convert --timings` prints): choosing a slab's blocks,
  // preparing the field for them, building them (in parallel), the slab window, the bounds, the prune.
  struct Times {
    double blocks = 0, prepare = 0, build = 0, window = 0, bounds = 0, prune = 0;
    double boundsKernels = 0;  // of `bounds`: the kernels proper (BrickKernels::computeSeconds)
  } times;
};

// The grid of `builder`'s field and options. `progress` reports pass 1 here and pass 2 while the
// grid is written; throws fcc::Error if it asks to stop.
StreamedBuild buildFccGridStreamed(const FccBlockBuilder& builder, const StreamedBuildOptions& options,
                                   openvdb::util::NullInterrupter* progress = nullptr);

}  // namespace fcc
