// `fccvdb synth` streams (sparse/StreamedBuild.h): writing a dense dataset, its peak memory grows by far
// less than the data's decoded size, where building it in memory took all of it and more.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "MeasuredRun.h"
#include "RunCommand.h"

namespace fcc::test {
namespace {

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
  const size_t at = dense.err.find(" stored values in ");
  ASSERT_NE(at, std::string::npos) << dense.err;
  ASSERT_EQ(std::sscanf(dense.err.c_str() + at, " stored values in %llu bricks", &leaves), 1) << dense.err;
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
