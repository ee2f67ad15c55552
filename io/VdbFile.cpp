#include "VdbFile.h"

#include "VdbLeafReader.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "AtomicOutput.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

constexpr char kVdbMagic[4] = {' ', 'B', 'D', 'V'};  // 0x56444220 little-endian

void checkReadableVdb(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open: " + std::strerror(errno));
  char magic[4] = {};
  in.read(magic, 4);
  if (in.gcount() != 4 || std::memcmp(magic, kVdbMagic, 4) != 0)
    throw InputError(path + ": not an OpenVDB file (no VDB magic number); valid inputs are .vdb files written by OpenVDB");
}

// Where fccvdb-guard is: $FCCVDB_GUARD if set (and only there), else beside this process's executable
// (fccvdb and the test programs all live in the build's bin/, with it), else where this build put it.
// An Error naming `path` and the places looked at if none holds it.
std::string guardExecutable(const std::string& path) {
  const auto executable = [](const std::string& p) { return !p.empty() && ::access(p.c_str(), X_OK) == 0; };
  if (const char* set = std::getenv("FCCVDB_GUARD"); set && *set) {
    if (executable(set)) return set;
    throw Error(path + ": cannot check it: FCCVDB_GUARD is " + set + ", which is not an executable");
  }
  std::string looked;
  char self[4096];
  const ssize_t n = ::readlink("/proc/self/exe", self, sizeof self - 1);
  if (n > 0) {
    std::string beside(self, size_t(n));
    beside = beside.substr(0, beside.rfind('/') + 1) + "fccvdb-guard";
    if (executable(beside)) return beside;
    looked = beside + ", ";
  }
  if (executable(FCC_GUARD_EXE)) return FCC_GUARD_EXE;
  throw Error(path + ": cannot check it: no fccvdb-guard executable at " + looked + FCC_GUARD_EXE +
              "; build the fccvdb-guard target, or set FCCVDB_GUARD to its path");
}

struct GuardEnd {
  bool timedOut = false;
  int status = 0;       // waitpid's, when it did not time out
  std::string output;   // the guard's stdout
};

// Runs fccvdb-guard with `args` (argv[1...]) until it exits or `limit` passes (then it is killed).
// posix_spawn starts it without copying this process (glibc: clone with CLONE_VM | CLONE_VFORK, then
// exec), which is safe however many threads hold locks here. Its stdout is a pipe read here; stdin is
// /dev/null; stderr is this process's (what OpenVDB or the C library print on the way to a crash).
GuardEnd runGuard(const std::string& path, const std::string& exe, const std::vector<std::string>& args,
                  std::chrono::seconds limit) {
  int fds[2];
  // Close-on-exec: a guard spawned by another thread at the same time must not hold this pipe's
  // write end open, or the EOF that says this guard ended would wait for that one too.
  if (::pipe2(fds, O_CLOEXEC) != 0) throw Error(path + ": cannot check it: pipe: " + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);  // dup2 clears close-on-exec
  // Default signal handling and no blocked signals, whatever this process set up (an ignored
  // SIGPIPE or a thread's blocked mask is inherited through exec otherwise).
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none, all;
  sigemptyset(&none);
  sigfillset(&all);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &all);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(exe.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int spawned = ::posix_spawn(&pid, exe.c_str(), &actions, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  ::close(fds[1]);
  if (spawned != 0) {
    ::close(fds[0]);
    throw Error(path + ": cannot check it: cannot start " + exe + ": " + std::strerror(spawned));
  }
  GuardEnd end;
  const auto deadline = std::chrono::steady_clock::now() + limit;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      end.timedOut = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int r = ::poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {  // not seen: one valid fd; the guard is stopped, not left running
      const int error = errno;
      ::close(fds[0]);
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, &end.status, 0) < 0 && errno == EINTR) {
      }
      throw Error(path + ": cannot check it: poll: " + std::strerror(error));
    }
    if (r == 0) continue;
    char buf[512];
    const ssize_t n = ::read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // EOF: the guard has exited
    end.output.append(buf, size_t(n));
  }
  ::close(fds[0]);
  if (end.timedOut) ::kill(pid, SIGKILL);
  while (::waitpid(pid, &end.status, 0) < 0 && errno == EINTR) {
  }
  return end;
}

// The guard's check of `path` described by `args`, its outcome as the one-line errors callers expect.
void guard(const std::string& path, const std::vector<std::string>& args) {
  checkReadableVdb(path);
  const std::string exe = guardExecutable(path);
  struct stat st {};
  ::stat(path.c_str(), &st);
  // Generous: reading runs at hundreds of MB/s; a hang is what this limit catches.
  const auto limit = std::chrono::seconds(20 + st.st_size / (20 << 20));
  GuardEnd end = runGuard(path, exe, args, limit);
  std::string& message = end.output;
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  for (char& c : message)
    if (c == '\n') c = ' ';
  if (end.timedOut)
    throw InputError(path + ": OpenVDB did not finish reading it within " + std::to_string(limit.count()) +
                     " s; the file is corrupt or truncated");
  if (WIFSIGNALED(end.status))
    throw InputError(path + ": OpenVDB crashed reading it (signal " + std::to_string(WTERMSIG(end.status)) +
                     "); the file is corrupt or truncated");
  if (WIFEXITED(end.status) && WEXITSTATUS(end.status) == 3)
    throw InputError(path + ": OpenVDB cannot read it: " + (message.empty() ? "unknown error" : message));
  // Any other status is the guard's own failure (a command line it refused, a library the loader
  // did not find: 127), which says nothing of the file.
  if (!WIFEXITED(end.status) || WEXITSTATUS(end.status) != 0)
    throw Error(path + ": cannot check it: " + exe + " exited with status " + std::to_string(WEXITSTATUS(end.status)) +
                (message.empty() ? "" : ": " + message));
}

}  // namespace

