// fccvdb bench …: benchmarks as programs (never timed unit tests); each kind lives in its own
// cmd_bench_*.cpp and registers itself under `bench`.
#include "Command.h"

namespace fcc::cli {

Command addBenchCommand(CLI::App& parent) {
  CLI::App* app = parent.add_subcommand("bench", "Benchmarks: render (frames per second over a camera orbit), preprocess (prefilter and brick bounds, samples per second)");
  app->require_subcommand(1, 1);
  const std::vector<Command> kinds = {addBenchRenderCommand(*app), addBenchPreprocessCommand(*app)};
  return {app, [kinds]() {
            for (const auto& k : kinds)
              if (k.app->parsed()) return k.run();
            return 2;
          }};
}

}  // namespace fcc::cli
