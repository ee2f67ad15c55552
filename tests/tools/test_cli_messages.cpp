// The messages and policies a user meets in the first hour (issue 16): what to try for a raw file
// with extra bytes, raw-only flags refused for other formats, one wording for an unwritable output,
// "did you mean" and the subcommand's own --help, render's positional output, --force for every
// output, and `bench render` (--layout auto, its progress bar, less work on a CPU renderer); statistics
// named for what they count.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "RunCommand.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

void writeBytes(const std::string& path, size_t n, char value = 7) { std::ofstream(path, std::ios::binary) << std::string(n, value); }

TEST(CliMessages, RawWithExtraBytesSuggestsTheHeaderSize) {
  TempDir dir;
  const std::string raw = dir / "head.den";
  writeBytes(raw, 62 + 8 * 8 * 8);
  const CommandResult r = runFccvdb("convert " + raw + " " + (dir / "o.vdb") + " --dims 8,8,8 --type u8 --quiet");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("62 extra bytes"));
  EXPECT_THAT(r.err, HasSubstr("try --header-bytes 62"));
  EXPECT_EQ(runFccvdb("convert " + raw + " " + (dir / "o.vdb") + " --dims 8,8,8 --type u8 --header-bytes 62 --quiet").status, 0);
  writeBytes(raw, 8 * 8 * 8 - 10);
  const CommandResult shortFile = runFccvdb("convert " + raw + " " + (dir / "p.vdb") + " --dims 8,8,8 --type u8 --quiet");
  EXPECT_THAT(shortFile.err, HasSubstr("10 bytes short"));
}

// An input that render, view or info would convert but cannot open is its one error line: no
// "converting ..." before it, no ITK warning block (a folder without a DICOM series).
TEST(CliMessages, AnInputThatCannotConvertIsOneLineWithoutConvertingFirst) {
  TempDir dir;
  const std::string folder = dir / "notdicom";
  std::filesystem::create_directories(folder);
  std::ofstream(folder + "/a.txt") << "not a DICOM file\n";
  const std::string raw = dir / "short.raw";
  writeBytes(raw, 8 * 8 * 8 - 10);
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"render " + folder + " " + (dir / "a.png"), "no DICOM series found in this folder"},
      {"info " + folder, "no DICOM series found in this folder"},
      {"render " + raw + " " + (dir / "b.png") + " --dims 8,8,8 --type u8", "10 bytes short"},
      {"info " + raw + " --dims 8,8,8 --type u8 --no-cache", "10 bytes short"},
  };
  for (const Case& c : cases) {
    const CommandResult r = runFccvdb(c.args);
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.says)) << c.args;
    EXPECT_THAT(r.err, Not(HasSubstr("converting"))) << c.args;
  }
}

// convert writes an OpenVDB file whatever OUTPUT is called: another extension is a slip, one line and
// nothing written.
TEST(CliMessages, ConvertRefusesAnOutputNotNamedVdb) {
  TempDir dir;
  const std::string raw = dir / "cube.raw";
  writeBytes(raw, 8 * 8 * 8);
  const CommandResult r = runFccvdb("convert " + raw + " " + (dir / "cube.png") + " --dims 8,8,8 --quiet");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("convert writes an OpenVDB file; name it .vdb"));
  EXPECT_FALSE(std::filesystem::exists(dir / "cube.png"));
  EXPECT_EQ(runFccvdb("convert " + raw + " " + (dir / "cube.VDB") + " --dims 8,8,8 --quiet").status, 0) << "any case";
}

TEST(CliMessages, RawOnlyFlagsAreRefusedForNifti) {
  TempDir dir;
  const std::string nifti = dir / "brain.nii";
  writeBytes(nifti, 400);  // refused by its extension before it is read
  for (const char* flag : {"--dims 4,4,4", "--type u16", "--header-bytes 62", "--endian big", "--spacing 2,2,2"}) {
    const CommandResult r = runFccvdb("convert " + nifti + " " + (dir / "o.vdb") + " " + flag);
    EXPECT_EQ(r.status, 1) << flag;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr("is for raw input only")) << flag;
  }
}

