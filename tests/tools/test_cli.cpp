// The command line as a user meets it: help, flag errors, and the subcommands end to end.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "RunCommand.h"
#include "io/VdbFile.h"
#include "sparse/FccGrid.h"
#include "sparse/SynthFields.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;

TEST(Cli, HelpDescribesEverySubcommand) {
  const auto r = runFccvdb("--help");
  EXPECT_EQ(r.status, 0);
  for (const char* sub : {"bench", "convert", "info", "probe", "synth"}) EXPECT_THAT(r.out, HasSubstr(sub));
  for (const char* sub : {"bench", "bench preprocess", "convert", "info", "probe", "synth"}) {
    const auto h = runFccvdb(std::string(sub) + " --help");
    EXPECT_EQ(h.status, 0) << sub;
    EXPECT_THAT(h.out, HasSubstr("--")) << sub << " help lists its flags";
  }
}

TEST(Cli, BadFlagsGiveOneLineAndStatus2) {
  for (const char* args : {"", "nosuchcommand", "synth sphere", "synth sphere x.vdb --dims 1,2", "info --bogus x.vdb",
                           "convert", "synth cube x.vdb --dims 8,8,8", "convert a b --mode sideways"}) {
    const auto r = runFccvdb(args);
    EXPECT_EQ(r.status, 2) << "args: " << args << "\nstderr: " << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << "args: " << args << "\nstderr: " << r.err;
  }
}

TEST(Cli, SynthInfoProbeRoundTrip) {
  TempDir dir;
  const std::string vdb = dir / "sphere.vdb";
  auto r = runFccvdb("synth sphere " + vdb + " --dims 24,24,24 --quiet");
  ASSERT_EQ(r.status, 0) << r.err;
  r = runFccvdb("info " + vdb + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"lattice\": \"fcc\"", "\"samples\":", "\"bricks\":", "\"bytes\":", "\"min\":", "\"max\":"})
    EXPECT_THAT(r.out, HasSubstr(key));
  // The sphere field f = |x - c|^2 / R^2 (c = 11.5, R = 11.5) is quadratic: the spline reproduces it.
  r = runFccvdb("probe " + vdb, "11.5 11.5 11.5\n14 12 9.25\n");
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream lines(r.out);
  double v, gx, gy, gz;
  ASSERT_TRUE(lines >> v >> gx >> gy >> gz);
  EXPECT_NEAR(v, 0.0, 1e-5);
  EXPECT_NEAR(gx, 0.0, 1e-5);
  ASSERT_TRUE(lines >> v >> gx >> gy >> gz);
  const double R2 = 11.5 * 11.5;
  EXPECT_NEAR(v, (2.5 * 2.5 + 0.5 * 0.5 + 2.25 * 2.25) / R2, 1e-5);
  EXPECT_NEAR(gx, 2 * 2.5 / R2, 1e-5);
  EXPECT_NEAR(gy, 2 * 0.5 / R2, 1e-5);
  EXPECT_NEAR(gz, -2 * 2.25 / R2, 1e-5);
}

