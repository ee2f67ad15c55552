// fccvdb bench render FILE.vdb: frames per second of the raycaster over an orbit of the camera, with
// and without empty-space skipping, analytic and finite-difference normals; the time to the first
// complete frame from cold caches and the bricks streamed per second meanwhile.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "BenchOrbit.h"
#include "Command.h"
#include "CpuRenderer.h"
#include "JsonText.h"
#include "ProgressBar.h"
#include "RenderData.h"
#include "RenderFlags.h"
#include "SurfaceFlags.h"
#include "sparse/Error.h"
#include "viewer/EglContext.h"
#ifdef FCC_MPI
#include "mpi/DistributedRender.h"
#include "mpi/MpiSession.h"
#endif

namespace fcc::cli {
namespace {

struct Measurement {
  std::string layout, variant, normals;
  bool skip = true;
  int frames = 0;
  double seconds = 0.0;
  uint64_t uploads = 0;
  int passes = 0;
  double gpuSeconds = 0.0;  // --gpu-time
  std::vector<uint64_t> bricksPerLevel;  // summed over the timed frames (level of detail)
  double fullResolutionFraction = 0.0;   // mean over the timed frames
  double lodBias = 0.0;                  // at the last frame
};

// Calls `tick` after every frame it renders (the progress bar). Renderer: the raycaster, or projected
// tetrahedra (anything whose render() gives FrameStats).
template <class Renderer>
Measurement measureOrbit(Renderer& raycaster, const render::Camera& camera, int width, int height,
                         int warmup, int frames, double arc, const std::function<void()>& tick) {
  Measurement m;
  for (int i = 0; i < warmup; ++i) {
    raycaster.render(orbitStep(camera, i, std::max(warmup, 1), arc), width, height);
    tick();
  }
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) {
    const render::FrameStats s = raycaster.render(orbitStep(camera, i, frames, arc), width, height);
    m.uploads += s.bricksUploaded;
    m.passes += s.passes;
    m.gpuSeconds += s.gpuSeconds;
    if (m.bricksPerLevel.size() < s.bricksPerLevel.size()) m.bricksPerLevel.resize(s.bricksPerLevel.size());
    for (std::size_t k = 0; k < s.bricksPerLevel.size(); ++k) m.bricksPerLevel[k] += s.bricksPerLevel[k];
    m.fullResolutionFraction += s.fullResolutionFraction / frames;
    m.lodBias = s.lodBias;
    tick();
  }
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.frames = frames;
  return m;
}

// "n0, n1, ...": bricks per level, level 0 first.
std::string levelMixList(const std::vector<uint64_t>& bricksPerLevel) {
  std::string list;
  for (std::size_t k = 0; k < bricksPerLevel.size(); ++k) list += (k ? ", " : "") + std::to_string(bricksPerLevel[k]);
  return list;
}

// What a CPU renderer times unless told otherwise: about a second a frame for llvmpipe on two cores.
constexpr int kCpuFrames = 8, kCpuWarmup = 1;
constexpr const char* kCpuRes = "128x128";

// The frame's shading: null for DVR without gradient shading; else its light ("headlight",
// "directional" with light_in_camera, the direction towards it in camera space, or "kit") and, for DVR,
// the highlight's strength and power.
std::string shadingJson(const render::RenderOptions& o) {
  const bool dvr = o.mode == render::RenderMode::Dvr;
  if (dvr && !o.dvrShading.on) return "null";
  // The isosurface's light is lightInCamera always (--light headlight sets it to the view axis).
  const render::DvrLight light = dvr ? o.dvrShading.light : render::DvrLight::Directional;
  std::string s = "{\"light\": " + jsonString(render::dvrLightName(light));
  if (light == render::DvrLight::Directional)
    s += ", \"light_in_camera\": [" + jsonNumber(o.lightInCamera.x) + ", " + jsonNumber(o.lightInCamera.y) + ", " +
         jsonNumber(o.lightInCamera.z) + "]";
  if (dvr)
    s += ", \"specular\": " + jsonNumber(o.dvrShading.specular) + ", \"specular_power\": " + jsonNumber(o.dvrShading.specularPower);
  return s + "}";
}

}  // namespace

