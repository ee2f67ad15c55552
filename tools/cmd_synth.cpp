// fccvdb synth KIND OUTPUT.vdb [--lattice fcc|cc|bcc]: synthetic datasets for tests and benchmarks: an
// FCC grid (the default), or the same field as a Cartesian float grid (--lattice cc) or a BCC dataset's
// two cosets (--lattice bcc) to compare the reconstructions at equal sample counts.
#include <cstdio>

#include "Command.h"
#include "ProgressBar.h"
#include "PyramidReport.h"
#include "Triple.h"
#include "io/FccPyramid.h"
#include "io/SynthFile.h"
#include "sparse/BrickKernels.h"
#include "sparse/Error.h"

namespace fcc::cli {

Command addSynthCommand(CLI::App& parent) {
  struct Args {
    std::string kind, output, dims, device = "auto", lattice = "fcc";
    uint64_t seed = 1;
    bool force = false, quiet = false, half = false, noPrefilter = false, pyramid = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = parent.add_subcommand(
      "synth",
      "Write a synthetic dataset: sphere (quadratic field, exact spherical isosurfaces), marschner-lobb (over [-1,1]^3), "
      "blobs (sparse smooth random blobs); an FCC grid, or with --lattice cc the same field as a Cartesian float grid, "
      "with --lattice bcc as a BCC dataset. Equal samples: FCC with --dims D holds D^3/2 sites; CC with as many "
      "samples has D / 2^(1/3) points per axis, BCC 2^(1/3) D (e.g. FCC --dims 256,256,256, CC --dims 203,203,203 and "
      "BCC --dims 323,323,323: 8.4 M samples each)");
  app->add_option("KIND", args->kind, "sphere | marschner-lobb | blobs")->required()->check(CLI::IsMember(synthKinds()));
  app->add_option("OUTPUT", args->output, "Output .vdb")->required();
  app->add_option("--dims", args->dims,
                  "Cartesian embedding size X,Y,Z: the grid's points (fcc: the lattice holds the half of them with an even "
                  "coordinate sum; cc: every point is a sample)")
      ->required()->check(tripleValidator("--dims"));
  app->add_option("--lattice", args->lattice,
                  "fcc: an FCC grid with its bounds (streamed, bounded memory); cc: a Cartesian FloatGrid fog volume over "
                  "the same world box as fcc with the same --dims, for `render --reconstruction trilinear|tricubic|type6|"
                  "tricubic-bspline` (built in memory: 4 bytes a point); bcc: the BCC sites of the same points (all "
                  "coordinates even or all odd: a quarter of them) as the grids bcc_primary and bcc_secondary, for "
                  "`render` with barycentric, sheared-trilinear, bilinear-spatial or bilinear (in memory)")
      ->capture_default_str()->check(CLI::IsMember({"fcc", "cc", "bcc"}));
  app->add_option("--seed", args->seed, "Random seed (blobs)")->capture_default_str();
  app->add_flag("--half", args->half, "Store values as 16-bit floats");
  app->add_flag("--no-prefilter", args->noPrefilter, "Store raw samples instead of spline coefficients (fcc only)");
  app->add_flag("--pyramid", args->pyramid,
                "Then add the level-of-detail pyramid (as `fccvdb pyramid OUTPUT`; fcc only, with the prefilter)");
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
            if (args->pyramid && (args->lattice != "fcc" || args->noPrefilter))
              throw ValueError("--pyramid: the pyramid is built from the spline coefficients of an FCC grid; drop " +
                               (args->lattice != "fcc" ? "--lattice " + args->lattice : std::string("--no-prefilter")));
            if (args->lattice != "fcc") {
              const bool cc = args->lattice == "cc";
              if (args->noPrefilter)
                throw ValueError(std::string("--no-prefilter: a ") + (cc ? "Cartesian grid" : "BCC dataset") +
                                 " always stores the samples" + (cc ? " (the renderer prefilters for tricubic)" : ""));
              const io::SynthSummary summary =
                  cc ? io::writeSynthCartesianFile(args->output, options) : io::writeSynthBccFile(args->output, options);
              if (!args->quiet)
                std::fprintf(stderr, "wrote %s: %s, %s of %llu samples in %llu leaves\n", args->output.c_str(),
                             args->kind.c_str(), cc ? "a Cartesian float grid" : "a BCC dataset (two coset grids)",
                             (unsigned long long)summary.activeSamples, (unsigned long long)summary.bricks);
              return 0;
            }
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
            if (args->pyramid) {
              io::PyramidOptions pyramid;  // in place: OUTPUT is ours, just written
              pyramid.kernels = kernels.get();
              const io::PyramidSummary p = io::addPyramid(args->output, pyramid, &progress);
              if (!args->quiet) printPyramidSummary(args->output, p);
            }
            return 0;
          }};
}

}  // namespace fcc::cli
