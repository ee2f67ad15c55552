#include "VdbFile.h"

#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <cstdlib>
#include <iterator>
#include <sstream>

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

// Every tile and every leaf of a tree, visited one after the other: a tree that reads but is
// inconsistent fails here, in the child. Serially, never through TBB (OpenVDB's activeVoxelCount()
// is a parallel reduce): the child is forked from a process whose TBB workers may be mid-flight, and
// a child's parallel loop then waited forever for a worker that fork had not copied (seen in CI, and
// caught by gdb: wait_on_address under activeVoxelCount's reduce), so a good file was called corrupt.
struct WalkTreeSerially {
  template <class GridT>
  void operator()(const GridT& grid) const {
    using TreeT = typename GridT::TreeType;
    openvdb::Index64 count = 0;
    auto tile = grid.tree().cbeginValueAll();
    tile.setMaxDepth(TreeT::ValueAllCIter::LEAF_DEPTH - 1);  // tiles only: leaves are walked below
    for (; tile; ++tile) count += tile.isValueOn();
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) count += leaf->onVoxelCount();
    (void)count;
  }
};

// The grid types whose trees the child walks: OpenVDB's own and ours (the FCC grid, the bounds grid).
using WalkedGridTypes = openvdb::GridTypes::Append<FccGrid, BoundsGrid>;

// What the child does: read the grids (to `depth`), then walk every tree once. No TBB (see above).
void readInChild(const std::string& path, GuardDepth depth) {
  initializeVdb();
  openvdb::io::File file(path);
  file.setCopyMaxBytes(0);
  file.open(depth == GuardDepth::Topology);  // Everything: no delayed loading, every byte is read now
  openvdb::GridPtrVecPtr grids = file.getGrids();
  for (const auto& g : *grids) {
    if (depth == GuardDepth::Topology && !isFccGrid(*g)) g->baseTree().readNonresidentBuffers();
    g->apply<WalkedGridTypes>(WalkTreeSerially{});
  }
  file.close();
}

}  // namespace

void guardVdbFile(const std::string& path, GuardDepth depth) {
  guardVdbRead(path, [&] { readInChild(path, depth); });
}

namespace {

// The CPU time (user + system, in clock ticks) a process has used, or -1 if /proc cannot say.
long long cpuTicksOf(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t paren = stat.rfind(')');
  if (paren == std::string::npos) return -1;
  std::istringstream fields(stat.substr(paren + 1));
  std::string field;
  long long utime = -1, stime = -1;
  for (int i = 3; i <= 15 && (fields >> field); ++i) {  // field 3 is the state; 14 utime, 15 stime
    if (i == 14) utime = std::atoll(field.c_str());
    if (i == 15) stime = std::atoll(field.c_str());
  }
  return utime < 0 || stime < 0 ? -1 : utime + stime;
}

enum class ChildEnd { Exited, TimedOut, Stalled };

// One forked child running `read`, watched until it exits, passes `limit`, or stalls: uses no CPU
// time for kStalledSeconds while it has not finished. OpenVDB stuck on a damaged file spins; a child
// that uses no CPU at all is waiting on a lock fork copied from a parent thread that is not in the
// child (TBB's, or an allocator's: forking a threaded process is only safe for async-signal-safe
// work, and OpenVDB's reading is not), which says nothing of the file.
ChildEnd runChild(const std::function<void()>& read, std::chrono::seconds limit, int& status, std::string& message) {
  constexpr int kStalledSeconds = 5;
  int fds[2];
  if (::pipe(fds) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) throw Error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::close(fds[0]);
    std::string failure;
    try {
      read();
      ::_exit(0);
    } catch (const std::exception& e) {
      failure = e.what();
    } catch (...) {
      failure = "unknown error";
    }
    (void)!::write(fds[1], failure.data(), failure.size());
    ::_exit(3);
  }
  ::close(fds[1]);
  const auto deadline = std::chrono::steady_clock::now() + limit;
  ChildEnd end = ChildEnd::Exited;
  long long lastTicks = -1;
  int stillSeconds = 0;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      end = ChildEnd::TimedOut;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int r = ::poll(&p, 1, int(std::min<long long>(left.count(), 1000)));
    if (r < 0 && errno == EINTR) continue;
    if (r > 0) {
      char buf[512];
      const ssize_t n = ::read(fds[0], buf, sizeof buf);
      if (n > 0) {
        message.append(buf, size_t(n));
        continue;
      }
      break;  // EOF: the child has exited (or closed the pipe)
    }
    if (r == 0) {  // a second without news: is the child working?
      const long long ticks = cpuTicksOf(pid);
      stillSeconds = ticks >= 0 && ticks == lastTicks ? stillSeconds + 1 : 0;
      lastTicks = ticks;
      if (stillSeconds >= kStalledSeconds) {
        end = ChildEnd::Stalled;
        break;
      }
    }
  }
  ::close(fds[0]);
  if (end != ChildEnd::Exited) ::kill(pid, SIGKILL);
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return end;
}

}  // namespace

void guardVdbRead(const std::string& path, const std::function<void()>& read) {
  checkReadableVdb(path);
  struct stat st {};
  ::stat(path.c_str(), &st);
  // Generous: reading runs at hundreds of MB/s; a hang is what this limit catches.
  const auto limit = std::chrono::seconds(20 + st.st_size / (20 << 20));
  constexpr int kAttempts = 3;
  int status = 0;
  std::string message;
  ChildEnd end = ChildEnd::Stalled;
  for (int attempt = 0; attempt < kAttempts && end == ChildEnd::Stalled; ++attempt) {
    message.clear();
    end = runChild(read, limit, status, message);
  }
  if (end == ChildEnd::Stalled)
    throw Error(path + ": the child process reading it stalled " + std::to_string(kAttempts) +
                " times without using any CPU (a lock copied by fork, not the file)");
  if (end == ChildEnd::TimedOut)
    throw InputError(path + ": OpenVDB did not finish reading it within " + std::to_string(limit.count()) +
                     " s; the file is corrupt or truncated");
  if (WIFSIGNALED(status))
    throw InputError(path + ": OpenVDB crashed reading it (signal " + std::to_string(WTERMSIG(status)) +
                     "); the file is corrupt or truncated");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    for (char& c : message)
      if (c == '\n') c = ' ';
    throw InputError(path + ": OpenVDB cannot read it: " + (message.empty() ? "unknown error" : message));
  }
}

namespace {

openvdb::GridPtrVecPtr readAllGrids(const std::string& path) {
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
