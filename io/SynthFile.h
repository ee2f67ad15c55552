// `fccvdb synth`: a synthetic field (sparse/SynthFields.h) as an FCC grid with its bounds grid in a
// .vdb, built streamed (sparse/StreamedBuild.h): memory stays bounded whatever the size.
#pragma once

#include <openvdb/util/NullInterrupter.h>

#include <cstdint>
#include <string>

#include "sparse/FccGrid.h"
#include "sparse/SampleHistogram.h"
#include "sparse/SynthFields.h"

namespace fcc {
class BrickKernels;
}

namespace fcc::io {

struct SynthOptions {
  SynthSpec spec;
  bool prefilter = true;
  bool half = false;
  bool overwrite = false;
  BrickKernels* preprocess = nullptr;  // who computes the bounds (null: the C++/TBB reference)
};

struct SynthSummary {
  uint64_t activeSamples = 0;
  uint64_t bricks = 0;        // leaves of the FCC grid
  uint64_t boundsBricks = 0;  // active bricks of the bounds grid
};

// Writes the dataset atomically (AtomicOutput); `progress` reports both passes.
SynthSummary writeSynthFile(const std::string& output, const SynthOptions& options,
                            openvdb::util::NullInterrupter* progress = nullptr);

// What a synth dataset's FCC grid carries: the kind as its name, the field's transform, and the
// metadata (fcc_mode synth:<kind>, the samples' range and histogram).
void describeSynthGrid(FccGrid& grid, const std::string& kind, const SynthField& synth, bool prefilter,
                       const SampleSummary& samples);

}  // namespace fcc::io
