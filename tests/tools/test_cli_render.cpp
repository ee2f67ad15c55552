// `fccvdb render` as a user meets it: the outputs and their channels, and one clear line (exit 1,
// nothing written) for each bad input the issue names.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>
#include <cmath>

#include "ExrRead.h"
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

// FCCVDB_SHADER_DEFINES (docs/RENDERER.md, a measurement knob): a knob reaches the shader (one DVR
// sub-step a piece changes the image), an empty setting is the default image, and anything but NAME=VALUE
// items is one line, exit 1, nothing written.
TEST(CliRender, ShaderDefinesReachTheShaderAndBadOnesGiveOneLine) {
  TempDir dir;
  const std::string vdb = dir / "ml.vdb";
  ASSERT_EQ(runFccvdb("synth marschner-lobb " + vdb + " --dims 24,24,24 --quiet").status, 0);
  const std::string flags = " --mode dvr --tf viridis --res 40x30 --quiet --force";
  const auto render = [&](const std::string& defines, const std::string& out) {
    return runShell("FCCVDB_SHADER_DEFINES='" + defines + "' " + std::string(FCC_FCCVDB_EXE) + " render " + vdb + " " + out + flags);
  };
  const CommandResult plain = runFccvdb("render " + vdb + " " + (dir / "plain.exr") + flags);
  if (failedForLackOfGl(plain)) GTEST_SKIP() << plain.err;
  ASSERT_EQ(plain.status, 0) << plain.err;
  ASSERT_EQ(render("", dir / "empty.exr").status, 0);
  ASSERT_EQ(render("FCC_DVR_FIXED_STEPS=1", dir / "one.exr").status, 0);
  EXPECT_EQ(readText(dir / "plain.exr"), readText(dir / "empty.exr")) << "an empty setting changes nothing";
  EXPECT_NE(readText(dir / "plain.exr"), readText(dir / "one.exr")) << "one sub-step a piece must change the image";
  const CommandResult bad = render("FCC_DVR_FIXED_STEPS=1; rm -rf x", dir / "bad.exr");
  EXPECT_EQ(bad.status, 1);
  EXPECT_THAT(bad.err, HasSubstr("FCCVDB_SHADER_DEFINES: ' ' is not allowed"));
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.exr"));
}

// A Cartesian .vdb renders as it is with each CC reconstruction; direct volume rendering writes
// R, G, B, A and Z (depth at opacity 0.5), no normals.
TEST(CliRender, CartesianReconstructionsAndDvrOutputs) {
  TempDir dir;
  const std::string cartesian = std::string(FCC_SHARED_DATA_DIR) + "/sphere.vdb";
  for (const char* recon : {"trilinear", "tricubic", "tricubic-bspline"}) {
    const std::string png = dir / (std::string(recon) + ".png");
    const auto r = runFccvdb("render " + cartesian + " " + png + " --res 32x24 --reconstruction " + recon);
    if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
    EXPECT_EQ(r.status, 0) << recon << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr("a level set's zero crossing")) << recon;
    EXPECT_TRUE(std::filesystem::exists(png)) << recon;
  }
  const std::string vdb = dir / "b.vdb", exr = dir / "b.exr";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 32,32,32 --quiet").status, 0);
  const auto r = runFccvdb("render " + vdb + " " + exr + " --res 40x30 --mode dvr --tf inferno --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  Imf::InputFile file(exr.c_str());
  std::set<std::string> channels;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) channels.insert(it.name());
  EXPECT_EQ(channels, (std::set<std::string>{"R", "G", "B", "A", "Z"}));
}

