// The guard's child process (io/VdbFile.h) is forked from a process whose TBB workers may be busy or
// going to sleep. A child that used TBB (OpenVDB's activeVoxelCount() is a parallel reduce) could wait
// forever for a worker fork had not copied — it did, 1 in ~30 runs of ConvertStreamed's fog test under
// load, gdb showing the child in wait_on_address under that reduce — and the guard then called a good
// file corrupt. These tests fork the guard many times in the two states seen (workers running in
// another thread; this thread's own parallel loop just ended) and every read of the good file must pass.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <tbb/parallel_for.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

#include "io/VdbFile.h"
#include "sparse/Error.h"
#include "tests/tools/RunCommand.h"

namespace fcc::io {
namespace {

// A small level set every guard read must accept.
std::string writeGoodFile(const test::TempDir& dir) {
  initializeVdb();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(20.0f, openvdb::Vec3f(0.0f), 1.0f, 3.0f);
  grid->setName("ls");
  const std::string path = dir / "ls.vdb";
  openvdb::io::File(path).write({grid});
  return path;
}

TEST(VdbGuard, GoodFileReadsWhileTheParentsTbbWorkersRun) {
  test::TempDir dir;
  const std::string path = writeGoodFile(dir);

  std::atomic<bool> stop{false};
  std::atomic<long> rounds{0};
  std::thread busy([&] {
    while (!stop) {
      std::atomic<double> sink{0.0};
      tbb::parallel_for(0, 64, [&](int i) {
        double s = 0.0;
        for (int k = 0; k < 20000; ++k) s += std::sqrt(double(i + k));
        sink = s;
      });
      ++rounds;
    }
  });
  constexpr int kReads = 40;
  int passed = 0;
  for (int i = 0; i < kReads; ++i) {
    const auto start = std::chrono::steady_clock::now();
    // As convert does: this thread's own parallel loop ends just before the fork.
    std::atomic<double> sink{0.0};
    tbb::parallel_for(0, 1 << 14, [&](int k) { sink = std::sqrt(double(k)); });
    try {
      guardVdbFile(path);
      ++passed;
    } catch (const InputError& e) {
      ADD_FAILURE() << "read " << i << " after "
                    << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                    << " s: " << e.what();
      break;
    }
  }
  stop = true;
  busy.join();
  EXPECT_EQ(passed, kReads);
  EXPECT_GT(rounds.load(), 0);
}

TEST(VdbGuard, GoodFileReadsRightAfterTheParentsParallelLoops) {
  test::TempDir dir;
  const std::string path = writeGoodFile(dir);
  for (int i = 0; i < 100; ++i) {
    std::atomic<double> sink{0.0};
    tbb::parallel_for(0, 1 << 12, [&](int k) { sink = std::sqrt(double(k)); });
    const auto start = std::chrono::steady_clock::now();
    try {
      guardVdbFile(path);
    } catch (const InputError& e) {
      ADD_FAILURE() << "read " << i << " after "
                    << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
                    << " s: " << e.what();
      break;
    }
  }
}

// A child that waits without using CPU (what a lock copied by fork looks like) is not the file's
// fault: it is stopped after 5 s and tried again; one that stalls every time is an Error naming the
// file, never an InputError calling it corrupt.
TEST(VdbGuard, AStalledChildIsTriedAgainAndNeverCallsTheFileCorrupt) {
  test::TempDir dir;
  const std::string path = writeGoodFile(dir);
  const std::string marker = dir / "stalled-once";
  guardVdbRead(path, [&] {
    if (!std::filesystem::exists(marker)) {
      std::ofstream(marker) << "1";
      ::pause();  // blocks, no CPU: stalled
    }
  });
  EXPECT_TRUE(std::filesystem::exists(marker)) << "the first child ran";
  try {
    guardVdbRead(path, [] { ::pause(); });
    ADD_FAILURE() << "a child that always stalls passed";
  } catch (const InputError& e) {
    ADD_FAILURE() << "called the file corrupt: " << e.what();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("stalled"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fcc::io
