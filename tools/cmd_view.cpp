// fccvdb view FILE: the interactive viewer (GLFW window, Dear ImGui panel) over the brick-paged
// renderer, streaming bricks progressively; --screenshot OUT --frames N for automation.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "Command.h"
#include "RenderData.h"
#include "RenderFlags.h"
#include "SurfaceFlags.h"
#include "io/AtomicOutput.h"
#include "io/Convert.h"
#include "io/PatientMetadata.h"
#include "sparse/Error.h"
#include "viewer/CameraFile.h"
#include "viewer/CameraPath.h"
#include "viewer/DatasetSummary.h"
#include "viewer/OpenAnotherFile.h"
#include "viewer/ViewerWindow.h"

namespace fcc::cli {
namespace {

// One file open in the viewer (tools/RenderData.h): an FCC .vdb (itself, or a Cartesian input's
// cached or temporary conversion), or with a Cartesian --reconstruction a Cartesian .vdb as it is.
struct Dataset {
  RenderFlags flags;  // what it was opened with (the camera and termination opacity read them)
  std::unique_ptr<RenderData> data;
  float iso = 0.0f;
  std::vector<render::Isosurface> surfaces;  // --iso's list with their colours and opacities (isosurface mode)
  std::optional<render::DvrTransfer> dvr;  // --mode dvr
};

Dataset openDataset(const RenderFlags& flags, std::size_t hostCacheBytes) {
  if (flags.dvrMethod != "ray")
    throw ValueError("--dvr-method " + flags.dvrMethod + ": the viewer draws with the raycaster (render and bench render take it)");
  Dataset d;
  d.flags = flags;
  d.data = std::make_unique<RenderData>(flags, hostCacheBytes, false);
  if (render::parseRenderMode(flags.mode) == render::RenderMode::Dvr) {
    render::RenderOptions options;
    d.data->applyMode(flags, options);  // the warnings `render` gives
    d.dvr = d.data->dvrTransfer(flags);
  } else {
    const io::IsoChoice choice = d.data->iso(flags);
    d.iso = choice.value;
    d.surfaces = surfacesFromFlags(flags, choice);
    for (const render::Isosurface& s : d.surfaces) d.data->warnIfIsoOutside(s.iso);
  }
  // Damaged patient axes refuse the file here, while a file opened from the window can still be
  // refused in a notice (the camera reads them).
  if (const io::BrickStore* store = d.data->fccStore()) io::patientAxesOf(store->index(), store->path());
  return d;
}

// The Cartesian grid `current` shows, with another reconstruction (the panel's choice): its store is
// shared (nothing read again); the view and the look are the session's, carried over
// (runOpeningFiles). ValueError (one line) for FCC data or a reconstruction of another lattice.
Dataset reopenDataset(const Dataset& current, const std::string& reconstruction) {
  Dataset d;
  d.flags = current.flags;
  d.flags.reconstruction = reconstruction;
  d.data = std::make_unique<RenderData>(*current.data, reconstruction);
  d.iso = current.iso;
  d.surfaces = current.surfaces;
  d.dvr = current.dvr;
  return d;
}

// The flags for a file opened from the window: the budgets and layout stay; what belonged to the
// first file (its grid, isovalue, camera, raw layout) goes, so the new one gets its own defaults.
RenderFlags flagsForAnotherFile(const RenderFlags& first, const std::string& path) {
  RenderFlags f;
  f.file = path;
  f.res = first.res;
  f.gpuCacheMiB = first.gpuCacheMiB;
  f.hostCacheMiB = first.hostCacheMiB;
  f.layout = first.layout;
  f.noCache = first.noCache;
  // The look stays too: the mode, the transfer function and a Cartesian reconstruction.
  f.reconstruction = first.reconstruction;
  f.mode = first.mode;
  f.tf = first.tf;
  f.unitDistance = first.unitDistance;
  f.densityScale = first.densityScale;
  f.terminationOpacity = first.terminationOpacity;
  f.lodBias = first.lodBias;
  f.fullResolution = first.fullResolution;
  f.shading = first.shading;
  f.specular = first.specular;
  f.specularPower = first.specularPower;
  f.light = first.light;
  return f;
}

}  // namespace

Command addViewCommand(CLI::App& parent) {
  struct Args {
    RenderFlags flags;
    std::string screenshot;
    std::string recordPath;
    int frames = 30;
    bool convert = false, force = false;
  };
  auto args = std::make_shared<Args>();
  args->flags.res = "1280x800";
  CLI::App* app = parent.add_subcommand(
      "view", "Interactive viewer: orbit/pan/zoom, isovalue or transfer function and shading panel, live streaming statistics (H for help)");
  addRenderFlags(*app, args->flags, /*levelsByDefault=*/true);
  app->get_option("--res")->description("Window size WxH");
  app->add_option("--screenshot", args->screenshot,
                  "Automation: after --frames frames, once streaming has settled, write OUT (.png: the window with "
                  "its panel; .exr: the image's R,G,B,A,Z,N.X,N.Y,N.Z) and exit");
  app->add_option("--frames", args->frames, "Frames before --screenshot is taken")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_option("--record-path", args->recordPath,
                  "Record the camera of every frame drawn of FILE into PATH.json (written on exit; a camera path: "
                  "`fccvdb bench stream FILE --path PATH.json` replays it, docs/VIEWER.md)");
  app->add_flag("--force", args->force, "Overwrite an existing --screenshot or --record-path file");
  // Cartesian inputs are converted (and cached) without being asked now; the flag stays for old scripts.
  app->add_flag("--convert", args->convert, "Accepted for old scripts: Cartesian inputs are always converted")->group("");
  return {app, [args]() {
            int width = 0, height = 0;
            resolutionFromFlags(args->flags.res, width, height);
            if (!args->screenshot.empty()) checkOutputWritable(args->screenshot, args->force);
            if (!args->recordPath.empty()) io::checkOutputPath(args->recordPath, args->force);
            // A bad camera file is one line before any window opens (it is read again for the camera).
            if (!args->flags.camera.empty()) render::readCameraFile(args->flags.camera);

            // No display: say so before a Cartesian input is converted (minutes for a large one).
            render::ViewerWindow::requireDisplay();
            const render::RenderOptions budgets = renderOptionsFromFlags(args->flags);
            Dataset data = openDataset(args->flags, budgets.hostCacheBytes);
            render::WindowOptions windowOptions;
            windowOptions.width = width;
            windowOptions.height = height;
            windowOptions.title = "fccvdb — " + args->flags.file;
            windowOptions.screenshot = args->screenshot;
            windowOptions.frames = args->frames;
            render::ViewerWindow window(windowOptions);
            const auto print = [](const std::string& line) { std::printf("%s\n", line.c_str()); };
            auto newSession = [&](const Dataset& d) {
              const RenderFlags& flags = d.flags;
              render::RenderOptions options = budgets;
              options.iso = d.iso;
              if (!d.surfaces.empty()) setSurfaces(options, d.surfaces);
              options.terminationOpacity = float(flags.terminationOpacity);
              // A pyramid's levels at bias 0 (or --lod-bias) unless --full-resolution: coarse bricks
              // stand in while finer ones stream, and the view converges to the full-resolution image
              // where every brick wants level 0.
              if (!d.dvr) d.data->applyLevels(flags, /*levelsByDefault=*/true, false, options);
              options.dvrShading.on = flags.shading == "on";
              options.dvrShading.specular = float(flags.specular);
              options.dvrShading.specularPower = float(flags.specularPower);
              const io::BrickStore* store = d.data->fccStore();
              auto session = std::make_unique<render::ViewerSession>(
                  d.data->source(), store, options, d.data->camera(flags, window.aspect()),
                  store ? render::summarizeDataset(*store) : render::summarizeSource(d.data->source()), d.dvr);
              session->setReport(print);
              return session;
            };
            std::unique_ptr<render::ViewerSession> session = newSession(data);
            // --record-path: the first file's frames (a file opened from the window ends the recording:
            // a path belongs to the data it was recorded over; another reconstruction of it goes on).
            render::CameraPathRecorder recorder(args->flags.file);
            if (!args->recordPath.empty()) session->recordPath(&recorder);
            // Another file dropped on the window or typed after O replaces the dataset; the window,
            // budgets and layout stay. One that does not open leaves the old one, and says why. The
            // panel's reconstruction replaces the source over the same store, keeping the view.
            render::runOpeningFiles(
                data, session, [&](render::ViewerSession& s) { return window.run(s); },
                [&](const std::string& path) {
                  return openDataset(flagsForAnotherFile(args->flags, path), budgets.hostCacheBytes);
                },
                [&](const std::string& reconstruction) { return reopenDataset(data, reconstruction); },
                newSession,
                [&](const render::OpenRequest& request) {
                  if (!request.path.empty()) {
                    window.setTitle("fccvdb — " + request.path);
                    print("opened " + request.path);
                  } else {
                    print(data.flags.file + ": reconstruction " + request.reconstruction);
                  }
                });
            if (!args->recordPath.empty()) {
              if (recorder.path().points.empty()) throw Error("--record-path " + args->recordPath + ": no frame was drawn, nothing recorded");
              render::writeCameraPathFile(args->recordPath, recorder.path(), args->force);
              print("camera path of " + std::to_string(recorder.path().points.size()) + " frames written to " + args->recordPath);
            }
            return 0;
          }};
}

}  // namespace fcc::cli
