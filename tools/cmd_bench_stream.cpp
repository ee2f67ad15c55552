// fccvdb bench stream FILE --path orbit|zoom|jumps|PATH.json: camera paths replayed at a fixed frame
// budget through the progressive renderer (Raycaster::step(), as the viewer drives it: one pass a
// frame, never waiting for the file), over every pair of --gpu-cache and --host-cache sizes; per frame
// the time, passes, bricks requested/uploaded/missing, bytes uploaded, level mix, GPU hit rate and
// the memory against the budgets; a JSON file and SVG plots (docs/BENCHMARKS.md, "bench stream").
#include <numeric>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "Command.h"
#include "CpuRenderer.h"
#include "ProcessMemory.h"
#include "ProgressBar.h"
#include "RenderData.h"
#include "RenderFlags.h"
#include "StreamPaths.h"
#include "StreamReport.h"
#include "SurfaceFlags.h"
#include "io/AtomicOutput.h"
#include "sparse/Error.h"
#include "viewer/BrickPool.h"
#include "viewer/CameraPath.h"
#include "viewer/EglContext.h"
#include "viewer/UploadBudget.h"

namespace fcc::cli {
namespace {

// "64,256": sizes in MiB, each a positive number; ValueError naming the flag otherwise.
std::vector<std::size_t> budgetList(const std::string& text, const char* flag) {
  std::vector<std::size_t> bytes;
  std::size_t at = 0;
  const std::string valid = "; valid is MiB[,MiB...], each a positive number of MiB, e.g. 64,256";
  do {
    const std::size_t comma = text.find(',', at);
    const std::string item = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    char* end = nullptr;
    const double mib = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(mib) || !(mib > 0.0))
      throw ValueError(std::string(flag) + " '" + text + "': '" + item + "' is not a size" + valid);
    bytes.push_back(std::size_t(mib * 1024.0 * 1024.0));
    at = comma == std::string::npos ? std::string::npos : comma + 1;
  } while (at != std::string::npos);
  return bytes;
}

// What a CPU renderer runs unless told otherwise (llvmpipe on two cores: a second or so a frame at 1080p).
constexpr int kCpuFrames = 30;
constexpr const char* kCpuRes = "160x90";
constexpr int kDefaultFrames = 120;
// --prime: steps of the path's first view (a dozen made the H200's driver swap in its optimized
// programs), then time for the driver to finish (500 ms was enough there; 0 was not).
constexpr int kPrimeSteps = 20;
constexpr int kPrimeWaitMs = 500;

// The working set of complete views: for each image size, the most bricks any of the path's first,
// middle and last views drew in a complete frame (render(); the pool evicting meanwhile may make it a
// lower bound: WorkingSetPoint::atLeast).
std::vector<WorkingSetPoint> measureWorkingSet(render::Raycaster& raycaster, const std::vector<render::Camera>& path,
                                               int width, int height) {
  std::vector<WorkingSetPoint> points;
  const std::vector<std::size_t> views = {0, path.size() / 2, path.size() - 1};
  for (int divisor : {4, 2, 1}) {
    WorkingSetPoint p;
    p.width = std::max(1, width / divisor);
    p.height = std::max(1, height / divisor);
    if (!points.empty() && points.back().width == p.width && points.back().height == p.height) continue;
    for (std::size_t v : views) {
      const uint64_t residentBefore = raycaster.residentCount();
      const render::FrameStats s = raycaster.render(path[v], p.width, p.height);
      // Every level's bricks: with --lod-bias a view is drawn mostly from coarser levels.
      const uint64_t drawn = std::accumulate(s.bricksPerLevel.begin(), s.bricksPerLevel.end(), uint64_t(0));
      p.bricks = std::max(p.bricks, drawn);
      // Slots evicted during the frame may have been drawn earlier in it: then the count is a lower bound.
      p.atLeast = p.atLeast || residentBefore + s.bricksUploaded > raycaster.slotCount();
    }
    p.bytes = p.bricks * raycaster.slotBytes();
    points.push_back(p);
  }
  return points;
}

}  // namespace

