// fccvdb bench view FILE.vdb: the viewer's frame time (raycaster step, image, ImGui panel) over a
// camera orbit, drawn offscreen through EGL, against the raycaster's own complete frames (as `bench
// render` times them) on the same orbit: the "within 10% of bench render" figure, on a GPU
// machine without a display.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "BenchOrbit.h"
#include "Command.h"
#include "JsonText.h"
#include "Median.h"
#include "RenderFlags.h"
#include "SurfaceFlags.h"
#include "sparse/Error.h"
#include "viewer/DatasetSummary.h"
#include "viewer/EglContext.h"
#include "viewer/GpuTimer.h"
#include "viewer/HeadlessViewer.h"
#include "viewer/Presenter.h"
#include "viewer/ViewerSession.h"

namespace fcc::cli {
namespace {

using render::HeadlessImGui;
using render::OffscreenTarget;

struct ViewTiming {
  double ms = 0.0;
  int completeFrames = 0;
  // --gpu-time: per frame on the GPU, the raycasting pass and the session's whole frame (pass,
  // uploads, image, ImGui's draw lists, and the GPU's idle time while the CPU works on it).
  double passGpuMs = 0.0, sessionGpuMs = 0.0;
};

// GPU intervals around the parts of a viewer frame (--gpu-time); null: not timed.
struct FrameTimers {
  GpuInterval session;
};

// The offscreen target keeps what was drawn into it, as a window's back buffer of age 1 would;
// kBufferAgeUnknown times a window that cannot tell (the whole image drawn every frame).
constexpr int kBufferAgeKept = 1, kBufferAgeUnknown = 0;

// How a frame ends. kSwap: as a buffer swap with vsync off, which submits the frame and lets the CPU
// start the next while the GPU finishes this one (the session itself waits for each raycasting pass,
// so the GPU never runs more than one frame behind). kFinish: glFinish after every frame, as if the
// CPU waited for each frame to be on screen; stricter than any swap.
enum class FrameEnd { kSwap, kFinish };

// One viewer frame at `camera` into the offscreen target.
void viewerFrame(render::ViewerSession& session, const OffscreenTarget& target, const render::Camera& camera, int width,
                 int height, int bufferAge, FrameEnd end, FrameTimers* timers = nullptr) {
  session.setCamera(camera);
  HeadlessImGui::newFrame();
  target.bind();
  if (timers) timers->session.begin();
  session.frame(width, height, height, bufferAge);
  if (timers) timers->session.end();
  if (end == FrameEnd::kFinish) glFinish();
  else glFlush();
}

// Warm-up as `render()` warms up: every orbit position drawn until streaming has settled, so the
// timed orbit finds its bricks resident, as the render timing does.
void settleOrbit(render::ViewerSession& session, const OffscreenTarget& target, const render::Camera& camera,
                 int width, int height, int frames) {
  constexpr int kMaxFramesPerView = 10000;  // a view that never settles is a bug, not a slow disk
  for (int i = 0; i < frames; ++i) {
    int n = 0;
    do viewerFrame(session, target, orbitStep(camera, i, frames), width, height, kBufferAgeKept, FrameEnd::kFinish);
    while (!session.settled() && ++n < kMaxFramesPerView);
    if (!session.settled()) throw Error("bench view: a view did not settle in " + std::to_string(kMaxFramesPerView) + " frames");
  }
}

ViewTiming timeViewer(render::ViewerSession& session, const OffscreenTarget& target, const render::Camera& camera,
                      int width, int height, int frames, int bufferAge, FrameEnd end, bool gpuTime) {
  ViewTiming t;
  std::unique_ptr<FrameTimers> timers = gpuTime ? std::make_unique<FrameTimers>() : nullptr;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) {
    viewerFrame(session, target, orbitStep(camera, i, frames), width, height, bufferAge, end, timers.get());
    t.completeFrames += session.stats().complete;
    if (timers) {
      t.passGpuMs += session.stats().passGpuMs / frames;
      t.sessionGpuMs += 1e3 * timers->session.seconds() / frames;
    }
  }
  glFinish();  // the last frame on screen
  t.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / frames;
  return t;
}

std::string listed(const std::vector<double>& values) {
  std::string out;
  char text[32];
  for (double v : values) {
    std::snprintf(text, sizeof text, "%s%.3f", out.empty() ? "" : " ", v);
    out += text;
  }
  return out;
}

// The image drawn over the background alone, the same image each time.
struct PresentTiming {
  double ms = 0.0, gpuMs = 0.0;
};

PresentTiming timePresent(const render::Raycaster& raycaster, const OffscreenTarget& target, int width, int height,
                          int frames) {
  render::Presenter presenter;
  GpuInterval timer;
  target.bind();
  PresentTiming t;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) {
    timer.begin();
    presenter.draw(raycaster.colorTexture(), glm::vec3(0.1f));
    timer.end();
    glFinish();
    t.gpuMs += 1e3 * timer.seconds() / frames;
  }
  t.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / frames;
  return t;
}

