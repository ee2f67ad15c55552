// fccvdb: sparse, out-of-core isosurface rendering of FCC-lattice volumes stored in OpenVDB files.
#include <cstdio>
#include <exception>

#include "Command.h"
#include "ParseErrorLine.h"
#include "sparse/Error.h"
#ifdef FCC_MPI
#include "mpi/MpiSession.h"
#endif

int main(int argc, char** argv) {
#ifdef FCC_MPI
  // Under mpirun: MPI for the whole run (tools/mpi/, docs/MPI.md); otherwise nothing.
  fcc::mpi::Session mpiSession(argc, argv);
  const fcc::mpi::World world = fcc::mpi::world();
#endif
  CLI::App app{"fccvdb: isosurfaces of volumes on the face-centered cubic (FCC) lattice, from OpenVDB files"};
  app.name("fccvdb");
  app.require_subcommand(1, 1);
  app.set_version_flag("--version", "fccvdb 0.1.0");
  const std::vector<fcc::cli::Command> commands = {
      fcc::cli::addBenchCommand(app),
      fcc::cli::addCompareCommand(app),
      fcc::cli::addConvertCommand(app),
      fcc::cli::addInfoCommand(app),
      fcc::cli::addProbeCommand(app),
      fcc::cli::addPyramidCommand(app),
      fcc::cli::addRenderCommand(app),
      fcc::cli::addSynthCommand(app),
      fcc::cli::addViewCommand(app),
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
#ifdef FCC_MPI
    if (world.rank != 0) return 2;  // every rank parsed the same words: one line, from rank 0
#endif
    std::fprintf(stderr, "fccvdb: %s\n", fcc::cli::parseErrorLine(app, e, argc, argv).c_str());
    return 2;
  }
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
    return 2;
  } catch (const std::exception& e) {
#ifdef FCC_MPI
    // Other ranks may be waiting for this one in a collective: end them all (renderDistributed has
    // agreed on whatever can fail on one rank alone before this point).
    if (world.distributed()) fcc::mpi::abortAll(e.what());
#endif
    std::fprintf(stderr, "fccvdb: %s\n", e.what());
    return 1;
  }
}