// --shading off is today's image, byte for byte, and on another; --shading on outside DVR is one line;
// --specular lights the shaded image and needs --shading on.
// --tf FILE.json:NAME renders that map of a file of several; a NAME it lacks is one line naming them.
TEST(CliRender, DvrShadingAndNamedParaViewMaps) {
  TempDir dir;
  const std::string vdb = dir / "b.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 32,32,32 --quiet").status, 0);
  const std::string plain = dir / "plain.png", off = dir / "off.png", on = dir / "on.png";
  const std::string common = " --res 40x30 --mode dvr --tf viridis --quiet";
  const auto r = runFccvdb("render " + vdb + " " + plain + common);
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_EQ(runFccvdb("render " + vdb + " " + off + common + " --shading off").status, 0);
  ASSERT_EQ(runFccvdb("render " + vdb + " " + on + common + " --shading on").status, 0);
  EXPECT_EQ(readText(plain), readText(off)) << "--shading off must be the unshaded image";
  EXPECT_NE(readText(plain), readText(on)) << "--shading on must shade";
  const auto iso = runFccvdb("render " + vdb + " " + (dir / "iso.png") + " --res 40x30 --shading on --quiet");
  EXPECT_NE(iso.status, 0);
  EXPECT_THAT(iso.err, HasSubstr("--shading on applies to --mode dvr"));
  EXPECT_EQ(std::count(iso.err.begin(), iso.err.end(), '\n'), 1) << iso.err;
  // --specular: a highlight on the shaded image; without --shading on, one line and no output.
  const std::string lit = dir / "lit.png", unlit = dir / "unlit.png";
  ASSERT_EQ(runFccvdb("render " + vdb + " " + lit + common + " --shading on --specular 0.8 --specular-power 4").status, 0);
  EXPECT_NE(readText(on), readText(lit)) << "--specular must show";
  const auto noShading = runFccvdb("render " + vdb + " " + unlit + common + " --specular 0.8");
  EXPECT_NE(noShading.status, 0);
  EXPECT_THAT(noShading.err, HasSubstr("add --shading on"));
  EXPECT_EQ(std::count(noShading.err.begin(), noShading.err.end(), '\n'), 1) << noShading.err;
  EXPECT_FALSE(std::filesystem::exists(unlit));
  const auto tooStrong = runFccvdb("render " + vdb + " " + unlit + common + " --shading on --specular 2");
  EXPECT_NE(tooStrong.status, 0);
  EXPECT_THAT(tooStrong.err, HasSubstr("--specular"));
  // --light: headlight is the default's image, byte for byte; AZIMUTH,ELEVATION another; without
  // --shading on, or malformed, one line and no output. The isosurface takes it too.
  const std::string headlight = dir / "headlight.png", side = dir / "side.png";
  const std::string litFlags = common + " --shading on --specular 0.8 --specular-power 4";
  ASSERT_EQ(runFccvdb("render " + vdb + " " + headlight + litFlags + " --light headlight").status, 0);
  EXPECT_EQ(readText(headlight), readText(lit)) << "--light headlight is the default";
  const auto sideLit = runFccvdb("render " + vdb + " " + side + litFlags + " --light 70,-20");
  ASSERT_EQ(sideLit.status, 0) << sideLit.err;
  EXPECT_NE(readText(side), readText(lit)) << "--light must show";
  for (const std::string& bad : {" --light 200,0", " --light 30", " --light 30,40,50", " --light up"}) {
    const auto r = runFccvdb("render " + vdb + " " + unlit + litFlags + bad);
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_THAT(r.err, HasSubstr("valid are headlight, kit, or AZIMUTH,ELEVATION in degrees")) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  // --light kit: another image again; the isosurface refuses it in one line.
  const std::string kit = dir / "kit.png";
  const auto kitLit = runFccvdb("render " + vdb + " " + kit + litFlags + " --light kit");
  ASSERT_EQ(kitLit.status, 0) << kitLit.err;
  EXPECT_NE(readText(kit), readText(lit)) << "--light kit must show";
  EXPECT_NE(readText(kit), readText(side)) << "--light kit is not the directional light";
  const auto isoKit = runFccvdb("render " + vdb + " " + unlit + " --res 40x30 --quiet --light kit");
  EXPECT_NE(isoKit.status, 0);
  EXPECT_THAT(isoKit.err, HasSubstr("--light kit lights --mode dvr --shading on"));
  EXPECT_EQ(std::count(isoKit.err.begin(), isoKit.err.end(), '\n'), 1) << isoKit.err;
  // bench render's JSON says how the frame was shaded.
  const auto bench = runFccvdb("bench render " + vdb + " --res 16x12 --frames 1 --warmup 0 --layout auto "
                               "--variants skip+analytic --json --mode dvr --tf viridis --shading on --specular 0.5 --light kit");
  ASSERT_EQ(bench.status, 0) << bench.err;
  EXPECT_EQ(checkJsonWithPython(dir, bench.out,
                                "assert rows[0]['shading'] == {'light': 'kit', 'specular': 0.5, 'specular_power': 20}, rows\n"),
            0)
      << bench.out;
  const auto lightUnshaded = runFccvdb("render " + vdb + " " + unlit + common + " --light 30,45");
  EXPECT_NE(lightUnshaded.status, 0);
  EXPECT_THAT(lightUnshaded.err, HasSubstr("--light lights the gradient shading in --mode dvr: add --shading on"));
  EXPECT_FALSE(std::filesystem::exists(unlit));
  const std::string isoDefault = dir / "iso.png", isoSide = dir / "iso_side.png";
  ASSERT_EQ(runFccvdb("render " + vdb + " " + isoDefault + " --res 40x30 --quiet").status, 0);
  ASSERT_EQ(runFccvdb("render " + vdb + " " + isoSide + " --res 40x30 --quiet --light -60,10").status, 0);
  EXPECT_NE(readText(isoDefault), readText(isoSide)) << "the isosurface's light must move";

  const std::string maps = dir / "maps.json";
  std::ofstream(maps) << R"([{"Name": "First", "RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1]},
                             {"Name": "Red Ramp", "RGBPoints": [0, 1, 0, 0, 1, 1, 0.5, 0.5], "Points": [0, 0, 0.5, 0, 1, 0.9, 0.5, 0]}])";
  const std::string first = dir / "first.png", named = dir / "named.png";
  ASSERT_EQ(runFccvdb("render " + vdb + " " + first + " --res 40x30 --mode dvr --quiet --tf " + maps).status, 0);
  const auto byName = runFccvdb("render " + vdb + " " + named + " --res 40x30 --mode dvr --quiet --tf '" + maps + ":Red Ramp'");
  ASSERT_EQ(byName.status, 0) << byName.err;
  EXPECT_NE(readText(first), readText(named)) << "the named map must be the second one";
  const auto missing = runFccvdb("render " + vdb + " " + (dir / "x.png") + " --res 40x30 --mode dvr --quiet --tf " + maps + ":Blue");
  EXPECT_NE(missing.status, 0);
  EXPECT_THAT(missing.err, HasSubstr("no colour map named 'Blue' (the file has 'First', 'Red Ramp')"));
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
}

