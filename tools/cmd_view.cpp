// fccvdb view FILE.vdb: the interactive viewer (GLFW window, Dear ImGui panel) over the brick-paged
// renderer, streaming bricks progressively; --screenshot OUT --frames N for automation.
#include <stdlib.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "Command.h"
#include "RenderFlags.h"
#include "io/Convert.h"
#include "sparse/Error.h"
#include "viewer/DatasetSummary.h"
#include "viewer/ViewerWindow.h"

namespace fcc::cli {
namespace {

// An FCC copy of a Cartesian input in the temporary directory (never beside the user's file),
// removed when the viewer exits.
class TemporaryFccCopy {
 public:
  explicit TemporaryFccCopy(const std::string& input) {
    std::string pattern = (std::filesystem::temp_directory_path() / "fccvdb-view-XXXXXX.vdb").string();
    const int fd = ::mkstemps(pattern.data(), 4);
    if (fd < 0) throw OutputError(pattern + ": cannot create a temporary file for the FCC copy");
    ::close(fd);
    path_ = pattern;
    io::ConvertOptions options;
    options.overwrite = true;  // the empty file mkstemps made
    std::fprintf(stderr, "converting %s to a temporary FCC file %s\n", input.c_str(), path_.c_str());
    try {
      io::convertToFcc(input, path_, options);
    } catch (...) {
      std::filesystem::remove(path_);
      throw;
    }
  }
  ~TemporaryFccCopy() {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace

Command addViewCommand(CLI::App& parent) {
  struct Args {
    RenderFlags flags;
    std::string screenshot;
    int frames = 30;
    bool convert = false;
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
  app->add_flag("--convert", args->convert,
                "Given a Cartesian volume (.vdb float grid, NRRD, NIfTI), view a temporary FCC copy of it");
  return {app, [args]() {
            int width = 0, height = 0;
            resolutionFromFlags(args->flags.res, width, height);
            if (!args->screenshot.empty()) checkOutputWritable(args->screenshot);

            std::unique_ptr<TemporaryFccCopy> copy;
            std::unique_ptr<io::BrickStore> store;
            try {
              store = std::make_unique<io::BrickStore>(args->flags.file, args->flags.grid);
            } catch (const InputError& e) {
              if (!args->convert)
                throw InputError(std::string(e.what()) + "; or view a temporary FCC copy: fccvdb view " +
                                 args->flags.file + " --convert");
              copy = std::make_unique<TemporaryFccCopy>(args->flags.file);
              store = std::make_unique<io::BrickStore>(copy->path(), "");
            }
            const float iso = isoFromFlags(args->flags, *store);
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
            window.run(session, [](const std::string& line) { std::printf("%s\n", line.c_str()); });
            return 0;
          }};
}

}  // namespace fcc::cli