void guardVdbFile(const std::string& path, GuardDepth depth) {
  guard(path, {"file", depth == GuardDepth::Topology ? "topology" : "everything", path});
}

void guardLeafRead(const std::string& path, const std::string& gridName, const std::vector<std::string>& treeTypes,
                   const std::string& boundsName) {
  std::string types;
  for (const std::string& t : treeTypes) types += (types.empty() ? "" : ",") + t;
  std::vector<std::string> args{"leaves", path, gridName, types};
  if (!boundsName.empty()) {
    args.push_back("--bounds");
    args.push_back(boundsName);
  }
  guard(path, args);
}

namespace {

openvdb::GridPtrVecPtr readAllGrids(const std::string& path) {
  // Our own parse of the header and grid descriptors first: a cut or damaged header is named as such
  // ("truncated: ... ends at byte E"), where OpenVDB would say "Grid type  is not registered".
  VdbLeafReader::listGrids(path);
  guardVdbFile(path);
  initializeVdb();
  try {
    openvdb::io::File file(path);
    file.setCopyMaxBytes(0);
    file.open(false);
    auto grids = file.getGrids();
    file.close();
    return grids;
  } catch (const std::exception& e) {
    throw InputError(path + ": OpenVDB cannot read it: " + e.what());
  }
}

std::string gridNames(const openvdb::GridPtrVec& grids) {
  std::string names;
  for (const auto& g : grids) names += (names.empty() ? "" : ", ") + g->getName() + " (" + g->type() + ")";
  return names.empty() ? "none" : names;
}

}  // namespace

// The bounds grid of `fccName` among `grids`, by its fcc_bounds_of metadata.
BoundsGrid::Ptr findBoundsGrid(const openvdb::GridPtrVec& grids, const std::string& fccName) {
  for (const auto& g : grids) {
    auto bounds = openvdb::gridPtrCast<BoundsGrid>(g);
    if (!bounds) continue;
    const auto of = bounds->getMetadata<openvdb::StringMetadata>(meta::kBoundsOf);
    if (of && of->value() == fccName) return bounds;
  }
  return nullptr;
}

FccGrid::Ptr findFccGrid(const std::string& path, const openvdb::GridPtrVec& grids, const std::string& gridName) {
  for (const auto& g : grids) {
    if (!gridName.empty() && g->getName() != gridName) continue;
    // Without a name: level 0, never a pyramid level (FccPyramid.h), whatever the grids' order.
    if (gridName.empty() && isLodGridName(g->getName())) continue;
    if (isFccGrid(*g)) return openvdb::gridPtrCast<FccGrid>(g);
    if (!gridName.empty())
      throw InputError(path + ": grid '" + gridName + "' is a " + g->type() +
                       " grid, not an FCC grid; run `fccvdb convert " + path + " OUT.vdb` first");
  }
  if (!gridName.empty())
    throw InputError(path + ": no grid named '" + gridName + "'; grids: " + gridNames(grids));
  throw InputError(path + ": holds no FCC grid (grids: " + gridNames(grids) + "); run `fccvdb convert " + path +
                   " OUT.vdb` first");
}


std::vector<GridInfo> listGrids(const std::string& path) {
  std::vector<GridInfo> out;
  const auto grids = readAllGrids(path);  // not `: *readAllGrids(path)`: the range would outlive the pointer
  for (const auto& g : *grids) out.push_back({g->getName(), g->type(), isFccGrid(*g)});
  return out;
}

FccGrid::Ptr readFccGrid(const std::string& path, const std::string& gridName) {
  return findFccGrid(path, *readAllGrids(path), gridName);
}

FccWithBounds readFccGridWithBounds(const std::string& path, const std::string& gridName) {
  const auto grids = readAllGrids(path);
  FccWithBounds r;
  r.grid = findFccGrid(path, *grids, gridName);
  r.bounds = findBoundsGrid(*grids, r.grid->getName());
  return r;
}

BoundsGrid::Ptr readBoundsGrid(const std::string& path, const std::string& fccGridName) {
  return findBoundsGrid(*readAllGrids(path), fccGridName);
}

openvdb::FloatGrid::Ptr readFloatGrid(const std::string& path, const std::string& gridName) {
  const auto grids = readAllGrids(path);
  for (const auto& g : *grids) {
    if (!gridName.empty() && g->getName() != gridName) continue;
    if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(g)) return f;
    if (!gridName.empty())
      throw InputError(path + ": grid '" + gridName + "' is a " + g->type() + " grid; convert needs a float grid");
  }
  if (!gridName.empty())
    throw InputError(path + ": no grid named '" + gridName + "'; grids: " + gridNames(*grids));
  throw InputError(path + ": holds no float grid to convert (grids: " + gridNames(*grids) + ")");
}

void writeVdbAtomically(const std::string& path, const openvdb::GridCPtrVec& grids, bool overwrite,
                        const std::string& inputPath) {
  initializeVdb();
  AtomicOutput out(path, overwrite, inputPath);
  try {
    openvdb::io::File file(out.tempPath());
    file.write(grids);
    file.close();
  } catch (const std::exception& e) {
    throw OutputError(path + ": writing failed: " + e.what());
  }
  out.commit();
}

}  // namespace fcc::io
