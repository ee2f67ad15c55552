// fccvdb convert INPUT OUTPUT.vdb: Cartesian data to an FCC grid (io/Convert.h: streamed).
#include <strings.h>

#include <cstdio>

#include "Command.h"
#include "ProgressBar.h"
#include "PyramidReport.h"
#include "SourceFlags.h"
#include "io/Convert.h"
#include "io/FccPyramid.h"
#include "sparse/BrickKernels.h"
#include "sparse/Error.h"

namespace fcc::cli {
namespace {

struct ConvertArgs {
  std::string input, output, device = "auto";
  SourceFlags source;
  float background = 0.0f;
  bool quiet = false, noPrefilter = false, timings = false, pyramid = false;
  io::ConvertOptions options;
};

}  // namespace

Command addConvertCommand(CLI::App& parent) {
  auto args = std::make_shared<ConvertArgs>();
  CLI::App* app = parent.add_subcommand("convert", "Convert a Cartesian volume (.vdb float grid, raw, NRRD, NIfTI, MetaImage, DICOM series) to an FCC grid in a .vdb file, streamed in bounded memory");
  app->add_option("INPUT", args->input, "Input: .vdb (fog volume or level set), .nrrd/.nhdr, .nii/.nii.gz, .mha/.mhd, a DICOM series (its folder or one of its files), or raw (anything else; needs --dims and --type)")->required();
  app->add_option("OUTPUT", args->output, "Output .vdb (written to a temporary file, then renamed)")->required();
  app->add_option("--grid", args->options.gridName, ".vdb input: the float grid to convert (default: the first float grid)");
  addRawFlags(*app, args->source);
  app->add_option("--mode", args->options.mode, "subsample: keep the even-parity voxels (exact, half the samples); resample: reconstruct the source (tricubic B-spline) on an FCC lattice of another spacing")->check(CLI::IsMember({"subsample", "resample"}))->capture_default_str();
  app->add_option("--samples", args->options.samples, "Resample: about this many FCC samples over the source's extent");
  app->add_option("--scale", args->options.scale, "Resample: lattice spacing in source voxels (instead of --samples)")->check(CLI::PositiveNumber);
  auto* bg = app->add_option("--background", args->background, "Value outside the data and of inactive voxels (default: the .vdb's background; 0 for raw, NRRD, NIfTI)");
  app->add_flag("--no-prefilter", args->noPrefilter, "Store the raw samples instead of the prefiltered spline coefficients the renderer uses");
  app->add_option("--tolerance", args->options.tolerance, "A packed voxel whose four values are within this of the background is inactive")->check(CLI::NonNegativeNumber)->capture_default_str();
  app->add_flag("--half", args->options.half, "Store values as 16-bit floats");
  app->add_flag("--force", args->options.overwrite, "Overwrite an existing OUTPUT");
  app->add_flag("--quiet", args->quiet, "No progress bar");
  app->add_flag("--pyramid", args->pyramid,
                "Then add the level-of-detail pyramid (as `fccvdb pyramid OUTPUT`: levels of spacing 2, 4, ... down to a "
                "few bricks; blobs 512^3: +26% file size, about as long again as synth, docs/BENCHMARKS.md)");
  app->add_flag("--timings", args->timings, "Print the wall time of each stage of the conversion (one line on stderr)");
  addDeviceOption(*app, args->device);
  return {app, [args, bg]() {
            io::ConvertOptions& o = args->options;
            // Whatever the name, the output is an OpenVDB file: another extension is a slip (convert a b.png).
            const std::string& out = args->output;
            if (out.size() < 4 || strcasecmp(out.c_str() + out.size() - 4, ".vdb") != 0)
              throw ValueError("OUTPUT '" + out + "': convert writes an OpenVDB file; name it .vdb");
            o.prefilter = !args->noPrefilter;
            if (bg->count() > 0) o.background = args->background;
            o.raw = rawLayoutFromFlags(args->source, args->input);
            if (args->pyramid && args->noPrefilter)
              throw ValueError("--pyramid: the pyramid is built from spline coefficients; drop --no-prefilter");
            const std::unique_ptr<BrickKernels> kernels = preprocessKernels(args->device);
            o.preprocess = kernels.get();
            ProgressBar progress(args->quiet);
            const io::ConvertSummary s = io::convertToFcc(args->input, args->output, o, &progress);
            // Each figure says what it counts: stored values are 4 per active packed voxel (with the
            // prefilter, the coefficients reach one site beyond the data), so they are not "half the
            // input voxels"; bounds bricks include the neighbours of the bricks with data.
            if (!args->quiet)
              std::fprintf(stderr,
                           "wrote %s: grid '%s', %llu stored values in %llu bricks (4 per active packed voxel%s), from "
                           "%llu input voxels; bounds: %llu bricks where the spline may vary (those with data and "
                           "their neighbours) (%s)\n",
                           args->output.c_str(), s.gridName.c_str(), (unsigned long long)s.activeSamples,
                           (unsigned long long)s.bricks,
                           o.prefilter ? ": the coefficients of the FCC sites with data and the sites next to them" : "",
                           (unsigned long long)s.inputVoxels, (unsigned long long)s.boundsBricks,
                           kernels->describe().c_str());
            if (args->timings && !s.timings.empty()) std::fprintf(stderr, "timings: %s\n", s.timings.c_str());
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
