// `mpirun -np N fccvdb render` (FCC_MPI builds; registered only when mpiexec is found): the composited
// image against one process's, bit for bit for isosurfaces and within a float tolerance for DVR; each
// rank reads only bricks of its own partition; a rank that cannot open the file ends every rank with
// one line. Small sizes: llvmpipe on two cores runs every rank (docs/MPI.md).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "ExrRead.h"
#include "RunCommand.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;

// Open MPI as root needs --allow-run-as-root; 4 ranks on 2 cores need --oversubscribe. A time limit:
// a hang fails the test instead of blocking CI.
std::string mpirun(int ranks, const std::string& args) {
  return "timeout 240 " + std::string(FCC_MPIEXEC) + " --allow-run-as-root --oversubscribe -np " + std::to_string(ranks) +
         " " + FCC_FCCVDB_EXE + " " + args;
}

struct Image {
  int width = 0, height = 0;
  std::vector<std::vector<float>> channels;
};

Image readExr(const std::string& path, const std::vector<const char*>& names) {
  Image image;
  for (const char* name : names) image.channels.push_back(readExrChannel(path, name, image.width, image.height));
  return image;
}

const std::vector<const char*> kIsoChannels = {"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"};
const std::vector<const char*> kDvrChannels = {"R", "G", "B", "A"};

// The JSON `render --json` prints, checked: every rank read only bricks of its partition, and the
// partitions together hold what one process needs.
void expectBricksWithinPartitions(const std::string& jsonText, int ranks, uint64_t bricksOneProcessNeeds) {
  const nlohmann::json report = nlohmann::json::parse(jsonText);
  ASSERT_EQ(report["ranks"].get<int>(), ranks);
  ASSERT_EQ(report["per_rank"].size(), std::size_t(ranks));
  uint64_t owned = 0, read = 0;
  for (const auto& rank : report["per_rank"]) {
    EXPECT_LE(rank["bricks_read"].get<uint64_t>(), rank["bricks_owned"].get<uint64_t>()) << rank.dump();
    EXPECT_GE(rank["render_seconds"].get<double>(), 0.0);
    EXPECT_GT(rank["bytes_sent"].get<uint64_t>(), 0u) << "every rank exchanges pieces";
    owned += rank["bricks_owned"].get<uint64_t>();
    read += rank["bricks_read"].get<uint64_t>();
  }
  EXPECT_EQ(owned, bricksOneProcessNeeds) << "the partitions split the bricks one process needs";
  EXPECT_GT(read, 0u);
}

// Renders `file` with `flags` once alone and with 2 and 4 ranks; compares the images.
void expectSameAsOneProcess(const TempDir& dir, const std::string& file, const std::string& flags, bool dvr) {
  const std::string one = dir / "one.exr";
  const auto single = runFccvdb("render " + file + " " + one + " " + flags + " --json --quiet --force");
  if (failedForLackOfGl(single)) GTEST_SKIP() << single.err;
  ASSERT_EQ(single.status, 0) << single.err;
  const uint64_t needed = nlohmann::json::parse(single.out)["per_rank"][0]["bricks_owned"].get<uint64_t>();
  ASSERT_GT(needed, 4u) << "too few bricks to split";
  const auto& names = dvr ? kDvrChannels : kIsoChannels;
  const Image reference = readExr(one, names);
  double alphaSum = 0.0;
  for (float a : reference.channels[3]) alphaSum += a;
  ASSERT_GT(alphaSum, 10.0) << "the view shows the data";
  for (int ranks : {2, 4}) {
    const std::string many = dir / ("ranks" + std::to_string(ranks) + ".exr");
    const auto r = runShell(mpirun(ranks, "render " + file + " " + many + " " + flags + " --json --quiet --force"));
    ASSERT_EQ(r.status, 0) << r.err;
    expectBricksWithinPartitions(r.out, ranks, needed);
    for (const char* key : {"isovalues", "tf"})  // what the frame showed, as one process says it
      EXPECT_EQ(nlohmann::json::parse(r.out).value(key, nlohmann::json()), nlohmann::json::parse(single.out).value(key, nlohmann::json()))
          << ranks << " ranks, " << key;
    const Image image = readExr(many, names);
    ASSERT_EQ(image.width, reference.width);
    ASSERT_EQ(image.height, reference.height);
    for (std::size_t c = 0; c < names.size(); ++c) {
      std::size_t differing = 0;
      double worst = 0.0;
      for (std::size_t p = 0; p < image.channels[c].size(); ++p) {
        const float a = reference.channels[c][p], b = image.channels[c][p];
        if (dvr) {
          worst = std::max(worst, double(std::abs(a - b)));
        } else if (std::memcmp(&a, &b, sizeof a) != 0) {
          ++differing;
        }
      }
      // Isosurfaces: the same rays and the same hits, so the same bits. DVR: the partitions' "over"
      // regroups the sums, and each rank stops its rays at opacity 0.995 of its own part (at most
      // 0.005 of the colour the ray would have had behind), so 0.01.
      if (dvr)
        EXPECT_LE(worst, 0.01) << ranks << " ranks, channel " << names[c];
      else
        EXPECT_EQ(differing, 0u) << ranks << " ranks, channel " << names[c] << " differs in " << differing << " pixels";
    }
  }
}