Command addBenchRenderCommand(CLI::App& bench) {
  struct Args {
    RenderFlags flags;
    int frames = 60, warmup = 5;
    double arc = 360.0;
    std::string workGroup = "4x8";
    std::vector<std::string> variants = {"skip+analytic", "skip+fd", "noskip+analytic", "noskip+fd"};
    bool json = false;
    bool gpuTime = false;
  };
  auto args = std::make_shared<Args>();
  args->flags.res = "512x512";
  CLI::App* app = bench.add_subcommand("render", "Frames per second over a camera orbit (skipping on/off, analytic/finite-difference normals)");
  addRenderFlags(*app, args->flags);
  app->get_option("--res")->capture_default_str();  // 512x512 here
  app->add_option("--frames", args->frames, "Timed frames per variant (one orbit)")->capture_default_str()->check(CLI::PositiveNumber);
  app->add_option("--warmup", args->warmup, "Untimed frames before each variant (the same arc)")->capture_default_str()->check(CLI::NonNegativeNumber);
  app->add_option("--arc", args->arc,
                  "Degrees the orbit turns through (360: a full turn; less: a user's drag, whose bricks a pool can hold)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 3600.0));
  app->add_option("--work-group", args->workGroup, "Pixels per raycasting work group WxH (tuning)")->capture_default_str();
  app->add_option("--variants", args->variants, "Variants to time, separated by spaces or commas (default: all four)")
      ->delimiter(',')
      ->check(CLI::IsMember({"skip+analytic", "skip+fd", "noskip+analytic", "noskip+fd"}));
  args->flags.layout = "all";
  std::string layouts;
  for (render::BrickLayout l : render::allBrickLayouts()) layouts += ", " + render::brickLayoutName(l);
  app->get_option("--layout")
      ->description("Brick layout to time: all (each in turn, with fresh caches), auto (the one render chooses)" + layouts)
      ->capture_default_str();
  app->add_flag("--gpu-time", args->gpuTime, "Also time the raycasting passes on the GPU (timestamp queries)");
  app->add_flag("--json", args->json,
                "A JSON list of objects: variant, skip, normals, fps, frame_ms, ... (under mpirun: one object, per rank "
                "mean render, wait and compositing seconds, bytes exchanged; docs/MPI.md)");
  return {app, [args, app]() {
#ifdef FCC_MPI
            // Started by mpirun with more than one rank: the orbit rendered sort-last over the ranks
            // (docs/MPI.md), skip+analytic only, the layout render chooses; fewer frames unless asked.
            if (mpi::world().distributed()) {
              RenderFlags flags = args->flags;
              if (flags.layout == "all") flags.layout = "auto";
              const auto given = [&](const char* flag) { return app->get_option(flag)->count() > 0; };
              if (!given("--res")) flags.res = kCpuRes;
              return mpi::benchRenderDistributed(flags, given("--frames") ? args->frames : kCpuFrames,
                                                 given("--warmup") ? args->warmup : kCpuWarmup, args->arc, args->json);
            }
#endif
            if (args->flags.layout != "all" && args->flags.layout != "auto") {
              try {
                render::parseBrickLayout(args->flags.layout);
              } catch (const ValueError& e) {
                throw ValueError("--layout: " + std::string(e.what()) + ", auto or all");
              }
            }
            const EglContext gl;
            // A CPU renderer takes minutes over the defaults: time less, unless the user chose, and say so.
            if (isCpuRenderer(gl.renderer())) {
              std::string scaled;
              auto unless = [&](const char* flag, const std::function<void()> apply, const std::string& now) {
                if (app->get_option(flag)->count() > 0) return;
                apply();
                scaled += (scaled.empty() ? "" : ", ") + std::string(flag) + " " + now;
              };
              unless("--layout", [&] { args->flags.layout = "auto"; }, "auto");
              unless("--frames", [&] { args->frames = kCpuFrames; }, std::to_string(kCpuFrames));
              unless("--warmup", [&] { args->warmup = kCpuWarmup; }, std::to_string(kCpuWarmup));
              unless("--res", [&] { args->flags.res = kCpuRes; }, kCpuRes);
              if (!scaled.empty())
                std::fprintf(stderr,
                             "fccvdb: warning: %s renders on the CPU: timing %s instead of the defaults (give the flags "
                             "to choose); its figures say nothing about a GPU\n",
                             gl.renderer().c_str(), scaled.c_str());
            }
            int width = 0, height = 0;
            resolutionFromFlags(args->flags.res, width, height);
            // --layout all: every layout in turn, each with fresh caches; auto: the renderer's choice.
            // First: the options below are parsed from `flags`, where "all" is no layout.
            std::vector<std::optional<render::BrickLayout>> layouts;
            RenderFlags flags = args->flags;
            if (flags.layout == "all") {
              for (render::BrickLayout l : render::allBrickLayouts()) layouts.push_back(l);
              flags.layout = "auto";
            } else {
              layouts.push_back(renderOptionsFromFlags(flags).layout);  // nullopt for auto
            }
            RenderData data(args->flags, renderOptionsFromFlags(flags).hostCacheBytes, false);
            const float iso = data.iso(args->flags).value;
            if (render::parseRenderMode(args->flags.mode) == render::RenderMode::Iso) data.warnIfIsoOutside(iso);
            const render::Camera camera = data.camera(args->flags, double(width) / height);
            render::RenderOptions options = renderOptionsFromFlags(flags);
            options.iso = iso;
            data.applyMode(args->flags, options);  // --mode dvr: the transfer function
            // Level of detail only with --lod-bias; full resolution reads no level mix per timed frame.
            const bool lod = data.applyLevels(args->flags, /*levelsByDefault=*/false, false, options) > 1;
            if (options.mode == render::RenderMode::Iso)  // several surfaces: --iso's list, their colours and opacities
              setSurfaces(options, surfacesFromFlags(args->flags, io::IsoChoice{iso, "--iso"}));
            options.timeGpu = args->gpuTime;
            options.countBricksDrawn = true;  // the first frame's level mix (timed frames: with levels only)
            resolutionFromFlags(args->workGroup, options.workGroup.x, options.workGroup.y, "--work-group");

            // Frames to render: per layout one cold frame, then warm-up and timed frames per variant.
            const long totalFrames = args->flags.dvrMethod == "tetrahedra"
                                         ? 1 + long(args->warmup + args->frames)
                                         : long(layouts.size()) * (1 + long(args->variants.size()) * (args->warmup + args->frames));
            long framesDone = 0;
            ProgressBar progress(false);
            progress.start("timing frames");
            auto tick = [&] { progress.wasInterrupted(int(100 * ++framesDone / std::max(totalFrames, 1L))); };

            std::vector<Measurement> results;
            render::FrameStats cold;
            std::string coldLayout;
            double poolMiB = 0.0;
            uint32_t slotCount = 0;
            // --dvr-method tetrahedra: paper 002's projected tetrahedra, one measurement (no pool, no
            // variants); "first complete frame" includes building them.
            if (args->flags.dvrMethod == "tetrahedra") {
              layouts.clear();
              const auto built = std::chrono::steady_clock::now();
              const std::unique_ptr<render::ProjectedTetrahedra> tetrahedra = data.projectedTetrahedra(args->flags, options);
              cold = tetrahedra->render(camera, width, height);
              cold.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count();
              tick();
              coldLayout = "in core: " + std::to_string(tetrahedra->tetrahedronCount()) + " tetrahedra";
              Measurement m = measureOrbit(*tetrahedra, camera, width, height, args->warmup, args->frames, args->arc, tick);
              m.layout = "tetrahedra";
              m.variant = "projected";
              m.skip = true;
              m.normals = "analytic";
              results.push_back(m);
            }
            for (const std::optional<render::BrickLayout>& layout : layouts) {
              options.layout = layout;
              // Cold: a fresh pool and host cache, one complete frame (reported for the first layout).
              // FCC data gets a fresh host cache per layout; a Cartesian grid has none.
              std::unique_ptr<render::Raycaster> made = data.fccStore() ? std::make_unique<render::Raycaster>(*data.fccStore(), options)
                                                                        : std::make_unique<render::Raycaster>(data.source(), options);
              render::Raycaster& raycaster = *made;
              const render::FrameStats c = raycaster.render(camera, width, height);
              tick();
              raycaster.setCountBricksDrawn(lod);
              const std::string layoutName = render::brickLayoutName(*raycaster.options().layout);
              if (coldLayout.empty()) {
                cold = c;
                coldLayout = layoutName;
                poolMiB = double(raycaster.poolBytes()) / (1 << 20);
                slotCount = raycaster.slotCount();
              }
              for (const bool skip : {true, false})
                for (const bool fd : {false, true}) {
                  const std::string variant = std::string(skip ? "skip" : "noskip") + "+" + (fd ? "fd" : "analytic");
                  if (std::find(args->variants.begin(), args->variants.end(), variant) == args->variants.end()) continue;
                  raycaster.setSkipEmpty(skip);
                  raycaster.setFiniteDifferenceNormals(fd);
                  Measurement m = measureOrbit(raycaster, camera, width, height, args->warmup, args->frames, args->arc, tick);
                  m.layout = layoutName;
                  m.skip = skip;
                  m.normals = fd ? "finite-difference" : "analytic";
                  m.variant = variant;
                  results.push_back(m);
                }
            }
            progress.end();

            if (args->json) {
              std::printf("[");
              for (std::size_t i = 0; i < results.size(); ++i) {
                const Measurement& m = results[i];
                std::printf("%s\n {\"variant\": %s, \"layout\": %s, \"skip\": %s, \"normals\": %s, "
                            "\"res\": [%d, %d], \"arc_degrees\": %s, \"iso\": %s, \"frames\": %d, \"fps\": %s, \"frame_ms\": %s, "
                            "\"gpu_frame_ms\": %s, \"passes_per_frame\": %s, \"bricks_streamed_per_second\": %s, "
                            "\"first_frame_seconds\": %s, \"first_frame_bricks\": %llu, \"pool_mib\": %s, "
                            "\"device\": %s, \"file\": %s, \"reconstruction\": %s, \"mode\": %s, \"tf\": %s, "
                            "\"level_mix\": [%s], \"full_resolution_fraction\": %s, \"lod_bias\": %s, \"shading\": %s}",
                            i ? "," : "", jsonString(m.variant).c_str(), jsonString(m.layout).c_str(), m.skip ? "true" : "false",
                            jsonString(m.normals).c_str(), width, height, jsonNumber(args->arc).c_str(), jsonNumber(iso).c_str(), m.frames,
                            jsonNumber(m.frames / m.seconds).c_str(), jsonNumber(1e3 * m.seconds / m.frames).c_str(),
                            args->gpuTime ? jsonNumber(1e3 * m.gpuSeconds / m.frames).c_str() : "null",
                            jsonNumber(double(m.passes) / m.frames).c_str(), jsonNumber(m.uploads / m.seconds).c_str(),
                            jsonNumber(cold.seconds).c_str(), (unsigned long long)cold.bricksUploaded,
                            jsonNumber(poolMiB).c_str(), jsonString(gl.renderer()).c_str(),
                            jsonString(args->flags.file).c_str(), jsonString(std::string(data.source().reconstruction().name)).c_str(),
                            jsonString(args->flags.mode).c_str(),
                            options.mode == render::RenderMode::Dvr ? jsonString(args->flags.tf).c_str() : "null",
                            levelMixList(lod ? m.bricksPerLevel : cold.bricksPerLevel).c_str(),
                            jsonNumber(lod ? m.fullResolutionFraction : 1.0).c_str(), jsonNumber(m.lodBias).c_str(),
                            shadingJson(options).c_str());
              }
              std::printf("\n]\n");
              return 0;
            }
            const std::string what = options.mode == render::RenderMode::Dvr ? "dvr, --tf " + args->flags.tf
                                                                              : "iso " + std::to_string(iso);
            std::printf("device: %s\nfile:   %s, %s, %s, %dx%d, pool %.0f MiB (%u slots), orbit %g degrees\n",
                        gl.renderer().c_str(), args->flags.file.c_str(), std::string(data.source().reconstruction().name).c_str(),
                        what.c_str(), width, height, poolMiB, slotCount, args->arc);
            std::printf("first complete frame (cold caches, %s): %.3f s, %llu bricks streamed (%.0f bricks/s), %d passes\n",
                        coldLayout.c_str(), cold.seconds, (unsigned long long)cold.bricksUploaded, cold.bricksUploaded / cold.seconds,
                        cold.passes);
            if (lod && !results.empty()) {
              const Measurement& m = results.back();
              std::printf("levels (last variant, bricks drawn over its timed frames): %s; %.1f%% of the surface pixels at full "
                          "resolution; bias %g\n",
                          levelMixList(m.bricksPerLevel).c_str(), 100.0 * m.fullResolutionFraction, m.lodBias);
            }
            std::printf("%-16s %-18s %10s %10s %10s %8s %14s\n", "layout", "variant", "fps", "frame ms", "gpu ms", "passes",
                        "bricks/s");
            for (const Measurement& m : results) {
              char gpuMs[32] = "-";
              if (args->gpuTime) std::snprintf(gpuMs, sizeof gpuMs, "%.3f", 1e3 * m.gpuSeconds / m.frames);
              std::printf("%-16s %-18s %10.1f %10.3f %10s %8.2f %14.0f\n", m.layout.c_str(), m.variant.c_str(),
                          m.frames / m.seconds, 1e3 * m.seconds / m.frames, gpuMs, double(m.passes) / m.frames,
                          m.uploads / m.seconds);
            }
            return 0;
          }};
}

}  // namespace fcc::cli
