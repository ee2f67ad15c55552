// Damaged files, as a user meets them: seeded campaigns of bit flips, truncations and overwritten runs
// over small FCC files (synth, and a converted level set) run through `info`, `render` and `probe`:
// every run ends by itself with status 0 or 1, and a failure says so in one line; never a signal.
// And a brick whose bytes are damaged is rendered as a hole and named, exit 1 unless --allow-damaged; so is
// a damaged leaf of a Cartesian grid rendered as it is (--reconstruction).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "ExrRead.h"
#include "RunCommand.h"
#include "io/VdbLeafReader.h"
#include "sparse/FccGrid.h"
#include "tests/io/LeafDamage.h"
#include "tests/viewer/CartesianTestSupport.h"
#include "viewer/Camera.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// One seeded damage of `bytes`: a flipped bit, a truncation or an overwritten 32-byte run.
std::string damaged(const std::string& bytes, std::mt19937& rng, std::string& what) {
  std::string out = bytes;
  std::uniform_int_distribution<size_t> at(0, bytes.size() - 1);
  switch (rng() % 3) {
    case 0: {
      const size_t i = at(rng);
      out[i] = char(out[i] ^ char(1 << (rng() % 8)));
      what = "bit flip at " + std::to_string(i);
      break;
    }
    case 1: {
      const size_t n = at(rng);
      out.resize(n);
      what = "truncated to " + std::to_string(n);
      break;
    }
    default: {
      const size_t i = at(rng);
      for (size_t k = i; k < std::min(out.size(), i + 32); ++k) out[k] = char(rng());
      what = "32 bytes overwritten at " + std::to_string(i);
    }
  }
  return out;
}

// Status 0, or 1 with one line; never a signal (128 + N) or another status.
void expectOneLineOrSuccess(const CommandResult& r, const std::string& what) {
  EXPECT_TRUE(r.status == 0 || r.status == 1) << what << ": status " << r.status << "\n" << r.err;
  if (r.status == 1) {
    EXPECT_EQ(lineCount(r.err), 1) << what << "\n" << r.err;
  }
}

TEST(CliDamage, SeededCampaignEndsEveryRunWithStatus0Or1AndOneLine) {
  TempDir dir;
  const std::string synth = dir / "blobs.vdb", converted = dir / "sphere_fcc.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + synth + " --dims 40,40,40 --quiet").status, 0);
  ASSERT_EQ(runFccvdb("convert " + std::string(FCC_SHARED_DATA_DIR) + "/sphere.vdb " + converted + " --quiet").status, 0);
  std::mt19937 rng(20261201);
  int runs = 0;
  for (const std::string& source : {synth, converted}) {
    const std::string bytes = readBytes(source);
    for (int copy = 0; copy < 10; ++copy) {
      std::string what;
      const std::string bad = dir / "bad.vdb";
      writeBytes(bad, damaged(bytes, rng, what));
      what = source + ", " + what;
      expectOneLineOrSuccess(runFccvdb("info " + bad), "info " + what);
      expectOneLineOrSuccess(runFccvdb("render " + bad + " -o " + (dir / "bad.png") + " --res 24x24 --quiet --gpu-cache 8"),
                             "render " + what);
      expectOneLineOrSuccess(runFccvdb("probe " + bad, "0 0 0\n"), "probe " + what);
      runs += 3;
    }
  }
  EXPECT_EQ(runs, 60);
}

