// fccvdb probe FILE.vdb: the spline's value and world-space gradient at points read from stdin.
#include <cstdio>
#include <iostream>
#include <sstream>

#include "Command.h"
#include "io/VdbFile.h"
#include "sparse/Error.h"
#include "sparse/FccSampler.h"

namespace fcc::cli {

Command addProbeCommand(CLI::App& parent) {
  struct Args {
    std::string file, grid;
  };
  auto args = std::make_shared<Args>();
  CLI::App* app = parent.add_subcommand(
      "probe", "Evaluate the FCC spline: reads lines 'x y z' (world coordinates) from stdin, writes 'value gx gy gz' (gradient in world coordinates)");
  app->add_option("FILE", args->file, "FCC .vdb file (from fccvdb convert or synth)")->required();
  app->add_option("--grid", args->grid, "The FCC grid to probe (default: the first)");
  return {app, [args]() {
            const FccGrid::Ptr grid = io::readFccGrid(args->file, args->grid);
            const FccSampler sampler(*grid, storesSamples(*grid));
            std::string line;
            for (size_t lineNumber = 1; std::getline(std::cin, line); ++lineNumber) {
              if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
              std::istringstream in(line);
              double x, y, z;
              if (!(in >> x >> y >> z) || !(in >> std::ws).eof())
                throw InputError("stdin line " + std::to_string(lineNumber) + ": expected 'x y z' (three numbers), got '" + line + "'");
              const auto r = sampler.evaluateWorld(openvdb::Vec3d(x, y, z));
              std::printf("%.9g %.9g %.9g %.9g\n", r.value, r.gradient.x, r.gradient.y, r.gradient.z);
            }
            return 0;
          }};
}

}  // namespace fcc::cli