Command addBenchStreamCommand(CLI::App& bench) {
  struct Args {
    RenderFlags flags;
    std::string path = "orbit", gpuCaches, hostCaches, json, plots;
    int frames = kDefaultFrames;
    double frameBudgetMs = 16.7, uploadMs = 4.0;
    std::string uploadFit = "on";
    std::string prime = "auto";
    uint64_t seed = 1;
    int jumpEvery = 10;
    bool force = false;
  };
  auto args = std::make_shared<Args>();
  args->flags.res = "1920x1080";
  CLI::App* app = bench.add_subcommand(
      "stream",
      "Camera paths (orbit, zoom, jumps, a recorded PATH.json) replayed at a fixed frame budget through the "
      "progressive renderer over a sweep of cache budgets: per-frame JSON and SVG plots");
  addRenderFlags(*app, args->flags);
  // The budgets take lists here: one run per pair.
  app->remove_option(app->get_option("--gpu-cache"));
  app->remove_option(app->get_option("--host-cache"));
  app->get_option("--res")->capture_default_str();
  app->add_option("--path", args->path,
                  "Camera path: orbit (a full turn about the data's centre in --frames frames), zoom (a straight "
                  "line from the whole dataset to one brick), jumps (a seeded random camera every --jump-every "
                  "frames), or PATH.json (recorded with `fccvdb view --record-path`, replayed in real time at the "
                  "frame budget unless --frames is given)")
      ->capture_default_str();
  app->add_option("--gpu-cache", args->gpuCaches, "GPU brick pool sizes to sweep, MiB[,MiB...] (default: 1024)");
  app->add_option("--host-cache", args->hostCaches,
                  "Host cache sizes to sweep, MiB[,MiB...] (default: a quarter of RAM); one run per pair with --gpu-cache");
  app->add_option("--frames", args->frames, "Frames of the path (default: 120; a recorded path's own length)");
  app->add_option("--frame-budget-ms", args->frameBudgetMs,
                  "The fixed frame budget: each frame is one step() and then waits out the rest of it (the loader "
                  "decodes meanwhile), as a viewer at that rate; the camera moves on every frame regardless")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_option("--upload-ms", args->uploadMs,
                  "Upload time per frame within step() (default: the viewer's 4 ms, or the whole frame budget if shorter)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  app->add_option("--upload-fit", args->uploadFit,
                  "on: each frame uploads for what the frame budget leaves after the last frame's pass and requests, "
                  "at most --upload-ms (viewer/UploadBudget.h, as the viewer does); off: --upload-ms every frame")
      ->capture_default_str()
      ->check(CLI::IsMember({"on", "off"}));
  app->add_option("--prime", args->prime,
                  "on: before the runs, a throwaway renderer of the same options draws the path's first view and "
                  "the GPU driver gets time to finish optimizing the programs (its first compile runs them slower); "
                  "auto: on, except on a CPU renderer")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "on", "off"}));
  app->add_option("--seed", args->seed, "Seed of the jumps path")->capture_default_str();
  app->add_option("--jump-every", args->jumpEvery, "Frames each camera of the jumps path is held")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_option("--json", args->json, "Write per-frame records and per-run summaries to OUT.json (plots go beside it)");
  app->add_option("--plots", args->plots, "Folder for the SVG plots (default: the --json file's folder)");
  app->add_flag("--force", args->force, "Overwrite existing --json and plot files");
  return {app, [args, app]() {
            const auto given = [&](const char* flag) { return app->get_option(flag)->count() > 0; };
            // The flags first, each refused in one line before any work.
            if (given("--frames") && args->frames < 1)
              throw ValueError("--frames " + std::to_string(args->frames) + ": valid is a number of frames, at least 1");
            const bool builtIn = args->path == "orbit" || args->path == "zoom" || args->path == "jumps";
            render::CameraPath recorded;
            if (!builtIn) {
              if (!std::filesystem::path(args->path).has_extension() ||
                  std::filesystem::path(args->path).extension() != ".json")
                throw ValueError("--path '" + args->path +
                                 "': valid are orbit, zoom, jumps, or a camera path PATH.json recorded with `fccvdb view --record-path`");
              try {
                recorded = render::readCameraPathFile(args->path);
              } catch (const InputError& e) {
                throw InputError(std::string("--path: ") + e.what());
              }
            }
            // The viewer's upload time (4 ms), or all of a shorter frame budget unless given.
            if (!given("--upload-ms")) args->uploadMs = std::min(args->uploadMs, args->frameBudgetMs);
            if (args->uploadMs > args->frameBudgetMs) {
              char line[160];
              std::snprintf(line, sizeof line, "--upload-ms %g: valid is at most --frame-budget-ms (%g), the frame's time",
                            args->uploadMs, args->frameBudgetMs);
              throw ValueError(line);
            }
            RenderFlags flags = args->flags;
            const render::RenderOptions defaults = renderOptionsFromFlags(flags);
            const std::vector<std::size_t> gpuBudgets =
                args->gpuCaches.empty() ? std::vector<std::size_t>{defaults.gpuCacheBytes} : budgetList(args->gpuCaches, "--gpu-cache");
            const std::vector<std::size_t> hostBudgets =
                args->hostCaches.empty() ? std::vector<std::size_t>{defaults.hostCacheBytes} : budgetList(args->hostCaches, "--host-cache");
            // Outputs are checked before any work (io::AtomicOutput's policy: --force to overwrite).
            std::string stem;
            if (!args->json.empty() || !args->plots.empty()) {
              const std::filesystem::path json(args->json.empty() ? "stream.json" : args->json);
              const std::filesystem::path folder = !args->plots.empty() ? std::filesystem::path(args->plots) : json.parent_path();
              stem = (folder / json.stem()).string();
              if (!args->plots.empty() && !std::filesystem::is_directory(args->plots))
                throw ValueError("--plots " + args->plots + ": not a folder (it must exist)");
              if (!args->json.empty()) io::checkOutputPath(args->json, args->force);
              for (const std::string& p : streamPlotPaths(stem)) io::checkOutputPath(p, args->force);
            }

            const EglContext gl;
            int frames = given("--frames") || !builtIn ? args->frames : kDefaultFrames;
            if (isCpuRenderer(gl.renderer())) {  // as bench render: minutes over the defaults without a word
              std::string scaled;
              if (!given("--res")) flags.res = kCpuRes, scaled = std::string("--res ") + kCpuRes;
              if (!given("--frames") && builtIn)
                frames = kCpuFrames, scaled += (scaled.empty() ? "" : ", ") + std::string("--frames ") + std::to_string(kCpuFrames);
              if (!scaled.empty())
                std::fprintf(stderr,
                             "fccvdb: warning: %s renders on the CPU: running %s instead of the defaults (give the flags "
                             "to choose); its figures say nothing about a GPU\n",
                             gl.renderer().c_str(), scaled.c_str());
            }
            int width = 0, height = 0;
            resolutionFromFlags(flags.res, width, height);

            // The data once, its caches unused (each run makes its own at its budget).
            RenderData data(flags, std::size_t(1) << 20, false);
            render::RenderOptions options = renderOptionsFromFlags(flags);
            const float iso = data.iso(flags).value;
            options.iso = iso;
            data.applyMode(flags, options);
            if (options.mode == render::RenderMode::Iso) {
              data.warnIfIsoOutside(iso);
              setSurfaces(options, surfacesFromFlags(flags, io::IsoChoice{iso, "--iso"}));
            }
            // --lod-bias: the pyramid's levels; opened again for every run below, with fresh host caches
            // shared out of that run's --host-cache.
            data.applyLevels(flags, /*levelsByDefault=*/false, false, options);
            options.countBricksDrawn = true;
            options.timeGpu = true;  // each pass's GPU time beside the wall times (gpu_pass_ms)
            const render::Camera start = data.camera(flags, double(width) / height);

            std::vector<render::Camera> cameras;
            if (args->path == "orbit") {
              cameras = orbitPath(start, frames);
            } else if (args->path == "zoom") {
              double brickWorld = 0.0;
              const glm::dvec3 target = zoomTarget(data.source(), start.lookat, iso, brickWorld);
              cameras = zoomPath(start, target, brickWorld, frames);
            } else if (args->path == "jumps") {
              glm::dvec3 lo, hi;
              data.source().worldBounds(lo, hi);
              cameras = jumpsPath(start, lo, hi, frames, args->jumpEvery, args->seed);
            } else {
              cameras = recordedPath(recorded, args->frameBudgetMs * 1e-3, given("--frames") ? args->frames : 0);
            }

            StreamReport report;
            report.device = gl.renderer();
            report.file = flags.file;
            report.path = args->path;
            report.reconstruction = std::string(data.source().reconstruction().name);
            report.mode = flags.mode;
            report.width = width;
            report.height = height;
            report.frames = int(cameras.size());
            report.frameBudgetMs = args->frameBudgetMs;
            report.uploadMs = args->uploadMs;
            report.uploadFit = args->uploadFit == "on";
            report.primed = args->prime == "on" || (args->prime == "auto" && !isCpuRenderer(gl.renderer()));
            report.seed = args->seed;
            report.jumpEvery = args->jumpEvery;
            report.dataBricks = data.source().varyingBrickCount();

            const long totalFrames = long(gpuBudgets.size() * hostBudgets.size() * cameras.size());
            long framesDone = 0;
            ProgressBar progress(false);
            progress.start("streaming frames");
            const std::size_t largestGpu = *std::max_element(gpuBudgets.begin(), gpuBudgets.end());
            const std::size_t largestHost = *std::max_element(hostBudgets.begin(), hostBudgets.end());
            const auto budget = std::chrono::duration<double, std::milli>(args->frameBudgetMs);
            // A raycaster with fresh caches and the pyramid's levels opened anew: FCC data gets a host
            // cache of opts' budget (a Cartesian grid has none).
            auto freshRaycaster = [&](render::RenderOptions& opts) {
              data.closeLevels();
              data.applyLevels(flags, /*levelsByDefault=*/false, /*quiet=*/true, opts);
              return data.fccStore() ? std::make_unique<render::Raycaster>(*data.fccStore(), opts)
                                     : std::make_unique<render::Raycaster>(data.source(), opts);
            };
            if (report.primed) {
              // The NVIDIA driver runs a program it has just compiled about 5x slower until, after a
              // dozen passes of real work, an optimized build replaces it, which it also keeps in its
              // shader cache; a later program of the same source starts from that one
              // (docs/BENCHMARKS.md, sessions 16 and 17). A throwaway raycaster of the same options
              // (the same programs) steps at the path's first camera, then the driver gets time to
              // finish, so that the runs measure streaming, not the driver's first compile. Once per
              // brick layout the runs use (`--layout auto` may choose another for another GPU budget:
              // another program). Its caches go with it: every run starts with fresh ones.
              std::vector<render::BrickLayout> primedLayouts;
              for (std::size_t gpuBytes : gpuBudgets) {
                const render::BrickLayout layout =
                    options.layout ? *options.layout : render::chooseBrickLayout(data.source(), gpuBytes);
                if (std::find(primedLayouts.begin(), primedLayouts.end(), layout) != primedLayouts.end()) continue;
                primedLayouts.push_back(layout);
                render::RenderOptions primeOptions = options;
                primeOptions.layout = layout;
                primeOptions.gpuCacheBytes = gpuBytes;
                primeOptions.hostCacheBytes = hostBudgets.front();
                std::unique_ptr<render::Raycaster> throwaway = freshRaycaster(primeOptions);
                for (int i = 0; i < kPrimeSteps; ++i) throwaway->step(cameras.front(), width, height, args->uploadMs * 1e-3);
              }
              std::this_thread::sleep_for(std::chrono::milliseconds(kPrimeWaitMs));
            }
            for (std::size_t gpuBytes : gpuBudgets)
              for (std::size_t hostBytes : hostBudgets) {
                options.gpuCacheBytes = gpuBytes;
                options.hostCacheBytes = hostBytes;
                std::unique_ptr<render::Raycaster> made = freshRaycaster(options);  // fresh caches a run
                render::Raycaster& raycaster = *made;
                StreamRun run;
                run.gpuBudgetBytes = gpuBytes;
                run.hostBudgetBytes = hostBytes;
                run.layout = render::brickLayoutName(*raycaster.options().layout);
                run.slots = raycaster.slotCount();
                run.slotBytes = raycaster.slotBytes();
                double lastRest = -1.0;  // the last frame's time besides its uploads (seconds; < 0: none yet)
                for (const render::Camera& camera : cameras) {
                  const double uploadSeconds = report.uploadFit
                                                   ? render::uploadSecondsWithin(args->frameBudgetMs * 1e-3, lastRest, args->uploadMs * 1e-3)
                                                   : args->uploadMs * 1e-3;
                  const auto begin = std::chrono::steady_clock::now();
                  const render::StepStats s = raycaster.step(camera, width, height, uploadSeconds);
                  const auto end = std::chrono::steady_clock::now();
                  StreamFrame f;
                  f.ms = std::chrono::duration<double, std::milli>(end - begin).count();
                  f.uploadMs = 1e3 * s.uploadSeconds;
                  f.dispatchMs = 1e3 * s.dispatchSeconds;
                  f.passMs = 1e3 * s.passSeconds;
                  f.requestMs = 1e3 * s.requestSeconds;
                  f.gpuPassMs = 1e3 * s.gpuSeconds;
                  f.passes = s.dispatched ? 1 : 0;
                  f.restarted = s.restarted;
                  f.complete = s.complete;
                  f.requested = s.requested;
                  f.uploaded = s.uploaded;
                  f.missing = s.missing;
                  f.bytesUploaded = s.bytesUploaded;
                  f.levelMix = s.bricksPerLevel;
                  f.fullResolutionFraction = s.fullResolutionFraction;
                  f.streaming = s.streaming;
                  f.gpuBytes = raycaster.poolBytes();
                  f.gpuResidentBytes = uint64_t(raycaster.residentCount()) * raycaster.slotBytes();
                  f.hostBytes = raycaster.hostCacheUse().bytesUsed;
                  f.rssBytes = residentSetBytes();
                  lastRest = std::max(0.0, f.ms - f.uploadMs) * 1e-3;
                  run.frames.push_back(std::move(f));
                  progress.wasInterrupted(int(100 * ++framesDone / std::max(totalFrames, 1L)));
                  // The rest of the frame budget: the loader threads decode meanwhile, as behind a viewer.
                  std::this_thread::sleep_until(begin + std::chrono::duration_cast<std::chrono::steady_clock::duration>(budget));
                }
                if (gpuBytes == largestGpu && hostBytes == largestHost && report.workingSet.empty()) {
                  report.dataGpuBytes = report.dataBricks * raycaster.slotBytes();
                  report.workingSet = measureWorkingSet(raycaster, cameras, width, height);
                }
                report.runs.push_back(std::move(run));
              }
            progress.end();

            if (!stem.empty()) {
              writeStreamPlots(report, stem, args->force);
              report.plots = streamPlotPaths(stem);
            }
            if (!args->json.empty()) io::writeTextFile(args->json, streamJson(report), args->force);
            printStreamTable(report);
            if (!args->json.empty()) std::printf("json: %s\n", args->json.c_str());
            return 0;
          }};
}

}  // namespace fcc::cli
