// `mpirun -np N fccvdb render …` (FCC_MPI builds; docs/MPI.md): every rank opens the file, owns one
// part of the bricks (KdPartition), renders the whole image from its bricks alone on its GPU, and the
// images are composited by radix-k over MPI (Compositor.h); rank 0 writes the image and the report.
#pragma once

#include <string>

#include "tools/RenderFlags.h"

namespace fcc::mpi {

struct DistributedRenderRequest {
  cli::RenderFlags flags;
  std::string output;
  bool force = false, quiet = false, json = false, allowDamaged = false;
};

// The exit status, the same on every rank. Anything that can fail on one rank alone before the ranks
// start waiting for each other (the output, the file, the camera, EGL) is agreed on first: then every
// rank exits 1 and rank 0 prints one line (naming the rank unless all failed alike).
int renderDistributed(const DistributedRenderRequest& request);

// `mpirun -np N fccvdb bench render`: a cold frame, `warmup` frames, then `frames` timed frames over an
// orbit of `arc` degrees, each rendered by all ranks and composited (and gathered) as render's; per
// rank the mean render, wait and compositing seconds and bytes exchanged, bricks read over the run.
int benchRenderDistributed(const cli::RenderFlags& flags, int frames, int warmup, double arc, bool json);

}  // namespace fcc::mpi
