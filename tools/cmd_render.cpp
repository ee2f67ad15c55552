// fccvdb render FILE OUT.(exr|png) (or -o OUT): one headless frame of the isosurface (FILE: an FCC
// .vdb, or any input convert takes, converted once into the cache; or with --reconstruction trilinear,
// tricubic, tricubic-bspline or type6 a Cartesian .vdb rendered as it is).
#include <chrono>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "Command.h"
#include "RenderData.h"
#include "RenderFlags.h"
#include "SurfaceFlags.h"
#include "RenderJson.h"
#include "io/ImageOutput.h"
#include "sparse/Error.h"
#include "viewer/EglContext.h"
#ifdef FCC_MPI
#include "mpi/DistributedRender.h"
#include "mpi/MpiSession.h"
#endif

namespace fcc::cli {
namespace {

// "levels: L0 120 bricks, L1 30, L2 4; 87.5% of the surface pixels at full resolution; bias 1": the frame's mix.
std::string levelMixLine(const render::FrameStats& stats, bool dvr) {
  std::string line = "levels:";
  for (std::size_t k = 0; k < stats.bricksPerLevel.size(); ++k)
    line += (k ? ", L" : " L") + std::to_string(k) + " " + std::to_string(stats.bricksPerLevel[k]) + (k ? "" : " bricks");
  char tail[160];
  std::snprintf(tail, sizeof tail, "; %.1f%% of the %s at full resolution; bias %g%s", 100.0 * stats.fullResolutionFraction,
                dvr ? "bricks drawn" : "surface pixels",
                stats.lodBias, stats.lodRestarts ? " (raised: the GPU cache could not hold the bricks wanted)" : "");
  return line + tail;
}

std::string formatNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

Command addRenderCommand(CLI::App& parent) {
  struct Args {
    RenderFlags flags;
    std::string output, positionalOutput;
    bool quiet = false, allowDamaged = false, force = false, timings = false, json = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = parent.add_subcommand("render", "Render the isosurface headless (EGL) to EXR (R,G,B,A,Z,N.X,N.Y,N.Z) or PNG");
  addRenderFlags(*app, args->flags);
  // OUTPUT as a positional, like convert and synth; -o stays for scripts. One of them is needed.
  auto* positional = app->add_option("OUTPUT", args->positionalOutput, "Output image, .exr or .png (or -o OUTPUT)");
  auto* named = app->add_option("-o,--output", args->output, "Output image, .exr or .png (or as the second positional)");
  positional->excludes(named);
  named->excludes(positional);
  app->parse_complete_callback([args] {
    if (args->output.empty() && args->positionalOutput.empty())
      throw CLI::RequiredError("OUTPUT (the image to write, .exr or .png; or -o OUTPUT) is required",
                               int(CLI::ExitCodes::RequiredError));
  });
  app->add_flag("--force", args->force, "Overwrite an existing output image");
  app->add_flag("--quiet", args->quiet, "No summary on stderr");
  app->add_flag("--timings", args->timings, "Print where the wall time went (open, EGL, renderer set-up, frame, image) on stderr");
  app->add_flag("--json", args->json,
                "Print a JSON object on stdout: the frame and, per process (MPI rank), render, wait and compositing "
                "seconds, bytes exchanged, bricks read and owned (docs/MPI.md)");
  app->add_flag("--allow-damaged", args->allowDamaged,
                "Exit 0 although damaged bricks were met (they are never trusted: rendered as holes, and named on stderr)");
  return {app, [args]() {
            const auto start = std::chrono::steady_clock::now();
            std::vector<std::pair<const char*, double>> times;  // stage, seconds since start
            const auto mark = [&](const char* stage) {
              times.emplace_back(stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
            };
            if (args->output.empty()) args->output = args->positionalOutput;
#ifdef FCC_MPI
            // Started by mpirun with more than one rank: sort-last over the ranks (docs/MPI.md).
            if (mpi::world().distributed())
              return mpi::renderDistributed({args->flags, args->output, args->force, args->quiet, args->json, args->allowDamaged});
#endif
            int width = 0, height = 0;
            resolutionFromFlags(args->flags.res, width, height);
            checkOutputWritable(args->output, args->force);
            render::RenderOptions options = renderOptionsFromFlags(args->flags);
            RenderData data(args->flags, options.hostCacheBytes, args->quiet);
            data.applyMode(args->flags, options);
            // Level of detail only with --lod-bias: a complete frame is full resolution by default.
            const int levels = data.applyLevels(args->flags, /*levelsByDefault=*/false, args->quiet, options);
            mark("open");
            const bool dvr = options.mode == render::RenderMode::Dvr;
            const io::IsoChoice isoChoice = data.iso(args->flags);
            const float iso = isoChoice.value;
            // Several surfaces (--iso's list, --surface-color, --surface-opacity); a warning for each
            // value outside the data's range.
            const std::vector<render::Isosurface> surfaces =
                dvr ? std::vector<render::Isosurface>{} : surfacesFromFlags(args->flags, isoChoice);
            for (const render::Isosurface& s : surfaces) data.warnIfIsoOutside(s.iso);
            const render::Camera camera = data.camera(args->flags, double(width) / height);
            const EglContext gl;
            mark("egl");
            options.iso = iso;
            if (!dvr) setSurfaces(options, surfaces);
            options.countBricksDrawn = true;  // the level mix for the summary and --json (one frame)
            // --dvr-method tetrahedra: paper 002's projected tetrahedra instead of the raycaster.
            const std::unique_ptr<render::ProjectedTetrahedra> tetrahedra = data.projectedTetrahedra(args->flags, options);
            std::unique_ptr<render::Raycaster> raycaster =
                tetrahedra ? nullptr : std::make_unique<render::Raycaster>(data.source(), options);
            mark("renderer");
            const auto frameStart = std::chrono::steady_clock::now();
            const render::FrameStats stats = raycaster ? raycaster->render(camera, width, height) : tetrahedra->render(camera, width, height);
            mark("frame");
            const render::FrameImages images = raycaster ? raycaster->readImages(/*withNormalDepth=*/io::imageHoldsNormalDepth(args->output))
                                                         : tetrahedra->readImages();
            io::RenderedImage image{images.width, images.height, &images.rgba, &images.normalDepth, /*normals=*/!dvr};
            io::writeRenderedImage(args->output, image, glm::vec3(0.08f, 0.09f, 0.11f));
            mark("image");
            if (args->json) {  // one process: the same fields as a distributed frame's, nothing exchanged
              RankReport report;
              report.renderSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - frameStart).count();
              report.bricksRead = raycaster ? raycaster->bricksDecoded() : data.source().varyingBrickCount();
              report.bricksOwned = stats.bricksNeeded;
              report.bricksUploaded = stats.bricksUploaded;
              report.passes = stats.passes;
              report.device = gl.renderer() + " (" + gl.platform() + ")";
              const LevelReport levelReport{stats.bricksPerLevel, stats.fullResolutionFraction, stats.lodBias};
              std::fputs(renderJson(args->flags.file, args->output, args->flags.mode, width, height, {}, report.renderSeconds, {report},
                                    levelReport, frameLook(options, args->flags.tf))
                             .c_str(),
                         stdout);
            }
            if (args->timings) {
              std::string line = "timings (s):";
              double before = 0.0;
              for (const auto& [stage, at] : times) {
                char part[64];
                std::snprintf(part, sizeof part, " %s %.3f", stage, at - before);
                line += part;
                before = at;
              }
              std::fprintf(stderr, "%s; total %.3f\n", line.c_str(), before);
            }
            // Rays load only the bricks they reach: of those whose bounds hold the isovalue, the ones
            // hidden behind the surface or outside the view are never needed, so "N of M" read as stuck.
            const std::string isoBasis = isoChoice.basis == "--iso" ? "" : " (default: " + isoChoice.basis + ")";
            std::string isoText = "iso " + formatNumber(iso);
            if (surfaces.size() > 1 || options.surfaceOpacity < 1.0f) {
              isoText = surfaces.size() > 1 ? "isos" : "iso";
              for (std::size_t k = 0; k < surfaces.size(); ++k)
                isoText += (k ? ", " : " ") + formatNumber(surfaces[k].iso) + " (opacity " + formatNumber(surfaces[k].opacity) + ")";
            }
            if (!args->quiet && tetrahedra)
              std::fprintf(stderr,
                           "wrote %s: %dx%d, dvr by projected tetrahedra (--tf %s over %g .. %g), %zu tetrahedra with "
                           "data, %.3f s (sort %.3f s) on %s\n",
                           args->output.c_str(), width, height, args->flags.tf.c_str(), options.transfer->vmin(),
                           options.transfer->vmax(), tetrahedra->tetrahedronCount(), stats.seconds, tetrahedra->sortSeconds(),
                           gl.renderer().c_str());
            else if (!args->quiet && dvr)
              std::fprintf(stderr,
                           "wrote %s: %dx%d, dvr (--tf %s over %g .. %g), %d passes, %llu bricks loaded (the rays reached "
                           "them; %llu bricks hold non-zero opacity), %.3f s on %s\n",
                           args->output.c_str(), width, height, args->flags.tf.c_str(), options.transfer->vmin(),
                           options.transfer->vmax(), stats.passes, (unsigned long long)stats.bricksUploaded,
                           (unsigned long long)stats.bricksNeeded, stats.seconds, gl.renderer().c_str());
            else if (!args->quiet)
              std::fprintf(stderr,
                           "wrote %s: %dx%d, %s%s, %d passes, %llu bricks loaded (the rays reached them; %llu "
                           "bricks hold %s), %.3f s on %s\n",
                           args->output.c_str(), width, height, isoText.c_str(), isoBasis.c_str(),
                           stats.passes, (unsigned long long)stats.bricksUploaded,
                           (unsigned long long)stats.bricksNeeded, surfaces.size() > 1 ? "an isovalue" : "the isovalue",
                           stats.seconds, gl.renderer().c_str());
            if (!args->quiet && raycaster && raycaster->levelCount() > 1) std::fprintf(stderr, "%s\n", levelMixLine(stats, dvr).c_str());
            else if (!args->quiet && levels > 1)
              std::fprintf(stderr, "fccvdb: note: --lod-bias: several or translucent surfaces are drawn at full resolution\n");
            if (!args->quiet) std::fprintf(stderr, "camera: %s\n", cameraFlags(camera).c_str());
            // FCC bricks or Cartesian leaves, each never trusted: read as the background (io/Damage.h).
            const io::Damage damage = data.damage();
            if (damage.count > 0) {
              std::fprintf(stderr, "fccvdb: %s rendered as holes in %s (first: %s)%s\n", io::damagedCountText(damage).c_str(),
                           args->output.c_str(), damage.first.c_str(), args->allowDamaged ? "" : "; --allow-damaged to exit 0");
              if (!args->allowDamaged) return 1;
            }
            return 0;
          }};
}

}  // namespace fcc::cli
