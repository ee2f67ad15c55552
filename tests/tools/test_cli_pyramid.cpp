// `fccvdb pyramid` as a user meets it: a file with a pyramid renders exactly as without one (the
// renderer opens level 0); damaged, raw-sample and foreign inputs are refused in one line and left as
// they were; `synth --pyramid` and `info` show the levels; memory stays far below the data's size.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "MeasuredRun.h"
#include "RunCommand.h"
#include "io/VdbLeafReader.h"
#include "sparse/FccGrid.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(CliPyramid, AFileWithAPyramidRendersBitForBitAsWithout) {
  TempDir dir;
  const std::string plain = dir / "plain.vdb", levels = dir / "levels.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + plain + " --dims 64,64,64 --quiet").status, 0);
  const CommandResult p = runFccvdb("pyramid " + plain + " -o " + levels);
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_THAT(p.err, HasSubstr("levels"));
  const CommandResult a = runFccvdb("render " + plain + " -o " + (dir / "a.png") + " --res 64x48 --quiet");
  if (failedForLackOfGl(a)) GTEST_SKIP() << a.err;
  ASSERT_EQ(a.status, 0) << a.err;
  const CommandResult b = runFccvdb("render " + levels + " -o " + (dir / "b.png") + " --res 64x48 --quiet");
  ASSERT_EQ(b.status, 0) << b.err;
  const std::string imageA = readBytes(dir / "a.png"), imageB = readBytes(dir / "b.png");
  ASSERT_GT(imageA.size(), 100u);
  EXPECT_TRUE(imageA == imageB) << "the file with a pyramid renders otherwise than the file without";
}

TEST(CliPyramid, SynthWithPyramidAndInfoShowTheLevels) {
  TempDir dir;
  const std::string file = dir / "s.vdb";
  const CommandResult s = runFccvdb("synth sphere " + file + " --dims 80,80,80 --pyramid");
  ASSERT_EQ(s.status, 0) << s.err;
  const CommandResult info = runFccvdb("info " + file + " --json");
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_EQ(checkJsonWithPython(dir, info.out,
                                "d = rows\nL = d['levels']\n"
                                "assert len(L) >= 3, L\n"
                                "assert int(d['metadata']['fcc_lod_levels']) == len(L), d['metadata']\n"
                                "for k, l in enumerate(L):\n"
                                "    assert l['level'] == k and l['spacing'] == 2 ** k, l\n"
                                "    assert l['grid'] == ('sphere' if k == 0 else 'sphere.lod%d' % k), l\n"
                                "    assert l['voxel_size'][0] == L[0]['voxel_size'][0] * 2 ** k, l\n"
                                "assert L[-1]['bricks'] <= 8, L[-1]\n"),
            0)
      << info.out;
  const CommandResult text = runFccvdb("info " + file);
  EXPECT_THAT(text.out, HasSubstr("sphere.lod1: spacing 2"));
  const CommandResult bad = runFccvdb("synth sphere " + (dir / "t.vdb") + " --dims 8,8,8 --pyramid --no-prefilter");
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(lineCount(bad.err), 1) << bad.err;
  EXPECT_THAT(bad.err, HasSubstr("--pyramid"));
}

TEST(CliPyramid, DamagedInputIsRefusedInOneLineAndLeftUnchanged) {
  TempDir dir;
  const std::string good = dir / "good.vdb", bad = dir / "bad.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + good + " --dims 96,96,96 --quiet").status, 0);
  uint64_t recordBegin = 0, recordEnd = 0;
  {
    initializeVdb();
    const io::VdbLeafReader reader(good, "", {kFccTreeTypeName});
    ASSERT_GT(reader.leafCount(), 4u);
    const size_t leaf = reader.leafCount() / 2;
    recordBegin = reader.leafOffset(leaf);
    recordEnd = recordBegin + reader.leafBytes(leaf);
  }
  // The uncompressed size in the blosc header of one leaf's payload (as test_cli_damage does): the
  // file opens, that brick fails when read.
  std::string bytes = readBytes(good);
  size_t payload = 0;
  for (uint64_t p = recordBegin + 65; p + 8 <= recordEnd && !payload; ++p) {
    int64_t size = 0;
    std::memcpy(&size, bytes.data() + p, 8);
    if (size > 16 && uint64_t(size) == recordEnd - (p + 8)) payload = size_t(p + 8);
  }
  ASSERT_NE(payload, 0u) << "no blosc payload found in the leaf's record";
  bytes[payload + 5] = char(bytes[payload + 5] ^ 0x40);
  std::ofstream(bad, std::ios::binary | std::ios::trunc) << bytes;

  const CommandResult r = runFccvdb("pyramid " + bad);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("bad.vdb"));
  EXPECT_THAT(r.err, HasSubstr("damaged"));
  EXPECT_TRUE(readBytes(bad) == bytes) << "the damaged input was changed";
  EXPECT_EQ(dir.fileCount(), 2) << "temporary files were left behind";

  // A truncated file: refused when opened.
  std::ofstream(bad, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
  const CommandResult t = runFccvdb("pyramid " + bad);
  EXPECT_EQ(t.status, 1) << t.err;
  EXPECT_EQ(lineCount(t.err), 1) << t.err;
  EXPECT_EQ(readBytes(bad).size(), bytes.size() / 2);
  EXPECT_EQ(dir.fileCount(), 2) << "temporary files were left behind";
}