// The camera render prints is the one it used: pasted back, it gives the same image bit for bit; by
// default it looks at the centre of info's world_bounds.
TEST(CliRender, PrintedCameraReproducesTheImageAndFramesTheWorldBounds) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb", first = dir / "a.png", second = dir / "b.png";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 24,20,28 --quiet").status, 0);
  const auto r = runFccvdb("render " + vdb + " " + first + " --res 48x32 --iso 0.25");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  const std::size_t at = r.err.find("camera: ");
  ASSERT_NE(at, std::string::npos) << r.err;
  const std::string flags = r.err.substr(at + 8, r.err.find('\n', at) - at - 8);
  EXPECT_THAT(flags, ::testing::MatchesRegex("--eye [^ ]+,[^ ]+,[^ ]+ --lookat [^ ]+ --up [^ ]+ --fov [^ ]+")) << flags;
  const auto again = runFccvdb("render " + vdb + " " + second + " --res 48x32 --iso 0.25 --quiet " + flags);
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(readText(first), readText(second)) << "the pasted camera gives another image: " << flags;
  // The default camera looks at the world bounds' centre.
  const auto info = runFccvdb("info " + vdb + " --json");
  ASSERT_EQ(info.status, 0) << info.err;
  const std::string lookat = flags.substr(flags.find("--lookat ") + 9, flags.find(" --up") - flags.find("--lookat ") - 9);
  EXPECT_EQ(checkJsonWithPython(dir, info.out,
                                "b = rows['world_bounds']\n"
                                "centre = [(lo + hi) / 2 for lo, hi in zip(b['min'], b['max'])]\n"
                                "lookat = [float(v) for v in '" + lookat + "'.split(',')]\n"
                                "assert all(lo < hi for lo, hi in zip(b['min'], b['max'])), b\n"
                                "assert all(abs(c - l) < 1e-6 * (1 + abs(c)) for c, l in zip(centre, lookat)), (centre, lookat)\n"),
            0)
      << info.out;
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
      {"render " + cartesian + " -o " + (dir / "a.png") + " --dims 4,4,4", "--dims is for raw input only"},
      {"render " + vdb + " -o " + (dir / "b.png") + " --iso nan", "finite"},
      {"render " + vdb + " -o " + (dir / "c.png") + " --iso inf", "finite"},
      {"render " + vdb + " -o " + (dir / "d.png") + " --res 0x64", "--res"},
      {"render " + vdb + " -o " + (dir / "e.png") + " --res 64", "WIDTHxHEIGHT"},
      {"render " + vdb + " -o " + dir.path.string() + "/missing/f.png", "cannot write there"},
      {"render " + vdb + " -o " + (dir / "g.jpg"), ".exr or .png"},
      {"render " + (dir / "nothere.vdb") + " -o " + (dir / "h.png"), "nothere.vdb"},
      {"render " + vdb + " -o " + (dir / "i.png") + " --eye 1,1,1 --lookat 1,1,1", "coincide"},
      {"render " + cartesian + " -o " + (dir / "j.png") + " --reconstruction nearest", "valid: trilinear"},
      {"render " + cartesian + " -o " + (dir / "k.png") + " --reconstruction barycentric", "not a BCC dataset"},
      {"render " + vdb + " -o " + (dir / "l.png") + " --reconstruction trilinear", "holds no grid of type Tree_float"},
      {"render " + vdb + " -o " + (dir / "m.png") + " --mode dvr --tf nope", "grayscale"},
      {"render " + vdb + " -o " + (dir / "n.png") + " --mode dvr --tf " + (dir / "nothere.json"), "nothere.json' is no such file"},
      {"render " + vdb + " -o " + (dir / "t.png") + " --camera " + (dir / "nothere.json"), "nothere.json: no such file"},
      {"render " + vdb + " -o " + (dir / "u.png") + " --clip 100,100,100,200,200,200", "holds none of"},
      // The other mode's flags, which would be ignored.
      {"render " + vdb + " -o " + (dir / "o.png") + " --tf viridis", "--tf applies to direct volume rendering: add --mode dvr"},
      {"render " + vdb + " -o " + (dir / "p.png") + " --density-scale 5", "--density-scale applies to direct volume rendering"},
      {"render " + vdb + " -o " + (dir / "q.png") + " --unit-distance 2", "--unit-distance applies to direct volume rendering"},
      {"render " + vdb + " -o " + (dir / "r.png") + " --mode dvr --iso 0.3", "--iso applies to --mode iso"},
      {"render " + vdb + " -o " + (dir / "s.png") + " --mode dvr --surface-opacity 0.5", "--surface-opacity applies to --mode iso"},
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
      "assert r['gpu_frame_ms'] is not None and 0 < r['gpu_frame_ms'] <= 1.5 * r['frame_ms'], r\n"
      "assert r['shading']['light'] == 'directional' and len(r['shading']['light_in_camera']) == 3, r\n";
  EXPECT_EQ(checkJsonWithPython(dir, r.out, check), 0) << r.out;
  // --variants takes a comma-separated list as well as several values.
  const auto two = runFccvdb("bench render " + vdb + " --res 16x16 --frames 1 --warmup 0 --variants skip+analytic,skip+fd"
                             " --layout texture-vec4 --json");
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_EQ(checkJsonWithPython(dir, two.out, "assert [r['variant'] for r in rows] == ['skip+analytic', 'skip+fd'], rows\n"), 0)
      << two.out;
}

