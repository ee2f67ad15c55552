// The level-of-detail pyramid of an FCC file (`fccvdb pyramid`, `convert --pyramid`, `synth --pyramid`;
// docs/FORMAT.md "The pyramid"): level k is an FCC grid of lattice spacing 2^k (in level 0's spacings)
// named "<level 0>.lod<k>", with its own bounds grid, in the same file; the coarsest level's data fits
// in a box of at most kMaxCoarsestBricks bricks.
//
// Level k's coefficients come from level k-1's: its spline sampled exactly at level k's sites
// (io/FinerSplineField.h), then level k's prefilter, so each level is the spline quasi-interpolation of
// the finer spline's values (constant and linear fields are reproduced exactly, up to rounding). Each
// level is built streamed (sparse/StreamedBuild.h): level k-1 is read brick by brick, level k built slab
// by slab, into a temporary file beside the output; the output is then written as level 0 and its
// bounds copied from the input (io/CopiedFccTree.h: the same values, so it renders exactly as before),
// followed by each level copied from its temporary file. No grid is ever held whole: memory is the
// topologies, bounds grids and a few slabs, as for `synth`.
#pragma once

#include <openvdb/util/NullInterrupter.h>

#include <cstdint>
#include <string>
#include <vector>

#include "sparse/FccGrid.h"

namespace fcc {
class BrickKernels;
}

namespace fcc::io {

// The coarsest level's data (leaves and non-background tiles) lies in a box of at most this many bricks.
inline constexpr uint64_t kMaxCoarsestBricks = 8;
// Levels never exceed this (a guard: each level halves the data's extent, so ~log2 of it are built).
inline constexpr int kMaxPyramidLevels = 24;

struct PyramidOptions {
  std::string output;           // empty: rewrite the input in place (atomically)
  bool overwrite = false;       // an output other than the input that exists
  BrickKernels* kernels = nullptr;  // who computes the levels' bounds (null: the C++ reference)
};

struct PyramidLevel {
  int level = 0;
  double spacing = 1.0;     // in level 0's lattice spacings: 2^level
  std::string grid;         // its grid's name
  uint64_t bricks = 0;      // leaves of its FCC grid
  uint64_t boundsBricks = 0;  // active bricks of its bounds grid
  uint64_t brickBox = 0;    // bricks in the box of its data (leaves and non-background tiles)
};

struct PyramidSummary {
  std::vector<PyramidLevel> levels;  // level 0 first
  uint64_t inputBytes = 0, outputBytes = 0;
};

// Adds the pyramid to the FCC file `input` (replacing one it already has). InputError, one line, for
// a file without an FCC grid, one of raw samples, one holding other grids than level 0, its bounds
// and its levels, or a damaged brick (the input is left as it was).
PyramidSummary addPyramid(const std::string& input, const PyramidOptions& options,
                          openvdb::util::NullInterrupter* progress = nullptr);

// The box (in bricks) of an FCC tree's data: its leaves and the tiles that are not the background.
uint64_t dataBrickBoxVolume(const FccTree& tree);

}  // namespace fcc::io
