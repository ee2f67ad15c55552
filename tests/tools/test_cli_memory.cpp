// `fccvdb synth` streams (sparse/StreamedBuild.h): writing a dense dataset, its peak memory grows by far
// less than the data's decoded size, where building it in memory took all of it and more.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <thread>
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

namespace fcc::test {
namespace {

// `render` keeps to its budgets (issue 15): on a file many times --gpu-cache + --host-cache, its peak
// resident set (VmHWM: anonymous and file-backed pages alike, so a mapped file would count) exceeds a
// render of a tiny file with the same budgets by no more than the budgets, the loader's fixed set of
// blocks and the bigger file's index. On llvmpipe the GPU pool is host memory too.
TEST(CliMemory, RenderOfAFileEightTimesItsBudgetsStaysWithinThem) {
  TempDir dir;
  const auto synth = [&](const std::string& name, int dim) {
    const std::string d = std::to_string(dim);
    const MeasuredRun r = runMeasured({"synth", "blobs", dir / name, "--dims", d + "," + d + "," + d, "--force", "--quiet"}, dir);
    ASSERT_EQ(r.status, 0) << r.err;
  };
  synth("tiny.vdb", 64);
  synth("big.vdb", 512);
  constexpr long kGpuMiB = 2, kHostMiB = 2;
  const long fileKiB = long(std::filesystem::file_size(dir / "big.vdb") / 1024);
  ASSERT_GE(fileKiB, 8 * (kGpuMiB + kHostMiB) * 1024) << "the file must be at least 8x the budgets";
  const auto render = [&](const std::string& name) {
    return runMeasured({"render", dir / name, dir / (name + ".png"), "--res", "160x160", "--gpu-cache",
                        std::to_string(kGpuMiB), "--host-cache", std::to_string(kHostMiB), "--force", "--quiet"},
                       dir);
  };
  const MeasuredRun tiny = render("tiny.vdb");
  ASSERT_EQ(tiny.status, 0) << tiny.err;
  const MeasuredRun big = render("big.vdb");
  ASSERT_EQ(big.status, 0) << big.err;
  // The loader's blocks: as many ready as the pool has slots (2 MiB of 16 000-byte slots here) and a
  // chunk of 8 per thread, 16 000 bytes each, plus as many recycled (viewer/BrickLoader.h); the bigger
  // file's topology, bounds grid, leaf index and page tables: a few MiB.
  const long slots = kGpuMiB * 1024 * 1024 / 16000;
  const long loaderKiB = 2 * (slots + 8 * long(std::thread::hardware_concurrency())) * 16000 / 1024;
  const long indexKiB = 8 * 1024;
  const long boundKiB = tiny.peakRssKiB + (kGpuMiB + kHostMiB) * 1024 + loaderKiB + indexKiB;
  EXPECT_LT(big.peakRssKiB, boundKiB) << "render of a " << fileKiB << " KiB file with budgets of " << kGpuMiB << " + "
                                      << kHostMiB << " MiB peaked at " << big.peakRssKiB << " KiB; a tiny file at "
                                      << tiny.peakRssKiB << " KiB";
  EXPECT_LT(boundKiB - tiny.peakRssKiB, fileKiB) << "the bound must be able to catch a mapped file";
  std::printf("render with %ld + %ld MiB budgets: %ld KiB file -> peak %ld KiB; tiny file %ld KiB; bound %ld KiB\n",
              kGpuMiB, kHostMiB, fileKiB, big.peakRssKiB, tiny.peakRssKiB, boundKiB);
}

}  // namespace
}  // namespace fcc::test
