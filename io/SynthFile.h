// `fccvdb synth`: a synthetic field (sparse/SynthFields.h) as an FCC grid with its bounds grid in a
// .vdb, built streamed (sparse/StreamedBuild.h): memory stays bounded whatever the size. With
// `--lattice cc`, the same field as a Cartesian float grid, for rendering with a CC reconstruction.
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

// `synth --lattice cc`: the same field at every point of the Cartesian embedding of spec.dims (the FCC
// file holds the half of them with an even coordinate sum), as a FloatGrid fog volume named after the
// kind, with the FCC file's transform, so both cover the same world box for the same --dims. Built in
// memory (sparse/CartesianGridBuilder.h: 4 bytes a point); `half` stores 16-bit floats; `prefilter` and
// `preprocess` do not apply (the renderer prefilters CC data itself). SynthSummary::bricks counts leaves,
// boundsBricks is 0 (no bounds grid: the renderer computes a Cartesian grid's ranges when it opens it).
SynthSummary writeSynthCartesianFile(const std::string& output, const SynthOptions& options);
// `synth --lattice bcc`: the same field at the BCC sites of the Cartesian embedding of spec.dims (the
// points whose coordinates are all even or all odd: a quarter of them), as the two coset grids of
// sparse/BccGrids.h, with the FCC file's transform for BCC index space. As writeSynthCartesianFile
// otherwise (in memory, 4 bytes a site; `half`; bricks counts both grids' leaves).
SynthSummary writeSynthBccFile(const std::string& output, const SynthOptions& options);

// What a synth dataset's FCC grid carries: the kind as its name, the field's transform, and the
// metadata (fcc_mode synth:<kind>, the samples' range and histogram).
void describeSynthGrid(FccGrid& grid, const std::string& kind, const SynthField& synth, bool prefilter,
                       const SampleSummary& samples);

}  // namespace fcc::io
