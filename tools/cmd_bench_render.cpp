// fccvdb bench render FILE.vdb: frames per second of the raycaster over an orbit of the camera, with
// and without empty-space skipping, analytic and finite-difference normals; the time to the first
// complete frame from cold caches and the bricks streamed per second meanwhile.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "BenchOrbit.h"
#include "Command.h"
#include "JsonText.h"
#include "RenderFlags.h"
#include "viewer/EglContext.h"

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
};

Measurement measureOrbit(render::Raycaster& raycaster, const render::Camera& camera, int width, int height,
                         int warmup, int frames, double arc) {
  Measurement m;
  for (int i = 0; i < warmup; ++i) raycaster.render(orbitStep(camera, i, std::max(warmup, 1), arc), width, height);
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) {
    const render::FrameStats s = raycaster.render(orbitStep(camera, i, frames, arc), width, height);
    m.uploads += s.bricksUploaded;
    m.passes += s.passes;
    m.gpuSeconds += s.gpuSeconds;
  }
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  m.frames = frames;
  return m;
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
  app->add_option("--frames", args->frames, "Timed frames per variant (one orbit)")->capture_default_str()->check(CLI::PositiveNumber);
  app->add_option("--warmup", args->warmup, "Untimed frames before each variant (the same arc)")->capture_default_str()->check(CLI::NonNegativeNumber);
  app->add_option("--arc", args->arc,
                  "Degrees the orbit turns through (360: a full turn; less: a user's drag, whose bricks a pool can hold)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 3600.0));
  app->add_option("--work-group", args->workGroup, "Pixels per raycasting work group WxH (tuning)")->capture_default_str();
  app->add_option("--variants", args->variants, "Variants to time (default: all four)")
      ->check(CLI::IsMember({"skip+analytic", "skip+fd", "noskip+analytic", "noskip+fd"}));
  args->flags.layout = "all";
  app->get_option("--layout")->description("Brick layout to time, or all (the default)");
  app->add_flag("--gpu-time", args->gpuTime, "Also time the raycasting passes on the GPU (timestamp queries)");
  app->add_flag("--json", args->json, "A JSON list of objects: variant, skip, normals, fps, frame_ms, ...");
  return {app, [args]() {
            int width = 0, height = 0;
            resolutionFromFlags(args->flags.res, width, height);
            const std::unique_ptr<io::FccInput> input = openFccInput(args->flags, false);
            const io::BrickStore store(input->path(), args->flags.grid);
            const float iso = isoFromFlags(args->flags, store);
            const render::Camera camera = cameraFromFlags(args->flags, store, double(width) / height);
            const EglContext gl;
            // --layout all: every layout in turn, each with fresh caches.
            std::vector<render::BrickLayout> layouts = render::allBrickLayouts();
            RenderFlags flags = args->flags;
            if (flags.layout == "all") flags.layout = render::brickLayoutName(layouts.front());
            else layouts = {render::parseBrickLayout(flags.layout)};
            render::RenderOptions options = renderOptionsFromFlags(flags);
            options.iso = iso;
            options.timeGpu = args->gpuTime;
            resolutionFromFlags(args->workGroup, options.workGroup.x, options.workGroup.y, "--work-group");

            std::vector<Measurement> results;
            render::FrameStats cold;
            double poolMiB = 0.0;
            uint32_t slotCount = 0;
            for (const render::BrickLayout layout : layouts) {
              options.layout = layout;
              // Cold: a fresh pool and host cache, one complete frame (reported for the first layout).
              render::Raycaster raycaster(store, options);
              const render::FrameStats c = raycaster.render(camera, width, height);
              if (layout == layouts.front()) {
                cold = c;
                poolMiB = double(raycaster.poolBytes()) / (1 << 20);
                slotCount = raycaster.slotCount();
              }
              for (const bool skip : {true, false})
                for (const bool fd : {false, true}) {
                  const std::string variant = std::string(skip ? "skip" : "noskip") + "+" + (fd ? "fd" : "analytic");
                  if (std::find(args->variants.begin(), args->variants.end(), variant) == args->variants.end()) continue;
                  raycaster.setSkipEmpty(skip);
                  raycaster.setFiniteDifferenceNormals(fd);
                  Measurement m = measureOrbit(raycaster, camera, width, height, args->warmup, args->frames, args->arc);
                  m.layout = render::brickLayoutName(layout);
                  m.skip = skip;
                  m.normals = fd ? "finite-difference" : "analytic";
                  m.variant = variant;
                  results.push_back(m);
                }
            }

            if (args->json) {
              std::printf("[");
              for (std::size_t i = 0; i < results.size(); ++i) {
                const Measurement& m = results[i];
                std::printf("%s\n {\"variant\": %s, \"layout\": %s, \"skip\": %s, \"normals\": %s, "
                            "\"res\": [%d, %d], \"arc_degrees\": %s, \"iso\": %s, \"frames\": %d, \"fps\": %s, \"frame_ms\": %s, "
                            "\"gpu_frame_ms\": %s, \"passes_per_frame\": %s, \"bricks_streamed_per_second\": %s, "
                            "\"first_frame_seconds\": %s, \"first_frame_bricks\": %llu, \"pool_mib\": %s, "
                            "\"device\": %s, \"file\": %s}",
                            i ? "," : "", jsonString(m.variant).c_str(), jsonString(m.layout).c_str(), m.skip ? "true" : "false",
                            jsonString(m.normals).c_str(), width, height, jsonNumber(args->arc).c_str(), jsonNumber(iso).c_str(), m.frames,
                            jsonNumber(m.frames / m.seconds).c_str(), jsonNumber(1e3 * m.seconds / m.frames).c_str(),
                            args->gpuTime ? jsonNumber(1e3 * m.gpuSeconds / m.frames).c_str() : "null",
                            jsonNumber(double(m.passes) / m.frames).c_str(), jsonNumber(m.uploads / m.seconds).c_str(),
                            jsonNumber(cold.seconds).c_str(), (unsigned long long)cold.bricksUploaded,
                            jsonNumber(poolMiB).c_str(), jsonString(gl.renderer()).c_str(),
                            jsonString(args->flags.file).c_str());
              }
              std::printf("\n]\n");
              return 0;
            }
            std::printf("device: %s\nfile:   %s, iso %g, %dx%d, pool %.0f MiB (%u slots), orbit %g degrees\n",
                        gl.renderer().c_str(), args->flags.file.c_str(), double(iso), width, height, poolMiB, slotCount,
                        args->arc);
            std::printf("first complete frame (cold caches, %s): %.3f s, %llu bricks streamed (%.0f bricks/s), %d passes\n",
                        render::brickLayoutName(layouts.front()).c_str(), cold.seconds, (unsigned long long)cold.bricksUploaded, cold.bricksUploaded / cold.seconds,
                        cold.passes);
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
