// fccvdb synth KIND OUTPUT.vdb: synthetic FCC datasets for tests and benchmarks.
#include <cstdio>

#include "Command.h"
#include "ProgressBar.h"
#include "Triple.h"
#include "io/SynthFile.h"
#include "sparse/BrickKernels.h"

namespace fcc::cli {

Command addSynthCommand(CLI::App& parent) {
  struct Args {
    std::string kind, output, dims, device = "auto";
    uint64_t seed = 1;
    bool force = false, quiet = false, half = false, noPrefilter = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = parent.add_subcommand("synth", "Write a synthetic FCC dataset: sphere (quadratic field, exact spherical isosurfaces), marschner-lobb (over [-1,1]^3), blobs (sparse smooth random blobs)");
  app->add_option("KIND", args->kind, "sphere | marschner-lobb | blobs")->required()->check(CLI::IsMember(synthKinds()));
  app->add_option("OUTPUT", args->output, "Output .vdb")->required();
  app->add_option("--dims", args->dims, "Cartesian embedding size X,Y,Z (the FCC lattice holds half of these points)")->required()->check(tripleValidator("--dims"));
  app->add_option("--seed", args->seed, "Random seed (blobs)")->capture_default_str();
  app->add_flag("--half", args->half, "Store values as 16-bit floats");
  app->add_flag("--no-prefilter", args->noPrefilter, "Store raw samples instead of spline coefficients");
  app->add_flag("--force", args->force, "Overwrite an existing OUTPUT");
  app->add_flag("--quiet", args->quiet, "No progress bar or summary");
  addDeviceOption(*app, args->device);
  return {app, [args]() {
            io::SynthOptions options;
            options.spec.kind = args->kind;
            glm::dvec3 dims(0.0);
            parseTriple(args->dims, dims);
            options.spec.dims = glm::ivec3(dims);
            options.spec.seed = args->seed;
            options.prefilter = !args->noPrefilter;
            options.half = args->half;
            options.overwrite = args->force;
            const std::unique_ptr<BrickKernels> kernels = preprocessKernels(args->device);
            options.preprocess = kernels.get();
            ProgressBar progress(args->quiet);
            const io::SynthSummary summary = io::writeSynthFile(args->output, options, &progress);
            if (!args->quiet)
              std::fprintf(stderr,
                           "wrote %s: %s, %llu stored values in %llu bricks (4 per active packed voxel); bounds: %llu "
                           "bricks where the spline may vary (those with data and their neighbours) (%s)\n",
                           args->output.c_str(), args->kind.c_str(), (unsigned long long)summary.activeSamples,
                           (unsigned long long)summary.bricks, (unsigned long long)summary.boundsBricks,
                           kernels->describe().c_str());
            return 0;
          }};
}

}  // namespace fcc::cli
