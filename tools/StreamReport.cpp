#include "StreamReport.h"

#include <numeric>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>

#include "JsonText.h"
#include "bench/SvgPlot.h"
#include "io/AtomicOutput.h"

namespace fcc::cli {
namespace {

constexpr double kMiB = 1024.0 * 1024.0;

std::string u64(uint64_t v) { return std::to_string(v); }

std::string levelMixJson(const std::vector<uint64_t>& mix) {
  std::string out = "[";
  for (std::size_t i = 0; i < mix.size(); ++i) out += (i ? ", " : "") + u64(mix[i]);
  return out + "]";
}

std::string runName(const StreamRun& run) {
  char text[96];
  std::snprintf(text, sizeof text, "GPU %g MiB, host %g MiB", run.gpuBudgetBytes / kMiB, run.hostBudgetBytes / kMiB);
  return text;
}

// Nearest rank: the smallest value with at least p of the values at or below it.
double percentile(std::vector<double> sorted, double p) {
  if (sorted.empty()) return 0.0;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t rank = std::size_t(std::ceil(p * double(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}

}  // namespace

namespace {
// Bricks drawn at every level: with a pyramid, a coarse brick drawn is a hit as much as a level-0 one.
uint64_t bricksDrawn(const std::vector<uint64_t>& levelMix) { return std::accumulate(levelMix.begin(), levelMix.end(), uint64_t(0)); }
}  // namespace

double StreamFrame::gpuHitRate() const {
  const uint64_t drawn = bricksDrawn(levelMix);
  const uint64_t reached = drawn + missing;
  return reached ? double(drawn) / double(reached) : std::numeric_limits<double>::quiet_NaN();
}

StreamSummary summarize(const StreamRun& run, double frameBudgetMs) {
  StreamSummary s;
  std::vector<double> ms;
  uint64_t drawn = 0, reached = 0;
  for (const StreamFrame& f : run.frames) {
    ms.push_back(f.ms);
    s.meanMs += f.ms / double(run.frames.size());
    s.maxMs = std::max(s.maxMs, f.ms);
    s.framesOverBudget += f.ms > frameBudgetMs;
    s.completeFrames += f.complete;
    s.bricksUploaded += f.uploaded;
    s.bytesUploaded += f.bytesUploaded;
    const uint64_t d = bricksDrawn(f.levelMix);
    drawn += d;
    reached += d + f.missing;
    s.maxGpuBytes = std::max(s.maxGpuBytes, f.gpuBytes);
    s.maxGpuResidentBytes = std::max(s.maxGpuResidentBytes, f.gpuResidentBytes);
    s.maxHostBytes = std::max(s.maxHostBytes, f.hostBytes);
    s.maxRssBytes = std::max(s.maxRssBytes, f.rssBytes);
  }
  s.p50Ms = percentile(ms, 0.50);
  s.p99Ms = percentile(ms, 0.99);
  s.fps = s.meanMs > 0.0 ? 1e3 / s.meanMs : 0.0;
  s.gpuHitRate = reached ? double(drawn) / double(reached) : std::numeric_limits<double>::quiet_NaN();
  s.budgetOk = double(s.maxGpuBytes) <= kBudgetTolerance * double(run.gpuBudgetBytes) &&
               double(s.maxHostBytes) <= kBudgetTolerance * double(run.hostBudgetBytes);
  return s;
}

std::string streamJson(const StreamReport& r) {
  std::string out = "{\"device\": " + jsonString(r.device) + ", \"file\": " + jsonString(r.file) +
                    ", \"path\": " + jsonString(r.path) + ", \"reconstruction\": " + jsonString(r.reconstruction) +
                    ", \"mode\": " + jsonString(r.mode) + ", \"res\": [" + std::to_string(r.width) + ", " +
                    std::to_string(r.height) + "], \"frames\": " + std::to_string(r.frames) +
                    ", \"frame_budget_ms\": " + jsonNumber(r.frameBudgetMs) + ", \"upload_ms\": " + jsonNumber(r.uploadMs) +
                    ", \"upload_fit\": " + (r.uploadFit ? "true" : "false") + ", \"primed\": " + (r.primed ? "true" : "false") + ", \"seed\": " + u64(r.seed) + ", \"jump_every\": " + std::to_string(r.jumpEvery) +
                    ", \"data_bricks\": " + u64(r.dataBricks) + ", \"data_gpu_bytes\": " + u64(r.dataGpuBytes) +
                    ",\n \"working_set\": [";
  for (std::size_t i = 0; i < r.workingSet.size(); ++i) {
    const WorkingSetPoint& w = r.workingSet[i];
    out += std::string(i ? ", " : "") + "{\"res\": [" + std::to_string(w.width) + ", " + std::to_string(w.height) +
           "], \"pixels\": " + u64(uint64_t(w.width) * uint64_t(w.height)) + ", \"bricks\": " + u64(w.bricks) +
           ", \"bytes\": " + u64(w.bytes) + ", \"at_least\": " + (w.atLeast ? "true" : "false") + "}";
  }
  out += "],\n \"plots\": [";
  for (std::size_t i = 0; i < r.plots.size(); ++i) out += (i ? ", " : "") + jsonString(r.plots[i]);
  out += "],\n \"runs\": [";
  for (std::size_t k = 0; k < r.runs.size(); ++k) {
    const StreamRun& run = r.runs[k];
    const StreamSummary s = summarize(run, r.frameBudgetMs);
    out += std::string(k ? ",\n" : "\n") + "  {\"gpu_budget_bytes\": " + u64(run.gpuBudgetBytes) +
           ", \"host_budget_bytes\": " + u64(run.hostBudgetBytes) + ", \"layout\": " + jsonString(run.layout) +
           ", \"slots\": " + std::to_string(run.slots) + ", \"slot_bytes\": " + u64(run.slotBytes) +
           ",\n   \"summary\": {\"frames\": " + std::to_string(run.frames.size()) +
           ", \"p50_frame_ms\": " + jsonNumber(s.p50Ms) + ", \"p99_frame_ms\": " + jsonNumber(s.p99Ms) +
           ", \"mean_frame_ms\": " + jsonNumber(s.meanMs) + ", \"max_frame_ms\": " + jsonNumber(s.maxMs) +
           ", \"fps\": " + jsonNumber(s.fps) + ", \"frames_over_budget\": " + std::to_string(s.framesOverBudget) +
           ", \"complete_frames\": " + std::to_string(s.completeFrames) + ", \"gpu_hit_rate\": " + jsonNumber(s.gpuHitRate) +
           ", \"bricks_uploaded\": " + u64(s.bricksUploaded) + ", \"bytes_uploaded\": " + u64(s.bytesUploaded) +
           ", \"max_gpu_bytes\": " + u64(s.maxGpuBytes) + ", \"max_gpu_resident_bytes\": " + u64(s.maxGpuResidentBytes) +
           ", \"max_host_bytes\": " + u64(s.maxHostBytes) + ", \"max_rss_bytes\": " + u64(s.maxRssBytes) +
           ", \"gpu_budget_bytes\": " + u64(run.gpuBudgetBytes) + ", \"host_budget_bytes\": " + u64(run.hostBudgetBytes) +
           ", \"budget_ok\": " + (s.budgetOk ? "true" : "false") + "},\n   \"frames\": [";
    for (std::size_t i = 0; i < run.frames.size(); ++i) {
      const StreamFrame& f = run.frames[i];
      out += std::string(i ? ",\n    " : "\n    ") + "{\"frame\": " + std::to_string(i) + ", \"frame_ms\": " + jsonNumber(f.ms) +
             ", \"upload_ms\": " + jsonNumber(f.uploadMs) + ", \"dispatch_ms\": " + jsonNumber(f.dispatchMs) +
             ", \"pass_ms\": " + jsonNumber(f.passMs) +
             ", \"request_ms\": " + jsonNumber(f.requestMs) + ", \"gpu_pass_ms\": " + jsonNumber(f.gpuPassMs) +
             ", \"passes\": " + std::to_string(f.passes) + ", \"restarted\": " + (f.restarted ? "true" : "false") +
             ", \"complete\": " + (f.complete ? "true" : "false") + ", \"bricks_requested\": " + std::to_string(f.requested) +
             ", \"bricks_uploaded\": " + std::to_string(f.uploaded) + ", \"bricks_missing\": " + std::to_string(f.missing) +
             ", \"bytes_uploaded\": " + u64(f.bytesUploaded) + ", \"level_mix\": " + levelMixJson(f.levelMix) +
             ", \"gpu_hit_rate\": " + jsonNumber(f.gpuHitRate()) +
             ", \"full_resolution_fraction\": " + jsonNumber(f.fullResolutionFraction) +
             ", \"streaming\": " + u64(f.streaming) + ", \"gpu_bytes\": " + u64(f.gpuBytes) +
             ", \"gpu_resident_bytes\": " + u64(f.gpuResidentBytes) + ", \"host_bytes\": " + u64(f.hostBytes) +
             ", \"rss_bytes\": " + u64(f.rssBytes) + "}";
    }
    out += "]}";
  }
  return out + "\n]}\n";
}

std::vector<std::string> streamPlotPaths(const std::string& stem) {
  return {stem + "-frame-time.svg", stem + "-fps.svg", stem + "-hit-rate.svg", stem + "-working-set.svg"};
}

void writeStreamPlots(const StreamReport& r, const std::string& stem, bool overwrite) {
  const std::vector<std::string> paths = streamPlotPaths(stem);
  // Frame time over the path, one line a budget pair.
  SvgPlot frameTime;
  frameTime.title = "Frame time over the " + r.path + " path (" + std::to_string(r.width) + "x" + std::to_string(r.height) + ")";
  frameTime.xLabel = "frame";
  frameTime.yLabel = "frame time (ms)";
  for (const StreamRun& run : r.runs) {
    PlotSeries s{runName(run), {}, {}};
    for (std::size_t i = 0; i < run.frames.size(); ++i) {
      s.x.push_back(double(i));
      s.y.push_back(run.frames[i].ms);
    }
    frameTime.series.push_back(s);
  }
  frameTime.references.push_back({"frame budget", r.frameBudgetMs});

  // fps and hit rate against the GPU cache, one line a host cache size.
  SvgPlot fps, hitRate;
  fps.title = "Frames per second against the GPU cache";
  hitRate.title = "GPU cache hit rate against the GPU cache";
  fps.xLabel = hitRate.xLabel = "GPU cache (MiB)";
  fps.yLabel = "fps (1000 / mean frame time)";
  hitRate.yLabel = "GPU hit rate (bricks drawn / reached)";
  std::map<std::size_t, std::pair<PlotSeries, PlotSeries>> byHost;
  for (const StreamRun& run : r.runs) {
    const StreamSummary s = summarize(run, r.frameBudgetMs);
    auto& [f, h] = byHost[run.hostBudgetBytes];
    char name[64];
    std::snprintf(name, sizeof name, "host %g MiB", run.hostBudgetBytes / kMiB);
    f.name = h.name = name;
    f.points = h.points = true;
    f.x.push_back(run.gpuBudgetBytes / kMiB);
    h.x.push_back(run.gpuBudgetBytes / kMiB);
    f.y.push_back(s.fps);
    h.y.push_back(s.gpuHitRate);
  }
  for (auto& [host, series] : byHost) {
    // Sorted by GPU cache size, so the line goes left to right.
    for (PlotSeries* s : {&series.first, &series.second}) {
      std::vector<std::size_t> order(s->x.size());
      for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return s->x[a] < s->x[b]; });
      PlotSeries sorted{s->name, {}, {}, true, true};
      for (std::size_t i : order) sorted.x.push_back(s->x[i]), sorted.y.push_back(s->y[i]);
      *s = sorted;
    }
    fps.series.push_back(series.first);
    hitRate.series.push_back(series.second);
  }
  fps.references.push_back({"frame budget's fps", 1e3 / r.frameBudgetMs});
  // Sweeps over powers of two read better on a logarithmic axis.
  double gpuLo = 0.0, gpuHi = 0.0;
  for (const StreamRun& run : r.runs) {
    const double mib = run.gpuBudgetBytes / kMiB;
    gpuLo = gpuLo == 0.0 ? mib : std::min(gpuLo, mib);
    gpuHi = std::max(gpuHi, mib);
  }
  fps.logX = hitRate.logX = gpuHi >= 8.0 * gpuLo;
  hitRate.references.push_back({"all resident", 1.0});

  // The working set of complete views against the image size, with the data's size and the budgets.
  SvgPlot workingSet;
  workingSet.title = "Working set of a complete view against image size";
  workingSet.xLabel = "image size (megapixels)";
  workingSet.yLabel = "GPU bricks (MiB)";
  PlotSeries ws{"working set (path's views, max)", {}, {}, true, true};
  for (const WorkingSetPoint& w : r.workingSet) {
    ws.x.push_back(double(w.width) * double(w.height) / 1e6);
    ws.y.push_back(double(w.bytes) / kMiB);
  }
  workingSet.series.push_back(ws);
  workingSet.references.push_back({"whole dataset: " + std::to_string(r.dataBricks) + " bricks", double(r.dataGpuBytes) / kMiB});
  std::vector<std::size_t> gpuBudgets;
  for (const StreamRun& run : r.runs)
    if (std::find(gpuBudgets.begin(), gpuBudgets.end(), run.gpuBudgetBytes) == gpuBudgets.end())
      gpuBudgets.push_back(run.gpuBudgetBytes);
  for (std::size_t b : gpuBudgets) {
    char name[64];
    std::snprintf(name, sizeof name, "GPU cache %g MiB", b / kMiB);
    workingSet.references.push_back({name, b / kMiB});
  }

  const SvgPlot* plots[] = {&frameTime, &fps, &hitRate, &workingSet};
  for (std::size_t i = 0; i < paths.size(); ++i) io::writeTextFile(paths[i], svgText(*plots[i]), overwrite);
}

void printStreamTable(const StreamReport& r) {
  std::printf("device: %s\nfile:   %s, %s, %s, %dx%d, path %s, %d frames at %.1f ms (uploads %.1f ms)\n",
              r.device.c_str(), r.file.c_str(), r.reconstruction.c_str(), r.mode.c_str(), r.width, r.height,
              r.path.c_str(), r.frames, r.frameBudgetMs, r.uploadMs);
  std::printf("%10s %10s %-14s %9s %9s %9s %8s %9s %10s %10s %10s %s\n", "gpu MiB", "host MiB", "layout", "p50 ms",
              "p99 ms", "fps", "hit rate", "complete", "uploaded", "max host", "max RSS", "budgets");
  for (const StreamRun& run : r.runs) {
    const StreamSummary s = summarize(run, r.frameBudgetMs);
    std::printf("%10g %10g %-14s %9.3f %9.3f %9.1f %8.3f %4d/%-4zu %10llu %8.1f M %8.1f M %s\n", run.gpuBudgetBytes / kMiB,
                run.hostBudgetBytes / kMiB, run.layout.c_str(), s.p50Ms, s.p99Ms, s.fps, s.gpuHitRate, s.completeFrames,
                run.frames.size(), (unsigned long long)s.bricksUploaded, s.maxHostBytes / kMiB, s.maxRssBytes / kMiB,
                s.budgetOk ? "ok" : "EXCEEDED");
  }
  for (const WorkingSetPoint& w : r.workingSet)
    std::printf("working set at %dx%d: %s%llu bricks (%.1f MiB); whole dataset %llu bricks\n", w.width, w.height,
                w.atLeast ? "at least " : "", (unsigned long long)w.bricks, w.bytes / kMiB,
                (unsigned long long)r.dataBricks);
  for (const std::string& p : r.plots) std::printf("plot: %s\n", p.c_str());
}

}  // namespace fcc::cli
