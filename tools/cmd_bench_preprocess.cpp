// fccvdb bench preprocess FILE.vdb: the two preprocessing stages (prefilter, bounds) on every OpenCL
// device and on the C++/TBB reference path, with warm-up and repetitions.
//
// Timed per repetition: the whole stage as convert runs it (prefilterGrid / computeBrickBounds:
// choosing the bricks, staging leaves and neighbour tables, transfers, the kernels, assembling the VDB
// grid) -> `seconds`; and the compute step alone (the kernel launches up to their completion; for the
// reference path its per-brick work) -> `kernel_seconds`. Medians over the repetitions. Samples are
// 4 x the active packed voxels of the stage's input grid; `bricks` is how many bricks the stage
// computed (leaves, their neighbours, tile borders) in one repetition.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "Command.h"
#include "JsonText.h"
#include "Median.h"
#include "io/VdbFile.h"
#include "kernels/ClBrickKernels.h"
#include "sparse/BrickBounds.h"
#include "sparse/BrickKernels.h"
#include "sparse/Error.h"

namespace fcc::cli {
namespace {

struct Measurement {
  std::string stage, device;
  uint64_t samples = 0, bricks = 0;
  double seconds = 0.0, kernelSeconds = 0.0;
  int repetitions = 0;
};

template <class Stage>
Measurement measure(const std::string& stageName, BrickKernels& kernels, uint64_t samples, int warmup, int repetitions,
                    Stage&& stage) {
  for (int i = 0; i < warmup; ++i) stage();
  std::vector<double> seconds, kernelSeconds;
  for (int i = 0; i < repetitions; ++i) {
    kernels.computeSeconds = 0.0;
    kernels.bricksDone = 0;
    const auto start = std::chrono::steady_clock::now();
    stage();
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    kernelSeconds.push_back(kernels.computeSeconds);
  }
  return {stageName, kernels.describe(), samples, kernels.bricksDone, median(seconds), median(kernelSeconds), repetitions};
}

double rate(uint64_t samples, double seconds) { return seconds > 0.0 ? double(samples) / seconds : 0.0; }

}  // namespace

Command addBenchPreprocessCommand(CLI::App& bench) {
  struct Args {
    std::string file, grid, device;
    bool json = false;
    int repetitions = 5, warmup = 1;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = bench.add_subcommand("preprocess", "Time the prefilter and the brick bounds on each OpenCL device and on the C++/TBB reference path (samples per second)");
  app->add_option("FILE", args->file, "FCC .vdb file (fccvdb convert / synth)")->required();
  app->add_option("--grid", args->grid, "The FCC grid (default: the first)");
  addDeviceOption(*app, args->device)->description(std::string("Only this device (default: every OpenCL device, then the reference path): ") + kDeviceSelectorHelp);
  app->add_option("--repetitions", args->repetitions, "Timed runs per stage and device (the median is reported)")->check(CLI::Range(1, 1000))->capture_default_str();
  app->add_option("--warmup", args->warmup, "Untimed runs first")->check(CLI::Range(0, 100))->capture_default_str();
  app->add_flag("--json", args->json, "A JSON list of {stage, device, samples, bricks, seconds, samples_per_second, kernel_seconds, kernel_only_samples_per_second, repetitions}");
  return {app, [args]() {
            const FccGrid::Ptr grid = io::readFccGrid(args->file, args->grid);
            std::vector<std::unique_ptr<BrickKernels>> devices;
            if (!args->device.empty()) {
              devices.push_back(makeBrickKernels(args->device));
            } else {
              try {
                for (const ClDeviceEntry& e : ClRunner::devices()) {
                  try {
                    devices.push_back(std::make_unique<ClBrickKernels>(std::to_string(e.index)));
                  } catch (const ClError& err) {
                    std::fprintf(stderr, "fccvdb: skipping OpenCL device %s: %s\n", e.describe().c_str(),
                                 std::string(err.what()).substr(0, std::string(err.what()).find('\n')).c_str());
                  }
                }
              } catch (const ClError& err) {
                std::fprintf(stderr, "fccvdb: OpenCL unavailable (%s): timing the CPU reference path only\n", err.what());
              }
              devices.push_back(makeReferenceBrickKernels());
            }
            // The prefilter's input is the stored values (samples or, for a coefficients grid, the same
            // work on its coefficients); the bounds' input is the coefficients.
            const FccGrid::ConstPtr coefficients = coefficientsOf(grid);
            const uint64_t samples = grid->activeVoxelCount() * 4, coefficientSamples = coefficients->activeVoxelCount() * 4;
            std::vector<Measurement> results;
            for (auto& kernels : devices) {
              BrickKernels* k = kernels.get();
              results.push_back(measure("prefilter", *k, samples, args->warmup, args->repetitions,
                                        [&] { (void)prefilterGrid(*grid, k); }));
              results.push_back(measure("bounds", *k, coefficientSamples, args->warmup, args->repetitions,
                                        [&] { (void)computeBrickBounds(*coefficients, k); }));
              if (!args->json)
                for (size_t i = results.size() - 2; i < results.size(); ++i) {
                  const Measurement& m = results[i];
                  std::printf("%-9s %-60s %8.2f M samples/s (%.4f s for %llu bricks; compute only %.2f M samples/s)\n",
                              m.stage.c_str(), m.device.c_str(), rate(m.samples, m.seconds) / 1e6, m.seconds,
                              (unsigned long long)m.bricks, rate(m.samples, m.kernelSeconds) / 1e6);
                  std::fflush(stdout);
                }
            }
            if (args->json) {
              std::printf("[");
              for (size_t i = 0; i < results.size(); ++i) {
                const Measurement& m = results[i];
                std::printf("%s\n  {\"stage\": %s, \"device\": %s, \"samples\": %llu, \"bricks\": %llu, \"seconds\": %.6g, "
                            "\"samples_per_second\": %.6g, \"kernel_seconds\": %.6g, \"kernel_only_samples_per_second\": %.6g, "
                            "\"repetitions\": %d}",
                            i ? "," : "", jsonString(m.stage).c_str(), jsonString(m.device).c_str(),
                            (unsigned long long)m.samples, (unsigned long long)m.bricks, m.seconds, rate(m.samples, m.seconds), m.kernelSeconds,
                            rate(m.samples, m.kernelSeconds), m.repetitions);
              }
              std::printf("\n]\n");
            }
            return 0;
          }};
}

}  // namespace fcc::cli
