// fccvdb pyramid FILE [-o OUT]: adds the level-of-detail pyramid to an FCC file (io/FccPyramid.h), in
// place by default: the rewrite is atomic (a temporary file renamed over FILE) and keeps level 0's
// values as they are, so it needs no --force; with -o, FILE is left alone and OUT follows the usual
// output policy.
#include "Command.h"
#include "ProgressBar.h"
#include "PyramidReport.h"
#include "io/FccPyramid.h"
#include "sparse/BrickKernels.h"

namespace fcc::cli {

Command addPyramidCommand(CLI::App& parent) {
  struct Args {
    std::string file, device = "auto";
    io::PyramidOptions options;
    bool quiet = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = parent.add_subcommand(
      "pyramid",
      "Add a level-of-detail pyramid to an FCC .vdb: level k is an FCC grid of spacing 2^k (the spline of level k-1 "
      "sampled at its sites, then prefiltered) with its own bounds grid, down to a level of at most 8 bricks; "
      "built streamed in bounded memory. FILE is rewritten atomically (level 0 unchanged), an existing pyramid replaced");
  app->add_option("FILE", args->file, "FCC .vdb file (spline coefficients, as convert and synth write)")->required();
  app->add_option("-o,--output", args->options.output, "Write the file with its pyramid here instead of rewriting FILE");
  app->add_flag("--force", args->options.overwrite, "With --output: overwrite an existing OUT");
  app->add_flag("--quiet", args->quiet, "No progress bar or summary");
  addDeviceOption(*app, args->device);
  return {app, [args]() {
            const std::unique_ptr<BrickKernels> kernels = preprocessKernels(args->device);
            args->options.kernels = kernels.get();
            ProgressBar progress(args->quiet);
            const io::PyramidSummary s = io::addPyramid(args->file, args->options, &progress);
            if (!args->quiet)
              printPyramidSummary(args->options.output.empty() ? args->file : args->options.output, s);
            return 0;
          }};
}

}  // namespace fcc::cli