// synth --lattice cc: the field at every point of the embedding (the FCC file holds the even-sum half),
// as a float grid over the same world box, the background beyond; render draws it as it is.
TEST(Cli, SynthCartesianHoldsTheFieldAtEveryPointAndRenders) {
  TempDir dir;
  struct Case {
    const char* kind;
    glm::ivec3 dims;
    glm::dvec3 worldLo, worldHi;  // of the first and the last point
  };
  for (const Case& c : {Case{"marschner-lobb", {20, 18, 16}, glm::dvec3(-1.0), glm::dvec3(1.0)},
                        Case{"sphere", {12, 10, 9}, glm::dvec3(0.0), glm::dvec3(11.0, 9.0, 8.0)},
                        Case{"blobs", {40, 36, 33}, glm::dvec3(0.0), glm::dvec3(39.0, 35.0, 32.0)}}) {
    SCOPED_TRACE(c.kind);
    const std::string vdb = dir / (std::string(c.kind) + "_cc.vdb");
    const auto r = runFccvdb("synth " + std::string(c.kind) + " " + vdb + " --dims " + std::to_string(c.dims.x) + "," +
                             std::to_string(c.dims.y) + "," + std::to_string(c.dims.z) + " --lattice cc");
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("Cartesian float grid"));
    const openvdb::FloatGrid::Ptr grid = io::readFloatGrid(vdb);
    EXPECT_EQ(grid->getName(), c.kind);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_FOG_VOLUME);
    SynthSpec spec;
    spec.kind = c.kind;
    spec.dims = c.dims;
    const SynthField synth = makeSynthField(spec);
    const auto accessor = grid->getConstAccessor();
    int points = 0, wrong = 0;
    for (int z = -1; z <= c.dims.z; ++z)
      for (int y = -1; y <= c.dims.y; ++y)
        for (int x = -1; x <= c.dims.x; ++x) {
          const glm::ivec3 ijk(x, y, z);
          const bool inside = glm::all(glm::greaterThanEqual(ijk, glm::ivec3(0))) && glm::all(glm::lessThan(ijk, c.dims));
          const float expected = inside ? synth.field->sample(ijk) : synth.field->background();
          points += inside;
          if (accessor.getValue(openvdb::Coord(x, y, z)) != expected && ++wrong <= 5)
            ADD_FAILURE() << "(" << x << ", " << y << ", " << z << "): " << accessor.getValue(openvdb::Coord(x, y, z))
                          << ", the field " << expected;
        }
    EXPECT_EQ(wrong, 0) << "of " << points << " points";
    if (std::string(c.kind) != "blobs") {
      EXPECT_EQ(grid->activeVoxelCount(), openvdb::Index64(points));
    }
    const openvdb::Vec3d lo = grid->indexToWorld(openvdb::Coord(0)),
                         hi = grid->indexToWorld(openvdb::Coord(c.dims.x - 1, c.dims.y - 1, c.dims.z - 1));
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(lo[a], c.worldLo[a], 1e-12);
      EXPECT_NEAR(hi[a], c.worldHi[a], 1e-12);
    }
  }
  const std::string png = dir / "ml.png";
  const auto r = runFccvdb("render --reconstruction trilinear " + dir / "marschner-lobb_cc.vdb" + " -o " + png +
                           " --res 32x24 --quiet");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GT(std::filesystem::file_size(png), 100u);
  // The FCC-only flag says so in one line.
  const auto noPrefilter = runFccvdb("synth sphere " + dir / "x.vdb" + " --dims 8,8,8 --lattice cc --no-prefilter");
  EXPECT_EQ(noPrefilter.status, 1);
  EXPECT_EQ(lineCount(noPrefilter.err), 1) << noPrefilter.err;
}