TEST(CliPyramid, RawSamplesAndForeignGridsAreRefusedInOneLine) {
  TempDir dir;
  const std::string samples = dir / "raw.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + samples + " --dims 24,24,24 --no-prefilter --quiet").status, 0);
  const std::string before = readBytes(samples);
  const CommandResult r = runFccvdb("pyramid " + samples);
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("--no-prefilter"));
  EXPECT_TRUE(readBytes(samples) == before);

  const CommandResult missing = runFccvdb("pyramid " + (dir / "none.vdb"));
  EXPECT_EQ(missing.status, 1);
  EXPECT_EQ(lineCount(missing.err), 1) << missing.err;

  const std::string out = dir / "o.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + out + " --dims 24,24,24 --quiet").status, 0);
  const CommandResult exists = runFccvdb("pyramid " + out + " -o " + samples);
  EXPECT_EQ(exists.status, 1);
  EXPECT_THAT(exists.err, HasSubstr("--force"));
  EXPECT_TRUE(readBytes(samples) == before);
}

// Peak memory: a dense dataset's pyramid grows the process by far less than the data's decoded size.
TEST(CliPyramid, MemoryGrowsFarLessThanTheData) {
  TempDir dir;
  const auto synth = [&](const std::string& name, int dim) {
    const std::string d = std::to_string(dim);
    const CommandResult r = runFccvdb("synth sphere " + (dir / name) + " --dims " + d + "," + d + "," + d +
                                      " --quiet --cl-device reference");
    ASSERT_EQ(r.status, 0) << r.err;
  };
  synth("tiny.vdb", 16);
  synth("big.vdb", 384);
  const MeasuredRun tiny = runMeasured({"pyramid", dir / "tiny.vdb", "--cl-device", "reference"}, dir);
  ASSERT_EQ(tiny.status, 0) << tiny.err;
  const MeasuredRun big = runMeasured({"pyramid", dir / "big.vdb", "--cl-device", "reference"}, dir);
  ASSERT_EQ(big.status, 0) << big.err;
  unsigned long long leaves = 0;
  const size_t at = big.err.find("0: spacing 1, ");
  ASSERT_NE(at, std::string::npos) << big.err;
  ASSERT_EQ(std::sscanf(big.err.c_str() + at, "0: spacing 1, %llu bricks", &leaves), 1) << big.err;
  const long dataKiB = long(leaves * 512 * 16 / 1024);
  const long growthKiB = big.peakRssKiB - tiny.peakRssKiB;
  ASSERT_GE(dataKiB, 64 * 1024) << "the dataset must be large against the process' own memory";
  // The topologies and bounds of every level (their top nodes: 512 KiB each for a Vec4f tree), a window
  // of level 0 (4 of its 24 slabs while level 1 is built, a batch's reach while it is written), level
  // 1's slab window and the leaves being copied. Loading level 0 alone would take all of the data.
  EXPECT_LT(growthKiB, dataKiB / 2) << "peak RSS " << big.peakRssKiB << " KiB against " << tiny.peakRssKiB
                                    << " KiB for a 16^3 sphere: grew by " << growthKiB << " KiB for " << dataKiB
                                    << " KiB of data";
  std::printf("pyramid of sphere 384^3: peak RSS %ld KiB (16^3: %ld KiB), growth %ld KiB for %ld KiB of data\n",
              big.peakRssKiB, tiny.peakRssKiB, growthKiB, dataKiB);
}

}  // namespace
}  // namespace fcc::test
