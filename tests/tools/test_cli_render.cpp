// `fccvdb render` as a user meets it: the outputs and their channels, and one clear line (exit 1,
// nothing written) for each bad input the issue names.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "RunCommand.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;

TEST(CliRender, WritesExrWithTheContractChannelsAndPng) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb", exr = dir / "s.exr", png = dir / "s.png";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 24,24,24 --quiet").status, 0);
  const auto r = runFccvdb("render " + vdb + " -o " + exr + " --res 40x30 --iso 0.25 --quiet");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  Imf::InputFile file(exr.c_str());
  std::set<std::string> channels;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    channels.insert(it.name());
    EXPECT_EQ(it.channel().type, Imf::FLOAT) << it.name();
  }
  EXPECT_EQ(channels, (std::set<std::string>{"R", "G", "B", "A", "Z", "N.X", "N.Y", "N.Z"}));
  EXPECT_EQ(file.header().compression(), Imf::ZIP_COMPRESSION);
  const auto dw = file.header().dataWindow();
  EXPECT_EQ(dw.max.x - dw.min.x + 1, 40);
  EXPECT_EQ(dw.max.y - dw.min.y + 1, 30);
  ASSERT_EQ(runFccvdb("render " + vdb + " -o " + png + " --res 40x30 --quiet").status, 0);
  EXPECT_GT(std::filesystem::file_size(png), 100u);
  EXPECT_EQ(dir.fileCount(), 3) << "no temporary files left behind";
}

TEST(CliRender, BadInputsGiveOneLineStatus1AndNoOutput) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 16,16,16 --quiet").status, 0);
  const std::string cartesian = std::string(FCC_SHARED_DATA_DIR) + "/sphere.vdb";
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"render " + cartesian + " -o " + (dir / "a.png"), "convert"},
      {"render " + vdb + " -o " + (dir / "b.png") + " --iso nan", "finite"},
      {"render " + vdb + " -o " + (dir / "c.png") + " --iso inf", "finite"},
      {"render " + vdb + " -o " + (dir / "d.png") + " --res 0x64", "--res"},
      {"render " + vdb + " -o " + (dir / "e.png") + " --res 64", "WIDTHxHEIGHT"},
      {"render " + vdb + " -o " + dir.path.string() + "/missing/f.png", "not writable"},
      {"render " + vdb + " -o " + (dir / "g.jpg"), ".exr or .png"},
      {"render " + (dir / "nothere.vdb") + " -o " + (dir / "h.png"), "nothere.vdb"},
      {"render " + vdb + " -o " + (dir / "i.png") + " --eye 1,1,1 --lookat 1,1,1", "coincide"},
  };
  for (const Case& c : cases) {
    const auto r = runFccvdb(c.args);
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.says)) << c.args;
  }
  EXPECT_EQ(dir.fileCount(), 1) << "only the input: nothing written for a bad render";
}


// `bench render --json`: one row per layout and variant with the documented keys; --arc and
// --gpu-time reach the rows (a GPU time that is a positive number, within the frame's wall time
// allowing for the timer's own resolution).
TEST(CliRender, BenchRenderJsonHasTheDocumentedKeys) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 24,24,24 --quiet").status, 0);
  const auto r = runFccvdb("bench render " + vdb +
                           " --res 32x24 --frames 3 --warmup 1 --variants skip+analytic --layout texture-vec4"
                           " --arc 10 --gpu-time --json");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string check =
      "assert len(rows) == 1, rows\n"
      "r = rows[0]\n"
      "assert r['variant'] == 'skip+analytic' and r['layout'] == 'texture-vec4', r\n"
      "assert r['arc_degrees'] == 10 and r['res'] == [32, 24] and r['frames'] == 3, r\n"
      "assert r['fps'] > 0 and r['frame_ms'] > 0 and r['first_frame_seconds'] > 0, r\n"
      "assert r['gpu_frame_ms'] is not None and 0 < r['gpu_frame_ms'] <= 1.5 * r['frame_ms'], r\n";
  EXPECT_EQ(checkJsonWithPython(dir, r.out, check), 0) << r.out;
}

}  // namespace
}  // namespace fcc::test