// synth --lattice bcc: the field at the BCC sites (all coordinates even, or all odd) as the two coset
// grids, each where its sites lie; render draws it with a BCC reconstruction (barycentric without
// --reconstruction), info describes it, and the wrong lattice's reconstruction is one line either way.
TEST(Cli, SynthBccHoldsTheFieldAtTheBccSitesAndRenders) {
  TempDir dir;
  const glm::ivec3 dims(20, 18, 16);
  const std::string vdb = dir / "ml_bcc.vdb";
  const auto r = runFccvdb("synth marschner-lobb " + vdb + " --dims 20,18,16 --lattice bcc");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("BCC dataset"));
  SynthSpec spec;
  spec.kind = "marschner-lobb";
  spec.dims = dims;
  const SynthField synth = makeSynthField(spec);
  initializeVdb();
  openvdb::io::File file(vdb);
  file.open();
  int sites = 0, wrong = 0;
  for (int coset = 0; coset < 2; ++coset) {
    const auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(coset == 0 ? "bcc_primary" : "bcc_secondary"));
    ASSERT_TRUE(grid);
    const auto accessor = grid->getConstAccessor();
    for (int z = -1; z <= dims.z / 2; ++z)
      for (int y = -1; y <= dims.y / 2; ++y)
        for (int x = -1; x <= dims.x / 2; ++x) {
          const glm::ivec3 site = 2 * glm::ivec3(x, y, z) + coset;
          const bool inside = glm::all(glm::greaterThanEqual(site, glm::ivec3(0))) && glm::all(glm::lessThan(site, dims));
          const float expected = inside ? synth.field->sample(site) : synth.field->background();
          sites += inside;
          if (accessor.getValue(openvdb::Coord(x, y, z)) != expected && ++wrong <= 5)
            ADD_FAILURE() << "coset " << coset << " site (" << site.x << ", " << site.y << ", " << site.z << ")";
          // The voxel lies where its site does in the FCC and CC files of the same --dims.
          if (x == 3 && y == 2 && z == 1) {
            const openvdb::Vec3d world = grid->indexToWorld(openvdb::Coord(x, y, z));
            const glm::dvec3 expectedWorld = -1.0 + 2.0 * glm::dvec3(site) / glm::dvec3(dims - 1);
            for (int a = 0; a < 3; ++a) EXPECT_NEAR(world[a], expectedWorld[a], 1e-12) << "coset " << coset;
          }
        }
  }
  file.close();
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(sites, 10 * 9 * 8 * 2);  // a quarter of the 20 x 18 x 16 points
  const auto info = runFccvdb("info " + vdb + " --json");
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("\"lattice\": \"bcc\""));
  for (const char* recon : {"", " --reconstruction sheared-trilinear", " --reconstruction bilinear"}) {
    const std::string png = dir / "ml_bcc.png";
    const auto render = runFccvdb("render " + vdb + " -o " + png + " --res 32x24 --force" + recon);
    if (failedForLackOfGl(render)) GTEST_SKIP() << render.err;
    ASSERT_EQ(render.status, 0) << recon << ": " << render.err;
    EXPECT_GT(std::filesystem::file_size(png), 100u);
  }
  // Paper 002's projected tetrahedra: DVR of the barycentric field; other modes and schemes in one line.
  const auto tetra = runFccvdb("render " + vdb + " -o " + (dir / "pt.png") + " --res 32x24 --mode dvr --tf viridis --dvr-method tetrahedra");
  ASSERT_EQ(tetra.status, 0) << tetra.err;
  EXPECT_THAT(tetra.err, HasSubstr("projected tetrahedra"));
  EXPECT_GT(std::filesystem::file_size(dir / "pt.png"), 100u);
  for (const std::string& bad : {std::string(" --dvr-method tetrahedra"), std::string(" --mode dvr --dvr-method tetrahedra --reconstruction bilinear"),
                                 std::string(" --mode dvr --dvr-method tetrahedra --clip 0,0,0,0.5,0.5,0.5")}) {
    const auto refused = runFccvdb("render " + vdb + " -o " + (dir / "z.png") + bad);
    EXPECT_EQ(refused.status, 1) << bad;
    EXPECT_EQ(lineCount(refused.err), 1) << refused.err;
  }
  // The wrong lattice's reconstruction, each way: one line naming the valid ones.
  const auto cc = runFccvdb("render " + vdb + " -o " + (dir / "x.png") + " --reconstruction trilinear");
  EXPECT_EQ(cc.status, 1);
  EXPECT_EQ(lineCount(cc.err), 1) << cc.err;
  EXPECT_THAT(cc.err, HasSubstr("barycentric, sheared-trilinear"));
  ASSERT_EQ(runFccvdb("synth sphere " + dir / "s_cc.vdb" + " --dims 12,12,12 --lattice cc --quiet").status, 0);
  const auto bcc = runFccvdb("render " + dir / "s_cc.vdb" + " -o " + (dir / "y.png") + " --reconstruction barycentric");
  EXPECT_EQ(bcc.status, 1);
  EXPECT_EQ(lineCount(bcc.err), 1) << bcc.err;
  EXPECT_THAT(bcc.err, HasSubstr("not a BCC dataset"));
}

TEST(Cli, ProbeFarFromDataIsTheBackground) {
  TempDir dir;
  const std::string vdb = dir / "blobs.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 32,32,32 --quiet").status, 0);
  const auto r = runFccvdb("probe " + vdb, "-100 -100 -100\n500 3 3\n");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "0 0 0 0\n0 0 0 0\n");
}

TEST(Cli, ProbeNamesTheLineThatDoesNotParse) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 8,8,8 --quiet").status, 0);
  const auto r = runFccvdb("probe " + vdb, "1 2 3\n4 five 6\n");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("line 2"));
  EXPECT_EQ(lineCount(r.err), 1);
}

TEST(Cli, SynthRefusesToOverwriteWithoutForce) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 8,8,8 --quiet").status, 0);
  auto r = runFccvdb("synth sphere " + vdb + " --dims 8,8,8 --quiet");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.err, HasSubstr("--force"));
  r = runFccvdb("synth sphere " + vdb + " --dims 8,8,8 --quiet --force");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(dir.fileCount(), 1) << "no temporary file is left beside the output";
}