// convert and render say the same about a directory they cannot write into, before any work.
TEST(CliMessages, UnwritableOutputDirectorySaysSoTheSameWay) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 8,8,8 --quiet").status, 0);
  // root writes through permissions: /proc takes no files from anyone.
  std::string locked = dir / "locked";
  std::filesystem::create_directories(locked);
  std::filesystem::permissions(locked, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
  if (::geteuid() == 0) locked = "/proc";
  for (const std::string& args : {"convert " + vdb + " " + locked + "/o.vdb", "synth sphere " + locked + "/o.vdb --dims 8,8,8",
                                  "render " + vdb + " " + locked + "/o.png"}) {
    const CommandResult r = runFccvdb(args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr("cannot write there (directory '" + locked + "' is not writable")) << args;
  }
  for (const std::string& args : {"convert " + vdb + " " + (dir / "no/o.vdb"), "render " + vdb + " " + (dir / "no/o.png")}) {
    const CommandResult r = runFccvdb(args);
    EXPECT_EQ(r.status, 1) << args;
    EXPECT_THAT(r.err, HasSubstr("cannot write there (directory '" + (dir / "no") + "' does not exist)")) << args;
  }
  std::filesystem::permissions(dir / "locked", std::filesystem::perms::owner_all);
}

TEST(CliMessages, UnknownFlagSuggestsTheClosestAndTheSubcommandsHelp) {
  struct Case {
    std::string args, suggestion, help;
  };
  const Case cases[] = {
      {"render x.vdb out.png --isso 3", "--isso: did you mean --iso?", "(see fccvdb render --help)"},
      {"bench render x.vdb --layuot auto", "--layuot: did you mean --layout?", "(see fccvdb bench render --help)"},
      {"convert a.raw b.vdb --header-byte 62", "did you mean --header-bytes?", "(see fccvdb convert --help)"},
      {"info x.vdb --jsno", "did you mean --json?", "(see fccvdb info --help)"},
      // A flag the known one starts (or a longer spelling of it), and a word that names no command.
      {"render x.vdb out.png --isovalue 3", "--isovalue: did you mean --iso?", "(see fccvdb render --help)"},
      {"rendr x.vdb out.png", "unknown command 'rendr': did you mean render?", "see fccvdb --help"},
      {"bench rendr x.vdb", "unknown command 'rendr': did you mean render?", "see fccvdb bench --help"},
      {"xyzzy x.vdb", "unknown command 'xyzzy' (valid: bench, compare, convert", "see fccvdb --help"},
  };
  for (const Case& c : cases) {
    const CommandResult r = runFccvdb(c.args);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.suggestion)) << c.args << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.help)) << c.args << ": " << r.err;
  }
  // A one-letter flag gets no guess (-r is one edit from -h, which is no help).
  const CommandResult shortFlag = runFccvdb("render x.vdb out.png -r 64x64");
  EXPECT_EQ(shortFlag.status, 2);
  EXPECT_THAT(shortFlag.err, Not(HasSubstr("did you mean")));
  // Nothing close: no suggestion, still the subcommand's help.
  const CommandResult far = runFccvdb("synth sphere x.vdb --dims 8,8,8 --completely-unrelated");
  EXPECT_EQ(far.status, 2);
  EXPECT_THAT(far.err, Not(HasSubstr("did you mean")));
  EXPECT_THAT(far.err, HasSubstr("(see fccvdb synth --help)"));
}

// A value of the wrong type names the flag, the value and what is valid, not CLI11's "Could not
// convert"; words not expected are listed in the order given.
TEST(CliMessages, ParseErrorsSayTheFlagTheValueAndTheOrderGiven) {
  struct Case {
    std::string args, says;
  };
  const Case cases[] = {
      {"info x.vdb --iso abc", "--iso 'abc': expected a number"},
      {"bench render x.vdb --frames many", "--frames 'many': expected a whole number above 0"},
      {"bench render x.vdb --frames 0", "--frames '0': expected a whole number above 0"},
      {"render x.vdb o.png --stop-opacity 2", "--stop-opacity '2': expected a number from 0.5 to 1"},
      {"render x.vdb o.png --density-scale -1", "--density-scale '-1': expected a number 0 or more"},
      {"synth sphere x.vdb --dims 8,8,8 --seed x", "--seed 'x': expected a whole number"},
      {"info x.vdb first second", "were not expected: first second"},
  };
  for (const Case& c : cases) {
    const CommandResult r = runFccvdb(c.args);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.says)) << c.args << ": " << r.err;
    EXPECT_THAT(r.err, Not(HasSubstr("Could not convert"))) << c.args << ": " << r.err;
    EXPECT_THAT(r.err, Not(HasSubstr("000000"))) << c.args << ": " << r.err;
  }
}

