// fccvdb compare: the case for the FCC lattice, measured. An analytic field (or a Cartesian volume's
// interpolating spline, --input) sampled on the CC, BCC and FCC lattices at equal sample budgets, every reconstruction of the layer measured against the field
// (sparse/Comparison.h); a table, --json rows, and with -o DIR the JSON, a Markdown report and the
// convergence plot.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <thread>

#include "Command.h"
#include "JsonText.h"
#include "CompareFps.h"
#include "CompareReport.h"
#include "io/AtomicOutput.h"
#include "io/DenseVolume.h"
#include "io/ImageOutput.h"
#include "SourceFlags.h"
#include "sparse/Comparison.h"
#include "sparse/Error.h"

namespace fcc::cli {
namespace {

std::vector<int64_t> parseBudgets(const std::string& text) {
  std::vector<int64_t> budgets;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const long long v = std::strtoll(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || v < 64 || v > 2000000000LL)
      throw ValueError("--budget: '" + item + "' is not a sample count (valid: integers from 64 to 2000000000, comma-separated)");
    budgets.push_back(v);
  }
  if (budgets.empty()) throw ValueError("--budget: no sample count given (e.g. --budget 100000,1000000)");
  // In increasing order, each once (a budget named twice would write its image twice).
  std::sort(budgets.begin(), budgets.end());
  budgets.erase(std::unique(budgets.begin(), budgets.end()), budgets.end());
  return budgets;
}

// The machine, for the report: host name, CPU model and thread count.
std::string machineLine() {
  char host[256] = "?";
  gethostname(host, sizeof host - 1);
  std::string cpu = "?";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);)
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  return std::string(host) + ", " + cpu + ", " + std::to_string(std::thread::hardware_concurrency()) + " threads";
}

// The Markdown lines that show the image grids and say what their rows are.
std::string gridNote(const std::vector<CompareRow>& rows, const std::vector<int64_t>& budgets, bool rendered) {
  if (!rendered) return "";
  std::string note = "\nImage grids (left: the isosurface; right: its normal error, 0 dark blue to 20 degrees and more red, "
                     "magenta where only one of the method and the truth hits). Rows from the top: the field itself, then ";
  bool first = true;
  for (const auto& r : rows)
    if (r.budget == budgets.front()) {
      note += std::string(first ? "" : ", ") + r.lattice + " " + r.reconstruction;
      first = false;
    }
  note += ".\n";
  for (int64_t b : budgets) note += "\n![budget " + std::to_string(b) + "](compare_" + std::to_string(b) + ".png)\n";
  return note;
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// A dense Cartesian volume as the truth.
std::unique_ptr<AnalyticField> readTruth(const std::string& path, const SourceFlags& flags) {
  const io::Format format = io::detectFormat(path);
  if (format == io::Format::Vdb)
    throw ValueError(path + ": --input takes a dense volume (raw, NRRD, NIfTI, MetaImage, DICOM), not a .vdb");
  io::DenseVolume volume;
  switch (format) {
    case io::Format::Nrrd: volume = io::readNrrd(path); break;
    case io::Format::Nifti: volume = io::readNifti(path); break;
    case io::Format::Dicom: volume = io::readDicom(path); break;
    case io::Format::MetaImage: volume = io::readMetaImage(path); break;
    default: {
      const auto layout = rawLayoutFromFlags(flags, path);
      if (!layout) throw ValueError(path + ": a raw volume needs --dims X,Y,Z and --type (u8|i8|u16|i16|u32|i32|f32|f64)");
      volume = io::readRaw(path, *layout);
    }
  }
  return makeVolumeField(path, volume.dims, volume.spacing, volume.values);
}

}  // namespace