// A Cartesian input is described as render draws it: converted once into the cache render uses (the
// second info, and render, reuse it), the FCC file named; a .vdb with nothing to convert is one line.
TEST(Cli, InfoDescribesACartesianInputAsRenderDrawsIt) {
  const std::string sphere = std::string(FCC_SHARED_DATA_DIR) + "/sphere.vdb";
  if (!std::ifstream(sphere)) GTEST_SKIP() << "missing " << sphere;
  TempDir dir;
  const std::string cache = "FCCVDB_CACHE_DIR=" + (dir / "cache") + " ";
  const auto first = runShell(cache + FCC_FCCVDB_EXE + " info " + sphere);
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_THAT(first.out, HasSubstr("file:          " + sphere));
  EXPECT_THAT(first.out, HasSubstr("converted:     " + (dir / "cache")));
  EXPECT_THAT(first.out, HasSubstr("surface range:"));
  const auto json = runShell(cache + FCC_FCCVDB_EXE + " info " + sphere + " --json");
  ASSERT_EQ(json.status, 0) << json.err;
  EXPECT_THAT(json.err, HasSubstr("using the FCC conversion of")) << "the second info converts nothing";
  EXPECT_EQ(checkJsonWithPython(dir, json.out,
                                "assert rows['file'].endswith('sphere.vdb') and rows['converted'].startswith(sys.argv[1].rsplit('/', 1)[0] + '/cache'), rows\n"
                                "assert rows['lattice'] == 'fcc' and rows['bricks'] > 0, rows\n"),
            0)
      << json.out;
  // An FCC file is described as it is.
  const std::string fcc = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + fcc + " --dims 8,8,8 --quiet").status, 0);
  const auto direct = runFccvdb("info " + fcc + " --json");
  ASSERT_EQ(direct.status, 0) << direct.err;
  EXPECT_THAT(direct.out, HasSubstr("\"converted\": null"));
  // Raw-only flags for an input that is not raw would be ignored: one line, as render says it.
  const auto rawFlag = runFccvdb("info " + fcc + " --dims 8,8,8");
  EXPECT_EQ(rawFlag.status, 1) << rawFlag.err;
  EXPECT_EQ(lineCount(rawFlag.err), 1) << rawFlag.err;
  EXPECT_THAT(rawFlag.err, HasSubstr("--dims"));
}

TEST(Cli, CorruptVdbGivesOneLineNoCrash) {
  TempDir dir;
  const std::string good = dir / "good.vdb";
  ASSERT_EQ(runFccvdb("synth marschner-lobb " + good + " --dims 32,32,32 --quiet").status, 0);
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Truncated at several places, and with bytes flipped in the middle.
  for (double cut : {0.1, 0.5, 0.9}) {
    const std::string bad = dir / "cut.vdb";
    std::ofstream(bad, std::ios::binary) << bytes.substr(0, size_t(bytes.size() * cut));
    const auto r = runFccvdb("info " + bad);
    EXPECT_EQ(r.status, 1) << "cut at " << cut << ": " << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr("cut.vdb"));
    // probe reads through OpenVDB, after our own parse of the header: the cut is named, not
    // OpenVDB's "Grid type  is not registered".
    const auto p = runFccvdb("probe " + bad, "1 1 1\n");
    EXPECT_EQ(p.status, 1) << "cut at " << cut << ": " << p.err;
    EXPECT_EQ(lineCount(p.err), 1) << p.err;
    EXPECT_THAT(p.err, Not(HasSubstr("not registered"))) << p.err;
    if (cut > 0.2) {
      EXPECT_THAT(p.err, HasSubstr("truncated")) << p.err;
    }
  }
  std::string flipped = bytes;
  for (size_t i = flipped.size() / 3; i < flipped.size() / 3 + 64; ++i) flipped[i] = char(~flipped[i]);
  const std::string bad = dir / "flipped.vdb";
  std::ofstream(bad, std::ios::binary) << flipped;
  const auto r = runFccvdb("info " + bad);
  EXPECT_LE(r.status, 1) << "no crash: " << r.err;
  EXPECT_LE(lineCount(r.err), 1) << r.err;
}