// render FILE OUT as convert takes it, -o still works, one of them is needed, and an existing image
// is kept unless --force (as convert and synth keep theirs).
TEST(CliMessages, RenderTakesThePositionalOutputAndNeedsForceToOverwrite) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb", png = dir / "s.png";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 16,16,16 --quiet").status, 0);
  const CommandResult none = runFccvdb("render " + vdb);
  EXPECT_EQ(none.status, 2);
  EXPECT_THAT(none.err, HasSubstr("OUTPUT"));
  EXPECT_EQ(runFccvdb("render " + vdb + " " + png + " -o " + (dir / "t.png")).status, 2) << "one output, not two";

  const CommandResult first = runFccvdb("render " + vdb + " " + png + " --res 16x16 --quiet");
  if (failedForLackOfGl(first)) GTEST_SKIP() << first.err;
  ASSERT_EQ(first.status, 0) << first.err;
  ASSERT_TRUE(std::filesystem::exists(png));
  writeBytes(png, 5);  // so a rewrite would show
  const CommandResult again = runFccvdb("render " + vdb + " -o " + png + " --res 16x16 --quiet");
  EXPECT_EQ(again.status, 1);
  EXPECT_EQ(lineCount(again.err), 1) << again.err;
  EXPECT_THAT(again.err, HasSubstr("exists; pass --force to overwrite it"));
  EXPECT_EQ(std::filesystem::file_size(png), 5u) << "kept";
  ASSERT_EQ(runFccvdb("render " + vdb + " " + png + " --res 16x16 --quiet --force").status, 0);
  EXPECT_GT(std::filesystem::file_size(png), 5u);
}

// --layout auto (the default the help names for render) is accepted by bench render; the rows name
// the layout auto chose; the isovalue is the one info suggests.
TEST(CliMessages, BenchRenderAcceptsLayoutAuto) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 24,24,24 --quiet").status, 0);
  const CommandResult bad = runFccvdb("bench render " + vdb + " --layout sideways --res 16x16");
  EXPECT_EQ(bad.status, 1);
  EXPECT_THAT(bad.err, HasSubstr("auto or all")) << "checked before any rendering";
  const CommandResult r = runFccvdb("bench render " + vdb +
                                    " --layout auto --res 16x16 --frames 2 --warmup 0 --variants skip+analytic --json");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  const CommandResult info = runFccvdb("info " + vdb + " --json");
  const size_t at = info.out.find("\"suggested_iso\": ");
  ASSERT_NE(at, std::string::npos) << info.out;
  const double suggested = std::stod(info.out.substr(at + 17));
  const std::string check =
      "assert len(rows) == 1, rows\n"
      "assert rows[0]['layout'] in ('ssbo-vec4', 'ssbo-scalar', 'texture-vec4', 'texture-scalar'), rows\n"
      "assert abs(rows[0]['iso'] - " + std::to_string(suggested) + ") < 1e-4, rows\n";
  EXPECT_EQ(checkJsonWithPython(dir, r.out, check), 0) << r.out;
  // --layout all (the default where the renderer is a GPU's, given here since a CPU renderer's default
  // is auto): a row per layout. It was parsed as a layout before being expanded, and refused.
  const CommandResult all = runFccvdb("bench render " + vdb +
                                      " --layout all --res 16x16 --frames 1 --warmup 0 --variants skip+analytic --json");
  ASSERT_EQ(all.status, 0) << all.err;
  EXPECT_EQ(checkJsonWithPython(dir, all.out, "assert len(rows) == 4, rows\n"), 0) << all.out;
}