TEST(CliDamage, DamagedBrickIsAHoleNamedInOneLine) {
  TempDir dir;
  const std::string good = dir / "blobs.vdb", bad = dir / "bad.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + good + " --dims 40,40,40 --quiet").status, 0);
  // Damage inside one leaf's compressed values, which opening the file does not read: the uncompressed
  // size in the blosc header of its payload (the payload ends the record; its Int64 size prefix is
  // the one that says so).
  uint64_t recordBegin = 0, recordEnd = 0;
  {
    initializeVdb();
    const io::VdbLeafReader reader(good, "", {kFccTreeTypeName});
    ASSERT_GT(reader.leafCount(), 4u);
    const size_t leaf = reader.leafCount() / 2;
    recordBegin = reader.leafOffset(leaf);
    recordEnd = recordBegin + reader.leafBytes(leaf);
  }
  std::string bytes = readBytes(good);
  size_t payload = 0;
  for (uint64_t p = recordBegin + 65; p + 8 <= recordEnd && !payload; ++p) {
    int64_t size = 0;
    std::memcpy(&size, bytes.data() + p, 8);
    if (size > 16 && uint64_t(size) == recordEnd - (p + 8)) payload = size_t(p + 8);
  }
  ASSERT_NE(payload, 0u) << "no blosc payload found in the leaf's record";
  bytes[payload + 5] = char(bytes[payload + 5] ^ 0x40);  // nbytes: the uncompressed size
  writeBytes(bad, bytes);

  const CommandResult r = runFccvdb("render " + bad + " -o " + (dir / "a.png") + " --res 32x32 --quiet");
  if (failedForLackOfGl(r)) GTEST_SKIP() << r.err;
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("damaged brick"));
  EXPECT_THAT(r.err, HasSubstr("bad.vdb"));
  EXPECT_THAT(r.err, HasSubstr("--allow-damaged"));
  EXPECT_TRUE(std::filesystem::exists(dir / "a.png")) << "the image is written all the same";
  const CommandResult allowed =
      runFccvdb("render " + bad + " -o " + (dir / "b.png") + " --res 32x32 --quiet --allow-damaged");
  EXPECT_EQ(allowed.status, 0) << allowed.err;
  EXPECT_THAT(allowed.err, HasSubstr("damaged brick"));
  const CommandResult clean = runFccvdb("render " + good + " -o " + (dir / "c.png") + " --res 32x32 --quiet");
  EXPECT_EQ(clean.status, 0) << clean.err;
  EXPECT_EQ(clean.err, "");

  // info reads no brick, so it describes the damaged file; --check reads them all and names it.
  const CommandResult info = runFccvdb("info " + bad);
  EXPECT_EQ(info.status, 0) << info.err;
  const CommandResult check = runFccvdb("info " + bad + " --check");
  EXPECT_EQ(check.status, 1);
  EXPECT_EQ(lineCount(check.err), 1) << check.err;
  EXPECT_THAT(check.out, HasSubstr("1 damaged"));
  EXPECT_THAT(check.out, HasSubstr("damaged:       " + bad + ": leaf at"));
  const CommandResult checkJson = runFccvdb("info " + bad + " --check --json");
  EXPECT_THAT(checkJson.out, HasSubstr("\"bricks_damaged\": 1"));
  const CommandResult cleanCheck = runFccvdb("info " + good + " --check");
  EXPECT_EQ(cleanCheck.status, 0) << cleanCheck.err;
  EXPECT_THAT(cleanCheck.out, HasSubstr(", 0 damaged"));
}

// A damaged leaf of one coset of a BCC dataset: read as the background (a hole), named in one line and
// counted as a Cartesian grid's, the image written all the same; --allow-damaged exits 0.
TEST(CliDamage, DamagedBccLeafIsAHoleNamedInOneLine) {
  TempDir dir;
  const std::string good = dir / "wavy_bcc.vdb", bad = dir / "damaged_bcc.vdb";
  test::writeBccFile(good, test::wavy, 1.0, openvdb::Vec3d(0.0));  // coset voxels [0, 24)^3: leaves at 0, 8, 16
  std::filesystem::copy_file(good, bad);
  damageLeafValues(bad, {"Tree_float_5_4_3"}, openvdb::Coord(8, 8, 8));  // the first float grid: bcc_primary
  const std::string env = "FCCVDB_CACHE_DIR=" + (dir / "cache") + " ";
  const std::string flags = " --iso 0.35 --res 48x40 --quiet";
  const CommandResult clean = runShell(env + FCC_FCCVDB_EXE + " render " + good + " " + (dir / "good.png") + flags);
  if (failedForLackOfGl(clean)) GTEST_SKIP() << clean.err;
  ASSERT_EQ(clean.status, 0) << clean.err;
  EXPECT_EQ(clean.err, "");
  const CommandResult r = runShell(env + FCC_FCCVDB_EXE + " render " + bad + " " + (dir / "bad.png") + flags);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("1 damaged leaf rendered as holes"));
  EXPECT_THAT(r.err, HasSubstr(bad + ": leaf at (8, 8, 8) is damaged"));
  EXPECT_TRUE(std::filesystem::exists(dir / "bad.png")) << "the image is written all the same";
  const CommandResult allowed =
      runShell(env + FCC_FCCVDB_EXE + " render " + bad + " " + (dir / "allowed.png") + flags + " --allow-damaged");
  EXPECT_EQ(allowed.status, 0) << allowed.err;
  EXPECT_THAT(allowed.err, HasSubstr("1 damaged leaf"));
}

