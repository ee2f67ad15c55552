// `compare`'s fps column: the real renderer (viewer/Raycaster.h) timed on each row's data, for every
// row (cc: trilinear, tricubic, tricubic-bspline, type6; bcc: barycentric, sheared-trilinear,
// bilinear-spatial, bilinear; fcc: boxspline). Per budget and lattice the row's samples — the sites
// inside the domain, the `samples` the row counts — are written into a temporary .vdb (CC: a FloatGrid;
// BCC: the two coset grids; FCC: the prefiltered grid with its bounds, as `synth` writes one), whose
// worldFromIndex puts them where compare sampled them, opened
// through the brick sources and rendered at compare's size from compare's camera: one cold frame, a
// few warm-up frames, then timed frames; fps = 1 / the median frame time (the GPU time of the frame's
// raycasting passes where the context has timer queries, else wall time). A software rasterizer
// (llvmpipe) gets fewer frames (FpsSettings).
#pragma once

#include <string>
#include <vector>

#include "sparse/Comparison.h"

namespace fcc::cli {

struct FpsSettings {
  int warmupFrames = 3;
  int timedFrames = 10;
  // On a software rasterizer (llvmpipe: seconds a frame at 256x256 on a few cores) instead.
  int cpuWarmupFrames = 1;
  int cpuTimedFrames = 3;
};

struct FpsReport {
  bool timed = false;    // some row has an fps
  std::string renderer;  // EglContext::describe() of the context timed on ("" when none was made)
  std::string line;      // one line for the report: how the fps were measured, or why they were not
};

// Sets CompareRow::fps of the rows it can time. Makes its own EGL context: without one (fcc::Error),
// nothing is timed and the line says why. A row whose rendering fails keeps null and the line says so.
FpsReport timeCompareRows(const AnalyticField& field, const CompareOptions& options, std::vector<CompareRow>& rows,
                          const FpsSettings& settings = {});

}  // namespace fcc::cli
