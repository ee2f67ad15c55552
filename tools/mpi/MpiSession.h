// MPI for `fccvdb` when started by mpirun/mpiexec (FCC_MPI builds only; docs/MPI.md). MPI is
// initialised only when the launcher's environment says so (Open MPI's OMPI_COMM_WORLD_SIZE, PMIx's or
// PMI's rank): a plain `fccvdb` never touches MPI, and one started by `mpirun -np 1` renders alone.
#pragma once

#include <string>

namespace fcc::mpi {

class Session {
 public:
  Session(int& argc, char**& argv);  // MPI_Init when launched by an MPI launcher
  ~Session();                         // MPI_Finalize
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
};

// This process's place in MPI_COMM_WORLD: {0, 1} without MPI.
struct World {
  int rank = 0, size = 1;
  bool distributed() const { return size > 1; }
};
World world();

// An error after the ranks have parted ways (one of them throws where the others wait in a
// collective): the line on stderr, naming the rank, then MPI_Abort so that no rank hangs.
[[noreturn]] void abortAll(const std::string& line);

}  // namespace fcc::mpi
