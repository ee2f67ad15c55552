#include "MpiSession.h"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>

namespace fcc::mpi {
namespace {

bool launchedByMpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

bool initialisedHere = false;

}  // namespace

Session::Session(int& argc, char**& argv) {
  if (!launchedByMpi()) return;
  MPI_Init(&argc, &argv);
  initialisedHere = true;
}

Session::~Session() {
  if (!initialisedHere) return;
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

World world() {
  World w;
  if (!initialisedHere) return w;
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size);
  return w;
}

void abortAll(const std::string& line) {
  const World w = world();
  std::fprintf(stderr, "fccvdb: rank %d of %d: %s\n", w.rank, w.size, line.c_str());
  std::fflush(stderr);
  if (initialisedHere) MPI_Abort(MPI_COMM_WORLD, 1);
  std::exit(1);
}

}  // namespace fcc::mpi