TEST(Cli, InfoReportsTheBoundsHierarchyForAnIsovalue) {
  TempDir dir;
  const std::string vdb = dir / "sphere.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 40,40,40 --quiet").status, 0);
  auto r = runFccvdb("info " + vdb + " --iso 0.5 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* key : {"\"lattice\":", "\"samples\":", "\"bricks\":", "\"bytes\":", "\"min\":", "\"max\":",
                          "\"range_from\": \"bounds\"", "\"sample_min\":", "\"sample_max\":",
                          "\"bounds\": {\"bricks\":", "\"nodes1\":", "\"nodes2\":", "\"iso\": 0.5", "\"bricks_kept\":",
                          "\"nodes1_kept\":", "\"nodes2_kept\":"})
    EXPECT_THAT(r.out, HasSubstr(key));
  // The JSON parses, and an isovalue inside the data keeps some but not all bricks.
  const std::string json = dir / "info.json";
  std::ofstream(json) << r.out;
  EXPECT_EQ(std::system(("python3 -c \"import json,sys; b=json.load(open('" + json +
                         "'))['bounds']; sys.exit(0 if 0 < b['bricks_kept'] < b['bricks'] else 1)\"").c_str()),
            0)
      << r.out;
  r = runFccvdb("info " + vdb + " --iso 0.5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("bounds:"));
  EXPECT_THAT(r.out, HasSubstr("iso 0.5: keeps"));
  EXPECT_EQ(r.err, "") << "an isovalue inside the range warns";
  // Outside the data's range nothing is kept, and info says so in one line with the valid range, as
  // render does (on stderr: the JSON stays one object).
  r = runFccvdb("info " + vdb + " --iso 1000 --json");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("\"bricks_kept\": 0, \"nodes1_kept\": 0, \"nodes2_kept\": 0"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("isovalue 1000 is outside the values the reconstruction takes in " + vdb + " ("));
  EXPECT_THAT(r.err, HasSubstr("pick --iso in that range"));
}

TEST(Cli, BadIsoOrDeviceGivesOneLine) {
  TempDir dir;
  const std::string vdb = dir / "s.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 8,8,8 --quiet").status, 0);
  for (const char* iso : {"nan", "inf", "-inf"}) {
    const auto r = runFccvdb("info " + vdb + " --iso " + iso);
    EXPECT_EQ(r.status, 1) << iso << ": " << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr("--iso"));
  }
  auto r = runFccvdb("info " + vdb + " --iso twelve");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  for (const std::string& cmd : {"synth sphere " + dir / "t.vdb" + " --dims 8,8,8", "bench preprocess " + vdb}) {
    r = runFccvdb(cmd + " --cl-device fastest");
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(lineCount(r.err), 1) << r.err;
    for (const char* valid : {"auto", "cpu", "gpu", "reference"}) EXPECT_THAT(r.err, HasSubstr(valid));
  }
  r = runFccvdb("synth sphere " + dir / "t.vdb" + " --dims 8,8,8 --cl-device 99");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("reference"));
}

TEST(Cli, NoOpenClFallsBackToTheReferenceWithOneLine) {
  TempDir dir;
  // The ICD loader finds no platform in an empty vendor directory.
  const std::string vdb = dir / "s.vdb";
  ::setenv("OCL_ICD_VENDORS", dir.path.c_str(), 1);
  const auto r = runFccvdb("synth sphere " + vdb + " --dims 16,16,16");
  ::unsetenv("OCL_ICD_VENDORS");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("OpenCL unavailable"));
  EXPECT_THAT(r.err, HasSubstr("using the CPU reference path"));
  EXPECT_THAT(r.err, HasSubstr("reference (C++/TBB)"));
}

TEST(Cli, FilesWithoutBoundsSayNone) {
  TempDir dir;
  const std::string vdb = dir / "old.vdb";
  ASSERT_EQ(runFccvdb("synth sphere " + vdb + " --dims 16,16,16 --quiet").status, 0);
  // Keep only the FCC grid, as files written before bounds existed.
  initializeVdb();
  openvdb::io::File in(vdb);
  in.open();
  openvdb::GridPtrVecPtr grids = in.getGrids();
  in.close();
  ASSERT_EQ(grids->size(), 2u);
  grids->pop_back();
  openvdb::io::File(vdb).write(*grids);
  auto r = runFccvdb("info " + vdb + " --iso 0.5 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("\"bounds\": null"));
  r = runFccvdb("info " + vdb);
  EXPECT_THAT(r.out, HasSubstr("bounds:        none"));
}

TEST(Cli, BenchPreprocessJsonHasTheRequiredKeys) {
  TempDir dir;
  const std::string vdb = dir / "blobs.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 48,48,48 --quiet").status, 0);
  const auto r = runFccvdb("bench preprocess " + vdb + " --json --repetitions 1 --warmup 0");
  ASSERT_EQ(r.status, 0) << r.err;
  // Both stages on the reference path (and on each OpenCL device), with positive rates.
  const std::string check =
      "assert all(k in r for r in rows for k in ('stage', 'device', 'samples_per_second', 'seconds', 'samples'))\n"
      "assert all(r['samples_per_second'] > 0 for r in rows)\n"
      "assert {(r['stage'], r['device']) for r in rows} >= {('prefilter', 'reference (C++/TBB)'), ('bounds', 'reference (C++/TBB)')}\n";
  EXPECT_EQ(checkJsonWithPython(dir, r.out, check), 0) << r.out;
}

}  // namespace
}  // namespace fcc::test