// `render --reconstruction trilinear` of a Cartesian .vdb with one damaged leaf: the frame renders and
// is written, one line names the file, the leaf and the damage (exit 1, or 0 with --allow-damaged, as
// for FCC bricks); every pixel whose ray passes nowhere near the leaf before its surface is the
// undamaged image's, bit for bit, and no surface lies inside the leaf (a trilinear cell blends the
// data with the background the leaf reads as only within one voxel of its faces).
TEST(CliDamage, DamagedCartesianLeafIsAHoleNamedInOneLine) {
  TempDir dir;
  const std::string good = dir / "plane.vdb", bad = dir / "damaged.vdb";
  const float background = 100.0f;  // the plane z = 20.5 of f = z; the background lies above it
  writeCartesianFile(good, [](const glm::ivec3& ijk) { return float(ijk.z); }, 1.0, openvdb::Vec3d(0.0), background);
  std::filesystem::copy_file(good, bad);
  damageLeafValues(bad, {"Tree_float_5_4_3"}, openvdb::Coord(16, 16, 16));
  const glm::dvec3 leafLo(16.0), leafHi(24.0);

  render::Camera camera;  // world = index space
  camera.eye = glm::dvec3(30.0, 18.0, 70.0);
  camera.lookat = glm::dvec3(22.0, 22.0, 20.0);
  camera.fovYDegrees = 55.0;
  const int w = 64, h = 48;
  const std::string env = "FCCVDB_CACHE_DIR=" + (dir / "cache") + " ";
  const std::string flags = " --reconstruction trilinear --iso 20.5 --res 64x48 --eye 30,18,70 --lookat 22,22,20 --up 0,1,0 --fov 55 --quiet";
  const CommandResult clean = runShell(env + FCC_FCCVDB_EXE + " render " + good + " " + (dir / "good.exr") + flags);
  if (failedForLackOfGl(clean)) GTEST_SKIP() << clean.err;
  ASSERT_EQ(clean.status, 0) << clean.err;
  EXPECT_EQ(clean.err, "");

  const CommandResult r = runShell(env + FCC_FCCVDB_EXE + " render " + bad + " " + (dir / "bad.exr") + flags);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("1 damaged leaf rendered as holes"));
  EXPECT_THAT(r.err, HasSubstr(bad + ": leaf at (16, 16, 16) is damaged"));
  EXPECT_THAT(r.err, HasSubstr("--allow-damaged"));
  EXPECT_TRUE(std::filesystem::exists(dir / "bad.exr")) << "the image is written all the same";
  const CommandResult allowed =
      runShell(env + FCC_FCCVDB_EXE + " render " + bad + " " + (dir / "allowed.exr") + flags + " --allow-damaged");
  EXPECT_EQ(allowed.status, 0) << allowed.err;
  EXPECT_EQ(lineCount(allowed.err), 1) << allowed.err;
  EXPECT_THAT(allowed.err, HasSubstr("1 damaged leaf"));

  int ew = 0, eh = 0;
  const char* channels[] = {"R", "G", "B", "A", "Z"};
  std::vector<std::vector<float>> before, after;
  for (const char* c : channels) {
    before.push_back(readExrChannel(dir / "good.exr", c, ew, eh));
    after.push_back(readExrChannel(dir / "allowed.exr", c, ew, eh));
  }
  ASSERT_EQ(ew, w);
  ASSERT_EQ(eh, h);
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  const auto meetsBox = [&](const glm::dvec3& d, double tMax, const glm::dvec3& lo, const glm::dvec3& hi) {
    double t0 = 0.0, t1 = tMax;
    for (int a = 0; a < 3; ++a) {
      double ta = (lo[a] - camera.eye[a]) / d[a], tb = (hi[a] - camera.eye[a]) / d[a];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    return t0 <= t1;
  };
  int unchanged = 0, holeBefore = 0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const std::size_t i = std::size_t(py) * w + px;
      const glm::dvec3 d = render::pixelRay(frame, px, py, w, h);
      const auto insideLeaf = [&](float depth) {  // more than one voxel inside its faces
        const glm::dvec3 p = camera.eye + double(depth) * d;
        return glm::all(glm::greaterThan(p, leafLo + 1.0)) && glm::all(glm::lessThan(p, leafHi - 1.0));
      };
      const bool hitBefore = before[3][i] > 0.5f, hitAfter = after[3][i] > 0.5f;
      holeBefore += hitBefore && insideLeaf(before[4][i]);
      EXPECT_FALSE(hitAfter && insideLeaf(after[4][i])) << "a surface inside the damaged leaf at pixel (" << px << ", " << py << ")";
      if (meetsBox(d, hitBefore ? double(before[4][i]) : 1e9, leafLo - 2.0, leafHi + 2.0)) continue;
      ++unchanged;
      for (int c = 0; c < 5; ++c)
        ASSERT_EQ(after[c][i], before[c][i]) << channels[c] << " of pixel (" << px << ", " << py << ")";
    }
  std::printf("%d pixels away from the damaged leaf unchanged; %d saw the plane inside it\n", unchanged, holeBefore);
  EXPECT_GT(unchanged, w * h / 10);
  EXPECT_GT(holeBefore, 20) << "the camera must see the plane inside the damaged leaf";
}

}  // namespace
}  // namespace fcc::test
