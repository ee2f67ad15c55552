// Builds the sparse four-channel FCC grid from a sample field in memory, block by block (one VDB leaf
// of packed voxels at a time, FccBlockBuilder.h), applying the quasi-interpolation prefilter on the
// way. StreamedBuild.h builds the same grid for writing without holding its values.
#pragma once

#include <openvdb/util/NullInterrupter.h>

#include "FccBlockBuilder.h"
#include "FccGrid.h"
#include "SampleField.h"

namespace fcc {

struct BuildResult {
  FccGrid::Ptr grid;
  SampleSummary samples;  // range and histogram of the samples V over the field's bounds
};

// The grid's transform is left as identity (lattice index space = world); the caller sets it. Throws
// fcc::Error if the interrupter asks to stop.
BuildResult buildFccGrid(const SampleField& field, const BuildOptions& options,
                         openvdb::util::NullInterrupter* interrupter = nullptr);

}  // namespace fcc