struct RenderTiming {
  double ms = 0.0, gpuMs = 0.0;  // gpuMs: the passes alone (RenderOptions::timeGpu)
};

RenderTiming timeRender(render::Raycaster& raycaster, const render::Camera& camera, int width, int height, int frames) {
  RenderTiming t;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i)
    t.gpuMs += 1e3 * raycaster.render(orbitStep(camera, i, frames), width, height).gpuSeconds / frames;
  t.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / frames;
  return t;
}

}  // namespace

Command addBenchViewCommand(CLI::App& bench) {
  struct Args {
    RenderFlags flags;
    int frames = 120;
    int rounds = 3;
    bool json = false;
    bool gpuTime = false;
  };
  auto args = std::make_shared<Args>();
  args->flags.res = "1920x1080";
  CLI::App* app = bench.add_subcommand(
      "view", "The viewer's frame time with and without its panel against complete raycaster frames (offscreen)");
  addRenderFlags(*app, args->flags);
  app->add_option("--frames", args->frames, "Timed frames per variant (one orbit)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_option("--rounds", args->rounds, "Rounds of timings; each figure is the median over them")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_flag("--gpu-time", args->gpuTime,
                "Also time the parts of a frame on the GPU (timestamp queries; adds a little to the frame times)");
  app->add_flag("--json", args->json, "One JSON object: render_ms, view_panel_ms, view_no_panel_ms, ratio, ...");
  return {app, [args]() {
            if (!args->flags.lodBias.empty())
              throw ValueError("--lod-bias " + args->flags.lodBias +
                               ": bench view times full resolution only (bench render --lod-bias times the levels)");
            int width = 0, height = 0;
            resolutionFromFlags(args->flags.res, width, height);
            const std::unique_ptr<io::FccInput> input = openFccInput(args->flags, false);
            const io::BrickStore store(input->path(), args->flags.grid);
            render::RenderOptions options = renderOptionsFromFlags(args->flags);
            // Every surface of --iso's list, with --surface-color and --surface-opacity.
            const std::vector<render::Isosurface> surfaces = surfacesFromFlags(args->flags, isoFromFlags(args->flags, store));
            for (const render::Isosurface& s : surfaces) warnIfIsoOutside(s.iso, store);
            setSurfaces(options, surfaces);
            options.timeGpu = args->gpuTime;
            const render::Camera camera = cameraFromFlags(args->flags, store, double(width) / height);
            const EglContext gl;
            const OffscreenTarget target(width, height);
            const HeadlessImGui imgui(width, height);

            // Warm caches first (one orbit each), then the same orbit timed several ways, in rounds
            // that alternate render and viewer: on the H200 one orbit's time varies by up to 8% from
            // run to run, so each figure is the median over the rounds, and so is each ratio.
            render::Raycaster raycaster(store, options);
            timeRender(raycaster, camera, width, height, args->frames);
            const PresentTiming present = timePresent(raycaster, target, width, height, args->frames);
            const double presentMs = present.ms;
            render::ViewerSession session(store, options, camera, render::summarizeDataset(store));
            settleOrbit(session, target, camera, width, height, args->frames);

            std::vector<double> renderRounds, panelRounds, finishRounds, wholeRounds, ratioRounds, finishRatioRounds;
            RenderTiming renderTiming;
            ViewTiming withPanel, finishing, wholeImage;
            for (int round = 0; round < args->rounds; ++round) {
              renderTiming = timeRender(raycaster, camera, width, height, args->frames);
              withPanel = timeViewer(session, target, camera, width, height, args->frames, kBufferAgeKept,
                                     FrameEnd::kSwap, args->gpuTime);
              finishing = timeViewer(session, target, camera, width, height, args->frames, kBufferAgeKept,
                                     FrameEnd::kFinish, args->gpuTime);
              wholeImage = timeViewer(session, target, camera, width, height, args->frames, kBufferAgeUnknown,
                                      FrameEnd::kSwap, args->gpuTime);
              renderRounds.push_back(renderTiming.ms);
              panelRounds.push_back(withPanel.ms);
              finishRounds.push_back(finishing.ms);
              wholeRounds.push_back(wholeImage.ms);
              ratioRounds.push_back(withPanel.ms / renderTiming.ms);
              finishRatioRounds.push_back(finishing.ms / renderTiming.ms);
            }
            const double renderMs = median(renderRounds);
            withPanel.ms = median(panelRounds);
            finishing.ms = median(finishRounds);
            wholeImage.ms = median(wholeRounds);
            session.settings().showPanel = false;
            // The columns the panel covered need rays (and maybe bricks) now: settle them too.
            settleOrbit(session, target, camera, width, height, args->frames);
            const ViewTiming noPanel = timeViewer(session, target, camera, width, height, args->frames, kBufferAgeKept,
                                                  FrameEnd::kSwap, args->gpuTime);

            const double ratio = median(ratioRounds), ratioFinish = median(finishRatioRounds);
            if (args->json) {
              std::printf("{\"device\": %s, \"file\": %s, \"res\": [%d, %d], \"frames\": %d, \"render_ms\": %s, "
                          "\"view_panel_ms\": %s, \"view_panel_finish_ms\": %s, \"view_panel_whole_image_ms\": %s, "
                          "\"view_no_panel_ms\": %s, \"present_ms\": %s, \"ratio\": %s, \"ratio_finish\": %s, "
                          "\"complete_frames_panel\": %d, \"complete_frames_no_panel\": %d}\n",
                          jsonString(gl.renderer()).c_str(), jsonString(args->flags.file).c_str(), width, height,
                          args->frames, jsonNumber(renderMs).c_str(), jsonNumber(withPanel.ms).c_str(),
                          jsonNumber(finishing.ms).c_str(), jsonNumber(wholeImage.ms).c_str(), jsonNumber(noPanel.ms).c_str(),
                          jsonNumber(presentMs).c_str(), jsonNumber(ratio).c_str(), jsonNumber(ratioFinish).c_str(),
                          withPanel.completeFrames, noPanel.completeFrames);
              return 0;
            }
            std::printf("device: %s\nfile:   %s, %dx%d, %d frames per orbit; medians of %d rounds (ratios %s)\n",
                        gl.renderer().c_str(), args->flags.file.c_str(), width, height, args->frames, args->rounds,
                        listed(ratioRounds).c_str());
            std::printf("render (complete frames):  %8.3f ms\n", renderMs);
            std::printf("viewer with panel:         %8.3f ms (%d of %d frames complete), %.3f x render\n",
                        withPanel.ms, withPanel.completeFrames, args->frames, ratio);
            std::printf("  the same, glFinish after every frame: %8.3f ms, %.3f x render\n", finishing.ms, ratioFinish);
            std::printf("  the same, the whole image drawn every frame (buffer age unknown): %.3f ms, %.3f x render\n",
                        wholeImage.ms, wholeImage.ms / renderMs);
            std::printf("viewer without panel:      %8.3f ms (%d of %d frames complete)\n", noPanel.ms,
                        noPanel.completeFrames, args->frames);
            std::printf("drawing the image alone:   %8.3f ms\n", presentMs);
            if (args->gpuTime) {
              std::printf("on the GPU: render passes %.3f ms; image %.3f ms; viewer with panel: pass %.3f, whole "
                          "frame %.3f ms; drawing the whole image: whole frame %.3f ms; without panel: pass %.3f, "
                          "whole frame %.3f ms\n",
                          renderTiming.gpuMs, present.gpuMs, withPanel.passGpuMs, withPanel.sessionGpuMs,
                          wholeImage.sessionGpuMs, noPanel.passGpuMs, noPanel.sessionGpuMs);
            }
            return 0;
          }};
}

}  // namespace fcc::cli
