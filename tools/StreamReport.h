// What `fccvdb bench stream` measured and how it is written: the per-frame records and summaries of
// each budget pair, the JSON (`--json`, the contract of issue 19) and the SVG plots (`--plots`).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fcc::cli {

// One frame: one Raycaster::step() at the frame's camera.
struct StreamFrame {
  double ms = 0.0;              // the step's wall time (uploads, the pass, its read-back)
  double uploadMs = 0.0;        // of that, the uploads before the pass,
  double dispatchMs = 0.0;      // issuing the pass,
  double passMs = 0.0;          // the wait for the pass and its results,
  double requestMs = 0.0;       // and queueing the bricks it asked for
  double gpuPassMs = 0.0;       // the raycasting pass on the GPU alone (a timer query around its dispatch)
  int passes = 0;               // 0 or 1: a complete view runs none
  bool restarted = false, complete = false;
  uint32_t requested = 0, uploaded = 0, missing = 0;
  uint64_t bytesUploaded = 0;
  std::vector<uint64_t> levelMix;  // bricks drawn per level of detail
  double fullResolutionFraction = 1.0;
  std::size_t streaming = 0;       // bricks queued or decoding after the step
  uint64_t gpuBytes = 0;           // the pool as allocated (its own accounting: slots x slot bytes)
  uint64_t gpuResidentBytes = 0;   // the resident bricks' share of it
  uint64_t hostBytes = 0;          // the host cache's own accounting
  uint64_t rssBytes = 0;           // VmRSS after the step
  // Of the distinct bricks the pass reached, those resident (drawn) over all (drawn and missing);
  // NaN when the pass reached none (or ran none).
  double gpuHitRate() const;
};

// One budget pair's run over the path.
struct StreamRun {
  std::size_t gpuBudgetBytes = 0, hostBudgetBytes = 0;
  std::string layout;
  uint32_t slots = 0;
  std::size_t slotBytes = 0;
  std::vector<StreamFrame> frames;
};

struct StreamSummary {
  double p50Ms = 0.0, p99Ms = 0.0, meanMs = 0.0, maxMs = 0.0, fps = 0.0;
  int framesOverBudget = 0;      // frame time above --frame-budget-ms
  int completeFrames = 0;
  double gpuHitRate = 0.0;       // NaN when no pass reached any brick
  uint64_t bricksUploaded = 0, bytesUploaded = 0;
  uint64_t maxGpuBytes = 0, maxGpuResidentBytes = 0, maxHostBytes = 0, maxRssBytes = 0;
  bool budgetOk = true;          // GPU and host within 2% of their budgets at every frame
};
// Percentiles by nearest rank on the sorted frame times (so p50 <= p99 <= max).
StreamSummary summarize(const StreamRun& run, double frameBudgetMs);
inline constexpr double kBudgetTolerance = 1.02;  // issue 19: never more than 2% over a budget

// The working set of a complete view at one image size: bricks the view's frame drew.
struct WorkingSetPoint {
  int width = 0, height = 0;
  uint64_t bricks = 0, bytes = 0;
  bool atLeast = false;  // the pool evicted during the frame: `bricks` may be a lower bound
};

struct StreamReport {
  std::string device, file, path, reconstruction, mode;
  int width = 0, height = 0, frames = 0;
  double frameBudgetMs = 0.0, uploadMs = 0.0;
  bool uploadFit = false;       // uploads fitted to what the frame budget leaves (viewer/UploadBudget.h)
  bool primed = false;          // the programs were run and left to the driver before the runs (--prime)
  uint64_t seed = 0;
  int jumpEvery = 0;
  uint64_t dataBricks = 0;      // bricks whose values vary: what the whole dataset needs on the GPU
  uint64_t dataGpuBytes = 0;    // those in the layout of the largest GPU budget
  std::vector<StreamRun> runs;
  std::vector<WorkingSetPoint> workingSet;
  std::vector<std::string> plots;  // the files written
};

std::string streamJson(const StreamReport& report);
// The plots' paths for a stem ("DIR/NAME"): frame time, fps and hit rate against cache size, working set.
std::vector<std::string> streamPlotPaths(const std::string& stem);
// Writes the plots (each through io::AtomicOutput) to streamPlotPaths(stem).
void writeStreamPlots(const StreamReport& report, const std::string& stem, bool overwrite);
// The table on stdout.
void printStreamTable(const StreamReport& report);

}  // namespace fcc::cli