// An isovalue outside the values the spline takes renders an empty image, exit 0, and says so once
// (bench render too; info, tests/tools/test_cli.cpp).
TEST(CliRender, IsoOutsideTheRangeWarnsInOneLine) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 24,24,24 --quiet").status, 0);
  const auto r = runFccvdb("render " + vdb + " -o " + (dir / "a.png") + " --res 32x32 --iso 1000 --quiet");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("isovalue 1000 is outside"));
  const auto inside = runFccvdb("render " + vdb + " -o " + (dir / "b.png") + " --res 32x32 --iso 0.5 --quiet");
  EXPECT_EQ(inside.status, 0) << inside.err;
  EXPECT_EQ(inside.err, "");
  // bench render times what it was given, and says the same.
  const auto bench = runFccvdb("bench render " + vdb + " --res 16x16 --iso 1000 --frames 1 --warmup 0 --layout auto "
                               "--variants skip+analytic --json");
  EXPECT_EQ(bench.status, 0) << bench.err;
  EXPECT_THAT(bench.err, HasSubstr("isovalue 1000 is outside the values the reconstruction takes in " + vdb));
}

// `render --reconstruction` keeps a Cartesian grid's brick ranges in the user cache beside the
// conversions (one .ccranges file, docs/FORMAT.md) and renders the same image from them; --no-cache
// neither reads nor writes one. (That a cached open reads no leaf: test_cartesian_store.)
TEST(CliRender, CartesianRangesAreKeptInTheUserCache) {
  TempDir dir;
  const std::string cache = dir / "cache", source = dir / "sphere.vdb";
  std::filesystem::copy_file(std::string(FCC_SHARED_DATA_DIR) + "/sphere.vdb", source);
  auto render = [&](const std::string& out, const std::string& extra) {
    return runShell("FCCVDB_CACHE_DIR=" + cache + " " + FCC_FCCVDB_EXE + " render " + source + " " + (dir / out) +
                    " --res 48x48 --quiet --reconstruction tricubic" + extra);
  };
  auto rangeFiles = [&] {
    int n = 0;
    std::error_code ec;
    for (auto& e : std::filesystem::directory_iterator(cache, ec)) n += e.path().extension() == ".ccranges";
    return n;
  };
  const CommandResult uncached = render("a.exr", " --no-cache");
  if (failedForLackOfGl(uncached)) GTEST_SKIP() << uncached.err;
  ASSERT_EQ(uncached.status, 0) << uncached.err;
  EXPECT_EQ(rangeFiles(), 0) << "--no-cache wrote a range file";
  ASSERT_EQ(render("b.exr", "").status, 0);
  EXPECT_EQ(rangeFiles(), 1);
  ASSERT_EQ(render("c.exr", "").status, 0);  // from the cache
  EXPECT_EQ(rangeFiles(), 1);
  int w = 0, h = 0;
  for (const char* c : {"R", "A", "Z"}) {
    const std::vector<float> a = readExrChannel(dir / "a.exr", c, w, h);
    EXPECT_EQ(readExrChannel(dir / "b.exr", c, w, h), a) << c;
    EXPECT_EQ(readExrChannel(dir / "c.exr", c, w, h), a) << c << ": the cached ranges gave another image";
  }
}

