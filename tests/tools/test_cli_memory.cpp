// `fccvdb synth` streams (sparse/StreamedBuild.h): writing a dense dataset, its peak memory grows by far
// less than the data's decoded size, where building it in memory took all of it and more.
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <fcntl.h>

#include <cstdio>
#include <string>
#include <vector>

#include "RunCommand.h"

extern char** environ;

namespace fcc::test {
namespace {

struct MeasuredRun {
  int status = -1;
  long peakRssKiB = 0;  // ru_maxrss of the process
  std::string err;
};

// Runs fccvdb with `args` as its own process and reads its peak resident set size (wait4).
MeasuredRun runMeasured(const std::vector<std::string>& args, const TempDir& dir) {
  std::vector<std::string> words{FCC_FCCVDB_EXE};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const std::string errPath = dir / "stderr.txt";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, errPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  MeasuredRun run;
  const int spawned = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return run;
  int status = 0;
  rusage usage{};
  if (::wait4(pid, &status, 0, &usage) != pid) return run;
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  run.peakRssKiB = usage.ru_maxrss;
  run.err = readText(errPath);
  return run;
}

TEST(CliMemory, SynthOfDenseDataGrowsFarLessThanTheData) {
  TempDir dir;
  // The reference kernels: OpenCL's staging and runtime would add their own, device-dependent memory.
  const std::vector<std::string> common{"--force", "--cl-device", "reference"};
  auto synth = [&](int dim) {
    const std::string d = std::to_string(dim);
    std::vector<std::string> args{"synth", "sphere", dir / "s.vdb", "--dims", d + "," + d + "," + d};
    args.insert(args.end(), common.begin(), common.end());
    return runMeasured(args, dir);
  };
  const MeasuredRun tiny = synth(16);
  ASSERT_EQ(tiny.status, 0) << tiny.err;
  // The sphere's field differs from its background almost everywhere: every block is a full leaf.
  const MeasuredRun dense = synth(320);
  ASSERT_EQ(dense.status, 0) << dense.err;
  unsigned long long leaves = 0;
  const size_t at = dense.err.find(" active samples in ");
  ASSERT_NE(at, std::string::npos) << dense.err;
  ASSERT_EQ(std::sscanf(dense.err.c_str() + at, " active samples in %llu bricks", &leaves), 1) << dense.err;
  const long dataKiB = long(leaves * 512 * 16 / 1024);  // 512 packed voxels of 4 floats a leaf
  const long growthKiB = dense.peakRssKiB - tiny.peakRssKiB;
  ASSERT_GE(dataKiB, 64 * 1024) << "the dataset must be large against the process' own memory";
  // Streamed: the topology (~100 bytes a leaf), three slabs of leaves (3 of 21 here) and the batches
  // being written. In memory it was the data and more.
  EXPECT_LT(growthKiB, dataKiB / 3) << "peak RSS " << dense.peakRssKiB << " KiB against " << tiny.peakRssKiB
                                    << " KiB for a 16^3 sphere: it grew by " << growthKiB << " KiB for " << dataKiB
                                    << " KiB of data (" << leaves << " leaves)";
  std::printf("synth sphere 320^3: peak RSS %ld KiB (16^3: %ld KiB), growth %ld KiB for %ld KiB of data\n",
              dense.peakRssKiB, tiny.peakRssKiB, growthKiB, dataKiB);
}

}  // namespace
}  // namespace fcc::test