TEST(MpiRender, SphereIsSameAsOneProcess) {
  TempDir dir;
  const std::string vdb = dir / "sphere.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 64,64,64 --quiet").status, 0);
  expectSameAsOneProcess(dir, vdb, "--res 96x80 --iso 0.25", false);
}

TEST(MpiRender, BlobsIsoAndDvrAreSameAsOneProcess) {
  TempDir dir;
  const std::string vdb = dir / "blobs.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 64,64,64 --quiet").status, 0);
  expectSameAsOneProcess(dir, vdb, "--res 96x80", false);
  expectSameAsOneProcess(dir, vdb, "--res 80x64 --mode dvr --tf inferno", true);
}

TEST(MpiRender, EngineCtIsSameAsOneProcess) {
  const std::string raw = std::string(FCC_SHARED_DATA_DIR) + "/engine_256x256x128_uint8.raw.gz";
  if (!std::ifstream(raw)) GTEST_SKIP() << "no " << raw;
  TempDir dir;
  const std::string vdb = dir / "engine.vdb";
  const auto converted = runFccvdb("convert " + raw + " " + vdb + " --dims 256,256,128 --type u8 --quiet");
  ASSERT_EQ(converted.status, 0) << converted.err;
  expectSameAsOneProcess(dir, vdb, "--res 96x96 --iso 100", false);
}

TEST(MpiRender, BenchRenderReportsEveryRank) {
  TempDir dir;
  const std::string vdb = dir / "sphere.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 48,48,48 --quiet").status, 0);
  const auto r = runShell(mpirun(2, "bench render " + vdb + " --iso 0.25 --res 48x40 --frames 2 --warmup 0 --json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["frames"].get<int>(), 2);
  EXPECT_GT(report["fps"].get<double>(), 0.0);
  ASSERT_EQ(report["per_rank"].size(), 2u);
  for (const auto& rank : report["per_rank"]) {
    EXPECT_LE(rank["bricks_read"].get<uint64_t>(), rank["bricks_owned"].get<uint64_t>()) << rank.dump();
    EXPECT_GT(rank["composite_seconds"].get<double>(), 0.0);
  }
}

TEST(MpiRender, ARankThatCannotOpenTheFileEndsEveryRankWithOneLine) {
  TempDir dir;
  const std::string vdb = dir / "sphere.vdb", missing = dir / "missing.vdb", out = dir / "out.exr";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 32,32,32 --quiet").status, 0);
  // Open MPI's MPMD form: rank 0 opens the sphere, rank 1 a file that does not exist.
  const std::string command = "timeout 120 " + std::string(FCC_MPIEXEC) + " --allow-run-as-root --oversubscribe -np 1 " +
                              FCC_FCCVDB_EXE + " render " + vdb + " " + out + " --res 32x32 : -np 1 " + FCC_FCCVDB_EXE +
                              " render " + missing + " " + out + " --res 32x32";
  const auto started = std::chrono::steady_clock::now();
  const auto r = runShell(command);
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.status, 124) << "timed out: a rank hung";
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(), 100.0);
  int fccLines = 0;
  std::istringstream lines(r.err);
  for (std::string line; std::getline(lines, line);) fccLines += line.rfind("fccvdb:", 0) == 0;
  EXPECT_EQ(fccLines, 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("rank 1 of 2"));
  EXPECT_THAT(r.err, HasSubstr("missing.vdb"));
  EXPECT_FALSE(std::filesystem::exists(out)) << "nothing written";
}

}  // namespace
}  // namespace fcc::test