Command addCompareCommand(CLI::App& parent) {
  struct Args {
    std::string field, input, budgets, outDir, reconstructions, res = "256x256";
    SourceFlags source;
    double iso = NAN;
    int points = 20000;
    uint64_t seed = 1;
    bool json = false, force = false, noFps = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = parent.add_subcommand(
      "compare",
      "Sample an analytic field on the CC, BCC and FCC lattices at equal sample budgets and measure every "
      "reconstruction against it: value error, gradient and isosurface-normal direction error");
  auto* fieldOption = app->add_option("--field", args->field, "marschner-lobb | random-waves")->check(CLI::IsMember(analyticFieldNames()));
  auto* inputOption = app->add_option("--input", args->input,
                                      "A Cartesian volume as the truth (raw with --dims/--type, NRRD, NIfTI, MetaImage, DICOM): "
                                      "its interpolating tricubic B-spline")
                          ->check(CLI::ExistingPath);
  fieldOption->excludes(inputOption);
  addRawFlags(*app, args->source);
  app->add_option("--budget", args->budgets, "Samples inside the domain per lattice ([-1,1]^3 for --field), N[,N...] (several: a convergence plot)")->required();
  app->add_option("--iso", args->iso, "Isovalue of the surface whose normals are measured (default: the field's, 0.5 for marschner-lobb, 0 for random-waves)");
  app->add_option("--points", args->points, "Seeded random points for the errors (uniform, and on the isosurface)")
      ->capture_default_str()->check(CLI::Range(100, 10000000));
  app->add_option("--seed", args->seed, "Seed of the points (and of random-waves)")->capture_default_str();
  app->add_option("--reconstruction", args->reconstructions,
                  "Only these, comma-separated (default: all: " + reconstructionNames() + ")");
  app->add_option("--res", args->res, "Size WxH of the renders measured against the field's own render (0x0: none)")
      ->capture_default_str();
  app->add_flag("--no-fps", args->noFps,
                "Do not time the renderer (by default every row's data is rendered at --res from the renders' "
                "camera: fps = 1 / the median frame time)");
  app->add_flag("--json", args->json, "Print the rows as a JSON list instead of the table");
  app->add_option("-o,--output-dir", args->outDir,
                  "Also write compare.json, compare.md, convergence.svg and (with renders) compare_BUDGET.png into DIR");
  app->add_flag("--force", args->force, "Overwrite those files in DIR");
  return {app, [args]() {
            if (args->field.empty() == args->input.empty())
              throw ValueError("give the truth as --field (" + joined(analyticFieldNames()) + ") or --input FILE");
            const auto field = args->input.empty() ? makeAnalyticField(args->field, args->seed) : readTruth(args->input, args->source);
            const std::string truthName = args->input.empty() ? args->field : args->input;
            CompareOptions options;
            options.budgets = parseBudgets(args->budgets);
            options.iso = std::isfinite(args->iso) ? args->iso : field->defaultIso();
            options.points = args->points;
            options.seed = args->seed;
            int width = 0, height = 0;
            char x = 0, extra = 0;
            if (std::sscanf(args->res.c_str(), "%d%c%d%c", &width, &x, &height, &extra) != 3 || x != 'x' || width < 0 ||
                height < 0 || width > 2048 || height > 2048 || (width == 0) != (height == 0))
              throw ValueError("--res: '" + args->res + "' is not WxH (valid: e.g. 256x256, up to 2048x2048; 0x0 for no renders)");
            options.width = width;
            options.height = height;
            std::stringstream names(args->reconstructions);
            for (std::string n; std::getline(names, n, ',');)
              if (!n.empty()) options.reconstructions.push_back(n);
            // The outputs are checked before the work: a folder that is not there, or files there without
            // --force, fail now, not after minutes.
            std::vector<std::string> outputs;
            if (!args->outDir.empty()) {
              for (const char* f : {"compare.json", "compare.md", "convergence.svg"}) outputs.push_back(args->outDir + "/" + f);
              if (width > 0)
                for (int64_t b : options.budgets) outputs.push_back(args->outDir + "/compare_" + std::to_string(b) + ".png");
              for (const auto& path : outputs) io::checkOutputPath(path, args->force);
            }
            options.keepImages = !args->outDir.empty();  // the images are only for the grids
            RgbImage truth;
            std::vector<CompareRow> rows = compareReconstructions(*field, options, &truth);
            if (rows.empty()) throw ValueError("--reconstruction: nothing to compare");
            // The frame rates, after the measurements have freed their samples.
            const FpsReport fps =
                args->noFps ? FpsReport{false, "", "fps: not timed (--no-fps)"} : timeCompareRows(*field, options, rows);
            // The command as run (its effective flags), the seed and the machine: what a reader needs to
            // measure the same.
            std::string command = "fccvdb compare " + (args->input.empty() ? "--field " + args->field : "--input " + args->input) +
                                  " --budget " + args->budgets + " --iso " + jsonNumber(options.iso) + " --points " +
                                  std::to_string(options.points) + " --seed " + std::to_string(options.seed) + " --res " + args->res;
            if (!args->reconstructions.empty()) command += " --reconstruction " + args->reconstructions;
            if (args->noFps) command += " --no-fps";
            char settings[1024];
            std::snprintf(settings, sizeof settings,
                          "%d uniform points and %d on the isosurface; the stack schemes' planes normal to z there, "
                          "from the view in the renders; renders %dx%d against the truth's own (img_norm: mean normal "
                          "error in degrees, img_depth: mean hit distance error, img_hm: pixels where only one hits)",
                          options.points, rows.front().surfacePoints, width, height);
            const std::string header = command + "\n" + settings + "\n" + fps.line + "\nmachine: " + machineLine() + "\n";
            const std::string table = compareTable(rows);
            if (args->json) std::fputs(compareJson(rows).c_str(), stdout);
            else std::printf("%s%s", header.c_str(), table.c_str());
            if (!args->outDir.empty()) {
              const std::string dir = args->outDir + "/";
              io::writeTextFile(dir + "compare.json", compareJson(rows), args->force);
              io::writeTextFile(dir + "compare.md", "# fccvdb compare\n\n```\n" + header + "\n" + table + "```\n\n![convergence](convergence.svg)\n" + gridNote(rows, options.budgets, width > 0), args->force);
              io::writeTextFile(dir + "convergence.svg",
                        convergenceSvg(rows, truthName + ": value RMS error against samples"), args->force);
              if (width > 0) {
                for (int64_t budget : options.budgets) {
                  const RgbImage grid = imageGrid(truth, rows, budget);
                  const std::string path = dir + "compare_" + std::to_string(budget) + ".png";
                  io::checkOutputPath(path, args->force);
                  io::writeScreenPng(path, grid.width, grid.height, grid.rgb);
                }
              }
            }
            return 0;
          }};
}

}  // namespace fcc::cli