// On a CPU renderer the defaults shrink, with one warning naming what was scaled; the progress bar
// shows on a terminal (script(1) gives the command one).
TEST(CliMessages, BenchRenderOnACpuRendererScalesDownAndShowsProgress) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 16,16,16 --quiet").status, 0);
  // --res given (small, for the test's time): only the others are scaled.
  const CommandResult r = runFccvdb("bench render " + vdb + " --variants skip+analytic --res 16x16 --json");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  const bool cpu = r.out.find("llvmpipe") != std::string::npos;
  if (cpu) {
    EXPECT_THAT(r.err, HasSubstr("renders on the CPU: timing --layout auto, --frames 8, --warmup 1 instead of the defaults"));
    EXPECT_EQ(checkJsonWithPython(dir, r.out, "assert len(rows) == 1 and rows[0]['frames'] == 8, rows\n"), 0);
  } else {
    EXPECT_THAT(r.err, Not(HasSubstr("renders on the CPU")));
    EXPECT_EQ(checkJsonWithPython(dir, r.out, "assert len(rows) == 4 and rows[0]['frames'] == 60, rows\n"), 0);
  }
  if (std::system("command -v script >/dev/null 2>&1") != 0) return;
  const CommandResult tty = runShell("script -qec '" + std::string(FCC_FCCVDB_EXE) + " bench render " + vdb +
                                     " --variants skip+analytic --res 16x16 --frames 3 --warmup 0 --layout auto' /dev/null");
  EXPECT_EQ(tty.status, 0) << tty.out << tty.err;
  EXPECT_THAT(tty.out, HasSubstr("timing frames ["));
  EXPECT_THAT(tty.out, HasSubstr("100%"));
}

// Each figure says what it counts (issue 16, item 5), and the figures agree: convert's stored values are
// info's samples, bounds bricks (the spline may vary: the bricks with data and their neighbours) are
// at least the bricks with data, info's dims are the active data's box, and render's bricks loaded (the
// rays reached them) are at most those that hold the isovalue, as info --iso counts them.
TEST(CliMessages, StatisticsSayWhatTheyCountAndAgree) {
  TempDir dir;
  const std::string raw = dir / "ball.raw", vdb = dir / "ball.vdb";
  {
    std::ofstream out(raw, std::ios::binary);
    for (int k = 0; k < 24; ++k)
      for (int j = 0; j < 24; ++j)
        for (int i = 0; i < 24; ++i)
          out.put(char((i - 12) * (i - 12) + (j - 12) * (j - 12) + (k - 12) * (k - 12) < 64 ? 200 : 0));
  }
  const CommandResult convert = runFccvdb("convert " + raw + " " + vdb + " --dims 24,24,24 --type u8");
  ASSERT_EQ(convert.status, 0) << convert.err;
  std::smatch m;
  const std::string line = convert.err.substr(convert.err.find("wrote "));
  ASSERT_TRUE(std::regex_search(line, m,
                                std::regex("(\\d+) stored values in (\\d+) bricks \\(4 per active packed voxel: the "
                                           "coefficients of the FCC sites with data and the sites next to them\\), from "
                                           "(\\d+) input voxels; bounds: (\\d+) bricks where the spline may vary "
                                           "\\(those with data and their neighbours\\)")))
      << convert.err;
  const long long stored = std::stoll(m[1]), bricks = std::stoll(m[2]), input = std::stoll(m[3]), bounds = std::stoll(m[4]);
  EXPECT_EQ(input, 24 * 24 * 24);
  EXPECT_GE(bounds, bricks);
  EXPECT_EQ(stored % 4, 0);

  const CommandResult info = runFccvdb("info " + vdb + " --iso 100");
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("samples:       " + std::to_string(stored) + " stored values (4 per active packed voxel)"));
  EXPECT_THAT(info.out, HasSubstr("lattice points: the box of the active (stored) data, from ("));
  EXPECT_THAT(info.out, HasSubstr("bricks:        " + std::to_string(bricks) + " (8^3 packed voxels each)"));
  ASSERT_TRUE(std::regex_search(info.out, m, std::regex("iso 100: keeps (\\d+) bricks"))) << info.out;
  const long long kept = std::stoll(m[1]);

  const CommandResult render = runFccvdb("render " + vdb + " " + (dir / "b.png") + " --res 48x48 --iso 100");
  if (failedForLackOfGl(render)) GTEST_SKIP() << render.err;
  ASSERT_EQ(render.status, 0) << render.err;
  ASSERT_TRUE(std::regex_search(render.err, m,
                                std::regex("(\\d+) bricks loaded \\(the rays reached them; (\\d+) bricks hold the isovalue\\)")))
      << render.err;
  const long long loaded = std::stoll(m[1]), hold = std::stoll(m[2]);
  EXPECT_GT(loaded, 0);
  EXPECT_LE(loaded, hold) << "more loaded than needed";
  EXPECT_EQ(hold, kept) << "render and info count the bricks at the isovalue differently";
}

}  // namespace
}  // namespace fcc::test