// Any input convert takes renders directly: converted once into the cache, then reused; a changed
// source is converted again; --no-cache converts into a temporary file that does not outlive the run.
TEST(CliRender, CartesianInputConvertsOnceIntoTheCacheAndIsReused) {
  TempDir dir;
  const std::string cache = dir / "cache", tmp = dir / "tmp", source = dir / "sphere.vdb";
  std::filesystem::create_directories(tmp);
  std::filesystem::copy_file(std::string(FCC_SHARED_DATA_DIR) + "/sphere.vdb", source);
  const std::string env = "FCCVDB_CACHE_DIR=" + cache + " TMPDIR=" + tmp + " ";
  auto render = [&](const std::string& input, const std::string& extra) {
    return runShell(env + FCC_FCCVDB_EXE + " render " + input + " -o " + (dir / "out.png") + " --res 48x48 --force" + extra);
  };
  auto cached = [&] {
    int n = 0;
    for (auto& e : std::filesystem::directory_iterator(cache)) n += e.path().extension() == ".vdb";
    return n;
  };
  const CommandResult first = render(source, "");
  if (failedForLackOfGl(first)) GTEST_SKIP() << first.err;
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_THAT(first.err, HasSubstr("converting " + source + " to FCC once"));
  EXPECT_THAT(first.err, HasSubstr("iso 0 (default: a level set's zero crossing),")) << "a level set's default isovalue is 0";
  EXPECT_EQ(cached(), 1);
  const CommandResult second = render(source, "");
  ASSERT_EQ(second.status, 0) << second.err;
  EXPECT_THAT(second.err, HasSubstr("using the FCC conversion of " + source));
  EXPECT_EQ(second.err.find("converting"), std::string::npos) << second.err;
  EXPECT_EQ(cached(), 1);

  // A new modification time is a changed source.
  std::filesystem::last_write_time(source, std::filesystem::last_write_time(source) + std::chrono::seconds(5));
  const CommandResult changed = render(source, "");
  ASSERT_EQ(changed.status, 0) << changed.err;
  EXPECT_THAT(changed.err, HasSubstr("converting"));
  EXPECT_EQ(cached(), 2);

  // The cache is bounded: with room for none, only the conversion in use stays.
  const CommandResult bounded = runShell("FCCVDB_CACHE_MAX_MIB=0 " + env + FCC_FCCVDB_EXE + " render " + source +
                                         " -o " + (dir / "out.png") + " --res 48x48 --iso 0.01 --force");
  ASSERT_EQ(bounded.status, 0) << bounded.err;
  EXPECT_EQ(cached(), 2) << "a cache hit evicts nothing";

  const CommandResult temporary = render(source, " --no-cache");
  ASSERT_EQ(temporary.status, 0) << temporary.err;
  EXPECT_THAT(temporary.err, HasSubstr("temporary"));
  EXPECT_EQ(cached(), 2);
  EXPECT_TRUE(std::filesystem::is_empty(tmp)) << "the temporary conversion is removed";

  // Raw input with its layout flags, as convert takes them.
  const std::string raw = dir / "cube.raw";
  {
    std::ofstream out(raw, std::ios::binary);
    for (int k = 0; k < 16; ++k)
      for (int j = 0; j < 16; ++j)
        for (int i = 0; i < 16; ++i) out.put(char(i > 3 && i < 12 && j > 3 && j < 12 && k > 3 && k < 12 ? 200 : 0));
  }
  const CommandResult rawRender = render(raw, " --dims 16,16,16 --type u8 --iso 100");
  ASSERT_EQ(rawRender.status, 0) << rawRender.err;
  EXPECT_EQ(cached(), 3);
  // Another conversion (other flags) into a cache with room for none evicts every other one.
  const CommandResult evicting = runShell("FCCVDB_CACHE_MAX_MIB=0 " + env + FCC_FCCVDB_EXE + " render " + raw + " -o " +
                                          (dir / "out.png") + " --res 48x48 --dims 16,16,16 --spacing 2,2,2 --iso 100 --force");
  ASSERT_EQ(evicting.status, 0) << evicting.err;
  EXPECT_EQ(cached(), 1);
  const CommandResult noDims = render(raw, "");
  EXPECT_EQ(noDims.status, 1);
  EXPECT_THAT(noDims.err, HasSubstr("--dims"));
}

