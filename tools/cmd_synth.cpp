// fccvdb synth KIND OUTPUT.vdb: synthetic FCC datasets for tests and benchmarks.
#include <cstdio>

#include "Command.h"
#include "ProgressBar.h"
#include "Triple.h"
#include "io/VdbFile.h"
#include "sparse/BrickBounds.h"
#include "sparse/BrickKernels.h"
#include "sparse/FccBuilder.h"
#include "sparse/SynthFields.h"

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
            SynthSpec spec;
            spec.kind = args->kind;
            glm::dvec3 dims;
            parseTriple(args->dims, dims);
            spec.dims = glm::ivec3(dims);
            spec.seed = args->seed;
            const SynthField synth = makeSynthField(spec);
            const std::unique_ptr<BrickKernels> kernels = preprocessKernels(args->device);
            initializeVdb();
            ProgressBar progress(args->quiet);
            BuildOptions build;
            build.prefilter = !args->noPrefilter;
            BuildResult built = buildFccGrid(*synth.field, build, &progress);
            auto xform = openvdb::math::Transform::createLinearTransform();
            const glm::dvec3 s = synth.worldFromIndexScale, o = synth.worldFromIndexOrigin;
            xform->preScale(openvdb::Vec3d(s.x, s.y, s.z));
            xform->postTranslate(openvdb::Vec3d(o.x, o.y, o.z));
            built.grid->setTransform(xform);
            built.grid->setName(args->kind);
            FccProvenance p;
            p.coefficients = build.prefilter;
            p.mode = "synth:" + args->kind;
            p.sampleMin = built.sampleMin;
            p.sampleMax = built.sampleMax;
            p.levelSet = synth.levelSet;
            setFccMetadata(*built.grid, p);
            built.grid->setSaveFloatAsHalf(args->half);
            // Bounds of the spline the renderer evaluates: of the prefiltered coefficients for samples.
            const BoundsGrid::Ptr bounds = computeBrickBounds(*coefficientsOf(valuesAsStored(built.grid), kernels.get()), kernels.get());
            io::writeVdbAtomically(args->output, openvdb::GridCPtrVec{built.grid, bounds}, args->force);
            if (!args->quiet)
              std::fprintf(stderr, "wrote %s: %s, %llu active samples in %llu bricks; bounds: %llu varying bricks (%s)\n",
                           args->output.c_str(), args->kind.c_str(), (unsigned long long)built.grid->activeVoxelCount() * 4,
                           (unsigned long long)built.grid->tree().leafCount(),
                           (unsigned long long)bounds->activeVoxelCount(), kernels->describe().c_str());
            return 0;
          }};
}

}  // namespace fcc::cli
