// fccvdb bench SUBCOMMAND: benchmarks as programs (docs/BENCHMARKS.md). Each benchmark lives in its own
// tools/cmd_bench_*.cpp and registers itself on the `bench` app here.
#include "Command.h"

namespace fcc::cli {

Command addBenchCommand(CLI::App& parent) {
  CLI::App* app = parent.add_subcommand("bench", "Benchmarks: time a stage of the pipeline on this machine (see docs/BENCHMARKS.md)");
  app->require_subcommand(1, 1);
  auto benchmarks = std::make_shared<std::vector<Command>>();
  benchmarks->push_back(addBenchBricksCommand(*app));
  benchmarks->push_back(addBenchConvertCommand(*app));
  benchmarks->push_back(addBenchPreprocessCommand(*app));
  benchmarks->push_back(addBenchRenderCommand(*app));
  benchmarks->push_back(addBenchStreamCommand(*app));
  benchmarks->push_back(addBenchViewCommand(*app));
  return {app, [benchmarks]() {
            for (const Command& c : *benchmarks)
              if (c.app->parsed()) return c.run();
            return 2;
          }};
}

}  // namespace fcc::cli
