// fccvdb view FILE: the interactive viewer (GLFW window, Dear ImGui panel) over the brick-paged
// renderer, streaming bricks progressively; --screenshot OUT --frames N for automation.
#include <cstdio>

#include "Command.h"
#include "RenderFlags.h"
#include "io/Convert.h"
#include "sparse/Error.h"
#include "viewer/CameraFile.h"
#include "viewer/DatasetSummary.h"
#include "viewer/ViewerWindow.h"

namespace fcc::cli {
Command addViewCommand(CLI::App& parent) {
  struct Args {
    RenderFlags flags;
    std::string screenshot;
    int frames = 30;
    bool convert = false, force = false;
  };
  auto args = std::make_shared<Args>();
  args->flags.res = "1280x800";
  CLI::App* app = parent.add_subcommand(
      "view", "Interactive viewer: orbit/pan/zoom, isovalue and shading panel, live streaming statistics (H for help)");
  addRenderFlags(*app, args->flags);
  app->get_option("--res")->description("Window size WxH");
  app->add_option("--screenshot", args->screenshot,
                  "Automation: after --frames frames, once streaming has settled, write OUT (.png: the window with "
                  "its panel; .exr: the image's R,G,B,A,Z,N.X,N.Y,N.Z) and exit");
  app->add_option("--frames", args->frames, "Frames before --screenshot is taken")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  app->add_flag("--force", args->force, "Overwrite an existing --screenshot file");
  // Cartesian inputs are converted (and cached) without being asked now; the flag stays for old scripts.
  app->add_flag("--convert", args->convert, "Accepted for old scripts: Cartesian inputs are always converted")->group("");
  return {app, [args]() {
            int width = 0, height = 0;
            resolutionFromFlags(args->flags.res, width, height);
            if (!args->screenshot.empty()) checkOutputWritable(args->screenshot, args->force);
            // A bad camera file is one line before any window opens (it is read again for the camera).
            if (!args->flags.camera.empty()) render::readCameraFile(args->flags.camera);

            const std::unique_ptr<io::FccInput> input = openFccInput(args->flags, false);
            const auto store = std::make_unique<io::BrickStore>(input->path(), args->flags.grid);
            const float iso = isoFromFlags(args->flags, *store).value;
            warnIfIsoOutside(iso, *store);
            render::RenderOptions options = renderOptionsFromFlags(args->flags);
            options.iso = iso;

            render::WindowOptions windowOptions;
            windowOptions.width = width;
            windowOptions.height = height;
            windowOptions.title = "fccvdb — " + args->flags.file;
            windowOptions.screenshot = args->screenshot;
            windowOptions.frames = args->frames;
            render::ViewerWindow window(windowOptions);
            const render::Camera camera = cameraFromFlags(args->flags, *store, window.aspect());
            render::ViewerSession session(*store, options, camera, render::summarizeDataset(*store));
            const auto print = [](const std::string& line) { std::printf("%s\n", line.c_str()); };
            session.setReport(print);
            window.run(session);
            return 0;
          }};
}

}  // namespace fcc::cli
