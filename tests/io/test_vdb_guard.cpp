// The guard (io/VdbFile.h) reads a file first in the fccvdb-guard executable, spawned with a time limit.
// It used to fork this process instead, and a fork copies whatever lock another thread holds at that
// moment: the child then waited forever (TBB's wait_on_address under a parallel reduce, later another
// lock in PreprocessFiles) until the time limit called a good file corrupt (docs/RELIABILITY.md, bug 5).
// These tests run the guard many times while this process is as busy as it gets — TBB workers running,
// OpenVDB reading in another thread, a mutex held, a second thread guarding too — and every check of
// the good file must pass; then the outcomes a guard can have, through stand-in guard executables.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <tbb/parallel_for.h>

#include <sys/stat.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <thread>

#include "io/VdbFile.h"
#include "sparse/Error.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

// A small level set every guard read must accept, its grid named `gridName`.
std::string writeGoodFile(const test::TempDir& dir, const std::string& gridName = "ls") {
  initializeVdb();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(20.0f, openvdb::Vec3f(0.0f), 1.0f, 3.0f);
  grid->setName(gridName);
  const std::string path = dir / "ls.vdb";
  openvdb::io::File(path).write({grid});
  return path;
}

// The guard's message for `check`, or "" if it passed; `isInputError` says which kind it threw.
template <class Check>
std::string guardError(Check&& check, bool& isInputError) {
  isInputError = false;
  try {
    check();
  } catch (const InputError& e) {
    isInputError = true;
    return e.what();
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

// FCCVDB_GUARD set for one test.
struct GuardOverride {
  explicit GuardOverride(const std::string& exe) { ::setenv("FCCVDB_GUARD", exe.c_str(), 1); }
  ~GuardOverride() { ::unsetenv("FCCVDB_GUARD"); }
};

// A stand-in guard: a shell script with `body`, made executable.
std::string writeScript(const test::TempDir& dir, const std::string& name, const std::string& body) {
  const std::string path = dir / name;
  std::ofstream(path) << "#!/bin/sh\n" << body << "\n";
  ::chmod(path.c_str(), 0755);
  return path;
}

TEST(VdbGuard, GoodFileReadsWhileOtherThreadsHoldLocksAndRunTbb) {
  test::TempDir dir;
  const std::string path = writeGoodFile(dir);

  std::atomic<bool> stop{false};
  std::atomic<long> tbbRounds{0}, vdbReads{0};
  std::thread tbbBusy([&] {
    while (!stop) {
      std::atomic<double> sink{0.0};
      tbb::parallel_for(0, 64, [&](int i) {
        double s = 0.0;
        for (int k = 0; k < 20000; ++k) s += std::sqrt(double(i + k));
        sink = s;
      });
      ++tbbRounds;
    }
  });
  // OpenVDB's own reading in this process: its registry and stream locks, the allocator's, taken and
  // released all the time — the locks a fork could copy held.
  std::thread vdbBusy([&] {
    while (!stop) {
      openvdb::io::File file(path);
      file.open(false);
      (void)file.getGrids();
      file.close();
      ++vdbReads;
    }
  });
  // A lock held for the whole test by a thread that is in no child.
  std::mutex held;
  std::atomic<bool> locked{false};
  std::thread holder([&] {
    std::lock_guard<std::mutex> lock(held);
    locked = true;
    while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  });
  while (!locked) std::this_thread::yield();

  constexpr int kReads = 20;
  std::atomic<int> passed{0};
  const auto guardMany = [&](const char* who) {
    for (int i = 0; i < kReads; ++i) {
      // As convert does: this thread's own parallel loop ends just before the guard starts.
      std::atomic<double> sink{0.0};
      tbb::parallel_for(0, 1 << 14, [&](int k) { sink = std::sqrt(double(k)); });
      const auto start = std::chrono::steady_clock::now();
      try {
        guardVdbFile(path);
        guardLeafRead(path, "ls", {openvdb::FloatTree::treeType()});
        ++passed;
      } catch (const Error& e) {
        ADD_FAILURE() << who << " read " << i << " after "
                      << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                      << " s: " << e.what();
        return;
      }
    }
  };
  std::thread second(guardMany, "second thread's");  // two guards at once: one's pipe is not the other's
  guardMany("main thread's");
  second.join();
  stop = true;
  tbbBusy.join();
  vdbBusy.join();
  holder.join();
  EXPECT_EQ(passed.load(), 2 * kReads);
  EXPECT_GT(tbbRounds.load(), 0);
  EXPECT_GT(vdbReads.load(), 0);
}

TEST(VdbGuard, GoodFileReadsRightAfterTheParentsParallelLoops) {
  test::TempDir dir;
  const std::string path = writeGoodFile(dir);
  for (int i = 0; i < 50; ++i) {
    std::atomic<double> sink{0.0};
    tbb::parallel_for(0, 1 << 12, [&](int k) { sink = std::sqrt(double(k)); });
    const auto start = std::chrono::steady_clock::now();
    try {
      guardVdbFile(path, i % 2 ? GuardDepth::Topology : GuardDepth::Everything);
    } catch (const Error& e) {
      ADD_FAILURE() << "read " << i << " after "
                    << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                    << " s: " << e.what();
      break;
    }
  }
}

// The grid name and tree types reach the guard's process as they are: a name with spaces and a comma
// is found, a missing one is the reader's one-line InputError, relayed.
TEST(VdbGuard, LeafReadChecksTheNamedGrid) {
  test::TempDir dir;
  const std::string name = "two words, one comma";
  const std::string path = writeGoodFile(dir, name);
  bool input = false;
  EXPECT_EQ(guardError([&] { guardLeafRead(path, name, {openvdb::FloatTree::treeType()}); }, input), "");
  EXPECT_EQ(guardError([&] { guardLeafRead(path, "", {"Tree_vec4s_5_4_3", openvdb::FloatTree::treeType()}); }, input), "");
  const std::string missing = guardError([&] { guardLeafRead(path, "nope", {openvdb::FloatTree::treeType()}); }, input);
  EXPECT_TRUE(input) << missing;
  EXPECT_EQ(missing.rfind(path + ": OpenVDB cannot read it: ", 0), 0u) << missing;
  EXPECT_NE(missing.find("no grid named \"nope\""), std::string::npos) << missing;
  EXPECT_EQ(missing.find('\n'), std::string::npos) << missing;
}

// What the guard's process does becomes one line naming the file: a failure it reports (status 3,
// the message on stdout, here over two lines) and a crash are the file's (InputError); any other
// status is the guard's own failure, an Error that does not call the file corrupt.
TEST(VdbGuard, TheGuardsOutcomesBecomeOneLineNamingTheFile) {
  test::TempDir dir;
  const std::string path = writeGoodFile(dir);
  bool input = false;
  {
    GuardOverride fake(writeScript(dir, "fails", "echo 'bad leaf'; echo 'at 0,0,0'; exit 3"));
    EXPECT_EQ(guardError([&] { guardVdbFile(path); }, input), path + ": OpenVDB cannot read it: bad leaf at 0,0,0");
    EXPECT_TRUE(input);
  }
  {
    GuardOverride fake(writeScript(dir, "crashes", "kill -SEGV $$"));
    EXPECT_EQ(guardError([&] { guardVdbFile(path); }, input),
              path + ": OpenVDB crashed reading it (signal 11); the file is corrupt or truncated");
    EXPECT_TRUE(input);
  }
  {
    const std::string exe = writeScript(dir, "broken", "echo 'usage'; exit 2");
    GuardOverride fake(exe);
    EXPECT_EQ(guardError([&] { guardVdbFile(path); }, input), path + ": cannot check it: " + exe + " exited with status 2: usage");
    EXPECT_FALSE(input);
  }
}

// Without the guard executable nothing can be checked: an Error naming the file and where it looked,
// never an InputError (the file is not at fault).
TEST(VdbGuard, AMissingGuardExecutableIsAnErrorSayingWhereItLooked) {
  test::TempDir dir;
  const std::string path = writeGoodFile(dir);
  const std::string nowhere = dir / "no-such-guard";
  GuardOverride fake(nowhere);
  bool input = true;
  const std::string message = guardError([&] { guardVdbFile(path); }, input);
  EXPECT_FALSE(input) << message;
  EXPECT_EQ(message, path + ": cannot check it: FCCVDB_GUARD is " + nowhere + ", which is not an executable");
}

}  // namespace
}  // namespace fcc::io