// Several surfaces: --iso's list with --surface-color (';' or repeated) and --surface-opacity renders
// the nested spheres of the sphere field composited (opacity 0.75 through the translucent outer one
// alone, 1 through both); a one-value list with opacity 1 is today's image bit for bit; a value outside
// the data's range is a one-line warning; each bad list is one line naming its flag, exit 1, no output.
TEST(CliRender, SeveralSurfacesFlagsAndTheirMessages) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 24,24,24 --quiet").status, 0);
  const std::string common = " --res 40x30 --eye 30,20,40 --lookat 11.5,11.5,11.5 --quiet";
  const auto plain = runFccvdb("render " + vdb + " " + (dir / "plain.exr") + " --iso 0.25" + common);
  if (failedForLackOfGl(plain)) GTEST_SKIP() << plain.err;
  ASSERT_EQ(plain.status, 0) << plain.err;
  ASSERT_EQ(runFccvdb("render " + vdb + " " + (dir / "one.exr") + " --iso 0.25 --surface-opacity 1" + common).status, 0);
  int w = 0, h = 0;
  for (const char* channel : {"R", "G", "B", "A", "Z", "N.X"})
    EXPECT_EQ(readExrChannel(dir / "plain.exr", channel, w, h), readExrChannel(dir / "one.exr", channel, w, h)) << channel;

  const auto two = runFccvdb("render " + vdb + " " + (dir / "two.exr") +
                             " --iso 0.1,0.3 --surface-opacity 1,0.5 --surface-color '#ff0000' --surface-color 0.2,0.4,1 --res 40x30 "
                             "--eye 30,20,40 --lookat 11.5,11.5,11.5");
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_THAT(two.err, HasSubstr("isos 0.1 (opacity 1), 0.3 (opacity 0.5)"));
  const std::vector<float> alpha = readExrChannel(dir / "two.exr", "A", w, h);
  const std::vector<float> red = readExrChannel(dir / "two.exr", "R", w, h);
  const std::vector<float> depth = readExrChannel(dir / "two.exr", "Z", w, h);
  int outerOnly = 0, both = 0;
  for (std::size_t i = 0; i < alpha.size(); ++i) {
    outerOnly += std::abs(alpha[i] - 0.75f) < 1e-6f;
    both += alpha[i] == 1.0f;
    if (alpha[i] > 0.0f) {
      EXPECT_TRUE(std::isfinite(depth[i])) << "Z is the first crossing's";
    }
    if (alpha[i] == 1.0f) {
      EXPECT_GT(red[i], 0.0f) << "the inner surface is red";
    }
  }
  EXPECT_GT(outerOnly, 10);
  EXPECT_GT(both, 10);

  // --json names what the frame showed: every surface's isovalue, or in DVR the transfer function.
  const auto isoJson = runFccvdb("render " + vdb + " " + (dir / "j.exr") + " --iso 0.1,0.3 --json" + common);
  ASSERT_EQ(isoJson.status, 0) << isoJson.err;
  EXPECT_EQ(checkJsonWithPython(dir, isoJson.out,
                                "assert [round(v, 6) for v in rows['isovalues']] == [0.1, 0.3] and 'tf' not in rows, rows\n"), 0)
      << isoJson.out;
  const auto dvrJson = runFccvdb("render " + vdb + " " + (dir / "k.exr") + " --mode dvr --tf inferno --json" + common);
  ASSERT_EQ(dvrJson.status, 0) << dvrJson.err;
  EXPECT_EQ(checkJsonWithPython(dir, dvrJson.out, "assert rows['tf'] == 'inferno' and 'isovalues' not in rows, rows\n"), 0)
      << dvrJson.out;

  const auto outside = runFccvdb("render " + vdb + " " + (dir / "w.png") + " --iso 0.25,1000" + common);
  EXPECT_EQ(outside.status, 0) << outside.err;
  EXPECT_EQ(lineCount(outside.err), 1) << outside.err;
  EXPECT_THAT(outside.err, HasSubstr("isovalue 1000 is outside"));

  struct Case {
    std::string flags, says;
  };
  const Case cases[] = {
      {"--iso 0.1,x", "--iso '0.1,x': expected 1 to 4 finite isovalues"},
      {"--iso 0.1,0.2,0.3,0.4,0.5", "valid are 1 to 4"},
      {"--iso 0.1,0.2 --surface-opacity 1,2", "--surface-opacity '1,2': expected an opacity per surface, 0 to 1"},
      {"--iso 0.1,0.2 --surface-opacity 1,0.5,1", "3 opacities for 2 surfaces"},
      {"--iso 0.1 --surface-color '#ff0000;#00ff00'", "2 colours for 1 surface"},
      {"--iso 0.1 --surface-color red", "#rrggbb or r,g,b"},
      {"--iso 0.1 --surface-color '#ff00'", "#rrggbb or r,g,b"},
      {"--iso 0.1 --surface-color 1,2,0", "#rrggbb or r,g,b"},
  };
  const int before = dir.fileCount();
  for (const Case& c : cases) {
    const auto r = runFccvdb("render " + vdb + " " + (dir / "bad.png") + " " + c.flags);
    EXPECT_EQ(r.status, 1) << c.flags << "\n" << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << c.flags << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.says)) << c.flags;
  }
  EXPECT_EQ(dir.fileCount(), before) << "nothing written for a bad list";
}

}  // namespace
}  // namespace fcc::test
