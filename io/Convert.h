// `fccvdb convert`: a Cartesian volume (.vdb float grid, raw, NRRD, NIfTI) to an FCC grid in a .vdb.
#pragma once

#include <openvdb/util/NullInterrupter.h>

#include <functional>
#include <optional>
#include <string>

#include "DenseVolume.h"

namespace fcc {
class BrickKernels;
}

namespace fcc::io {

struct ConvertOptions {
  std::string mode = "subsample";     // "subsample" (even-parity voxels) or "resample"
  uint64_t samples = 0;               // resample: about this many FCC samples over the extent
  double scale = 0.0;                 // resample: lattice spacing in source voxels (instead of samples)
  std::optional<float> background;    // default: the VDB's background, 0 for raw/NRRD/NIfTI
  bool prefilter = true;
  float tolerance = 0.0f;
  bool half = false;
  bool overwrite = false;
  std::string gridName;               // .vdb input: which float grid (default: the first)
  std::optional<RawLayout> raw;       // raw input layout (required for raw files)
  bool bounds = true;                 // compute the bounds grid and store it beside the FCC grid
  BrickKernels* preprocess = nullptr; // who computes it (null: the C++/TBB reference)
  // The reference path the streamed conversion is tested against: the whole source and output in
  // memory (buildFccGrid, then computeBrickBounds). Without it, the output is built twice and never
  // held (StreamedBuild.h), and a .vdb source is read leaf by leaf (VdbSourceField.h).
  bool inMemory = false;
  // Called once the input is open and its header understood, before the long read: a line such as
  // "converting X" then comes only for an input that converts (a bad one is its error line alone).
  std::function<void()> onOpened;
};

struct ConvertSummary {
  std::string gridName;
  uint64_t inputVoxels = 0;
  uint64_t activeSamples = 0;
  uint64_t bricks = 0;
  uint64_t boundsBricks = 0;           // active bricks of the bounds grid (0 without bounds)
  std::string timings;                 // wall seconds by stage (streamed conversions), for --timings
};

ConvertSummary convertToFcc(const std::string& input, const std::string& output, const ConvertOptions& options,
                            openvdb::util::NullInterrupter* interrupter = nullptr);

}  // namespace fcc::io
