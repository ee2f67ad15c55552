// A subcommand of `fccvdb`: each lives in its own tools/cmd_*.cpp and registers its flags on the app;
// `run` is called after parsing when the subcommand was chosen. Errors are thrown (sparse/Error.h).
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace fcc {
class BrickKernels;
}

namespace fcc::cli {

struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Command addCompareCommand(CLI::App& parent);
Command addConvertCommand(CLI::App& parent);
Command addInfoCommand(CLI::App& parent);
Command addProbeCommand(CLI::App& parent);
Command addPyramidCommand(CLI::App& parent);
Command addRenderCommand(CLI::App& parent);
Command addSynthCommand(CLI::App& parent);
Command addViewCommand(CLI::App& parent);
// `bench` is a parent command; each benchmark registers itself on it from its own file.
Command addBenchCommand(CLI::App& parent);
Command addBenchBricksCommand(CLI::App& bench);      // under `bench`
Command addBenchConvertCommand(CLI::App& bench);     // under `bench`
Command addBenchRenderCommand(CLI::App& bench);      // under `bench`
Command addBenchPreprocessCommand(CLI::App& bench);  // under `bench`
Command addBenchViewCommand(CLI::App& bench);        // under `bench`
Command addBenchStreamCommand(CLI::App& bench);      // under `bench`

// Validators shared by several subcommands.
CLI::Validator tripleValidator(const std::string& what);  // "X,Y,Z"

// --cl-device: where preprocessing runs (kernels/ClBrickKernels.h).
CLI::Option* addDeviceOption(CLI::App& app, std::string& device);
std::unique_ptr<BrickKernels> preprocessKernels(const std::string& device);

}  // namespace fcc::cli
