// Damaged files, as a user meets them: seeded campaigns of bit flips, truncations and overwritten runs
// over small FCC files (synth, and a converted level set) run through `info`, `render` and `probe`:
// every run ends by itself with status 0 or 1, and a failure says so in one line; never a signal.
// And a brick whose bytes are damaged is rendered as a hole and named, exit 1 unless --allow-damaged.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

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

}  // namespace
}  // namespace fcc::test
