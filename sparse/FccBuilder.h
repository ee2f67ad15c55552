// Builds the sparse four-channel FCC grid from a sample field, block by block (one VDB leaf of packed
// voxels at a time), applying the quasi-interpolation prefilter on the way.
#pragma once

#include <openvdb/util/NullInterrupter.h>

#include "FccGrid.h"
#include "SampleField.h"

namespace fcc {

struct BuildOptions {
  bool prefilter = true;   // store coefficients c = q_fcc * V (what the renderer needs) or raw samples V
  float tolerance = 0.0f;  // a packed voxel whose four values are within this of the background is inactive
};

struct BuildResult {
  FccGrid::Ptr grid;
  float sampleMin = 0.0f;  // range of the samples V over the field's bounds
  float sampleMax = 0.0f;
};

// The grid's transform is left as identity (lattice index space = world); the caller sets it. Throws
// fcc::Error if the interrupter asks to stop.
BuildResult buildFccGrid(const SampleField& field, const BuildOptions& options,
                         openvdb::util::NullInterrupter* interrupter = nullptr);

}  // namespace fcc
