// `--lod-bias` and `--full-resolution` on `render` (docs/RENDERER.md, "Level of detail"): without them a
// file with a pyramid renders as the same file without one, bit for bit; with a bias the levels are
// drawn and `--json` says which; bad values are one line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ExrRead.h"
#include "RunCommand.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;

TEST(CliRender, LodBiasFlagsAndTheirMessages) {
  TempDir dir;
  const std::string plain = dir / "s.vdb", pyramid = dir / "s_lod.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + plain + " --dims 48,48,48 --quiet").status, 0);
  ASSERT_EQ(runFccvdb("synth sphere " + pyramid + " --dims 48,48,48 --pyramid --quiet").status, 0);
  const std::string common = " --res 40x30 --eye 70,50,80 --lookat 23.5,23.5,23.5 --iso 0.5 --quiet";
  const auto today = runFccvdb("render " + plain + " " + (dir / "today.exr") + common);
  if (failedForLackOfGl(today)) GTEST_SKIP() << today.err;
  ASSERT_EQ(today.status, 0) << today.err;
  // render draws full resolution unless --lod-bias: the pyramid's file, with and without
  // --full-resolution, and the plain file with --lod-bias (no pyramid: a note, full resolution).
  const auto same = runFccvdb("render " + pyramid + " " + (dir / "same.exr") + common + " --json");
  ASSERT_EQ(same.status, 0) << same.err;
  EXPECT_THAT(same.out, HasSubstr("\"level_mix\": ["));
  EXPECT_THAT(same.out, HasSubstr("\"full_resolution_fraction\": 1"));
  ASSERT_EQ(runFccvdb("render " + pyramid + " " + (dir / "full.exr") + common + " --full-resolution").status, 0);
  const auto noted = runFccvdb("render " + plain + " " + (dir / "noted.exr") + " --res 40x30 --eye 70,50,80 --lookat 23.5,23.5,23.5 --iso 0.5 --lod-bias 1");
  ASSERT_EQ(noted.status, 0) << noted.err;
  EXPECT_THAT(noted.err, HasSubstr("has no pyramid"));
  int w = 0, h = 0;
  for (const char* image : {"same.exr", "full.exr", "noted.exr"})
    for (const char* channel : {"R", "G", "B", "A", "Z", "N.X"})
      EXPECT_EQ(readExrChannel(dir / "today.exr", channel, w, h), readExrChannel(dir / image, channel, w, h)) << image << " " << channel;

  // A large bias: every brick from the coarsest level; the mix and the summary say so.
  const auto coarse = runFccvdb("render " + pyramid + " " + (dir / "coarse.exr") +
                                " --res 40x30 --eye 70,50,80 --lookat 23.5,23.5,23.5 --iso 0.5 --lod-bias 16 --json");
  ASSERT_EQ(coarse.status, 0) << coarse.err;
  EXPECT_THAT(coarse.out, HasSubstr("\"level_mix\": [0, "));
  EXPECT_THAT(coarse.out, HasSubstr("\"full_resolution_fraction\": 0"));
  EXPECT_THAT(coarse.err, HasSubstr("levels: L0 0 bricks"));
  const std::vector<float> alpha = readExrChannel(dir / "coarse.exr", "A", w, h);
  int hits = 0;
  for (float a : alpha) hits += a == 1.0f;
  EXPECT_GT(hits, 40) << "the coarsest level still shows the sphere";

  const char* bad[] = {"--lod-bias x", "--lod-bias nan", "--lod-bias 17", "--lod-bias -9", "--lod-bias 1x",
                       "--lod-bias 1 --full-resolution"};
  const int before = dir.fileCount();
  for (const char* flags : bad) {
    const auto r = runFccvdb("render " + pyramid + " " + (dir / "bad.png") + " " + flags);
    EXPECT_EQ(r.status, 1) << flags << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << flags << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr("--lod-bias")) << flags;
  }
  EXPECT_EQ(dir.fileCount(), before) << "nothing written for a bad --lod-bias";
}

// `--lookahead N` changes how many bricks a pass requests, never the image: with a pool too small for the
// frame (many passes), 0 and 16 give the default's EXR bit for bit.
TEST(CliRender, LookaheadChangesThePassesNotTheImage) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 96,96,96 --quiet").status, 0);
  const std::string common = " --res 48x36 --eye 150,90,160 --lookat 47.5,47.5,47.5 --iso 0.5 --gpu-cache 2 --json --quiet";
  const auto byDefault = runFccvdb("render " + vdb + " " + (dir / "default.exr") + common);
  if (failedForLackOfGl(byDefault)) GTEST_SKIP() << byDefault.err;
  ASSERT_EQ(byDefault.status, 0) << byDefault.err;
  int w = 0, h = 0;
  for (const char* lookahead : {"0", "16"}) {
    const std::string exr = dir / (std::string("la") + lookahead + ".exr");
    const auto r = runFccvdb("render " + vdb + " " + exr + common + " --lookahead " + lookahead);
    ASSERT_EQ(r.status, 0) << r.err;
    for (const char* channel : {"R", "A", "Z", "N.X", "N.Y", "N.Z"})
      EXPECT_EQ(readExrChannel(dir / "default.exr", channel, w, h), readExrChannel(exr, channel, w, h)) << lookahead << " " << channel;
  }
  for (const char* flags : {"--lookahead -1", "--lookahead 65", "--lookahead x"}) {
    const auto r = runFccvdb("render " + vdb + " " + (dir / "bad.png") + " " + flags);
    EXPECT_EQ(r.status, 2) << flags << "\n" << r.err;  // a flag's value out of its range: a usage error
    EXPECT_EQ(lineCount(r.err), 1) << flags << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr("--lookahead")) << flags;
  }
}

}  // namespace
}  // namespace fcc::test
