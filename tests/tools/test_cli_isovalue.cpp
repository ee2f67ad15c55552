// Picking an isovalue (issue 16): `convert` records the samples' histogram, `info` reports its
// percentiles and the suggested isovalue (Otsu's threshold, background left out), and `render` and
// `bench render` use that same value without --iso; the two ranges are named the same everywhere.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "RunCommand.h"
#include "sparse/FccGrid.h"

namespace fcc::test {
namespace {

using ::testing::HasSubstr;

// A u8 raw volume of n^3 voxels, x fastest, value(i, j, k).
void writeRaw(const std::string& path, int n, const std::function<int(int, int, int)>& value) {
  std::ofstream out(path, std::ios::binary);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) out.put(char(value(i, j, k)));
}

// A number after `"key": ` in JSON text (the first occurrence).
double jsonValue(const std::string& json, const std::string& key) {
  const size_t at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return std::nan("");
  return std::stod(json.substr(at + key.size() + 4));
}

// Background 0 around two clusters of values: 100..110 in one box, 200..210 in another, with more
// voxels in the first. Otsu's threshold without the background lies in the gap (about 155); with it,
// between 0 and the clusters (about 50); the middle of the range (0 .. 210, plus the spline's
// overshoot) inside the first cluster. So only the intended rule passes.
TEST(CliIsovalue, DefaultIsOtsusThresholdWithoutTheBackground) {
  TempDir dir;
  const std::string raw = dir / "bimodal.raw", vdb = dir / "bimodal.vdb";
  writeRaw(raw, 32, [](int i, int j, int k) {
    const int wiggle = (i + j + k) % 11;
    if (i >= 4 && i < 28 && j >= 4 && j < 16 && k >= 4 && k < 28) return 100 + wiggle;
    if (i >= 8 && i < 24 && j >= 20 && j < 28 && k >= 8 && k < 24) return 200 + wiggle;
    return 0;
  });
  ASSERT_EQ(runFccvdb("convert " + raw + " " + vdb + " --dims 32,32,32 --type u8 --quiet").status, 0);
  const CommandResult info = runFccvdb("info " + vdb + " --json");
  ASSERT_EQ(info.status, 0) << info.err;
  const double suggested = jsonValue(info.out, "suggested_iso");
  EXPECT_GT(suggested, 150.0) << info.out;
  EXPECT_LT(suggested, 160.0) << info.out;
  EXPECT_THAT(info.out, HasSubstr("\"suggested_iso_basis\": \"Otsu"));
  const CommandResult text = runFccvdb("info " + vdb);
  EXPECT_THAT(text.out, HasSubstr("suggested iso: "));
  EXPECT_THAT(text.out, HasSubstr("data range:    0 .. 210"));
  EXPECT_THAT(text.out, HasSubstr("surface range: "));

  // render uses it without --iso, and says where it came from.
  const CommandResult render = runFccvdb("render " + vdb + " " + (dir / "a.png") + " --res 16x16");
  if (failedForLackOfGl(render)) GTEST_SKIP() << render.err;
  ASSERT_EQ(render.status, 0) << render.err;
  char expected[64];
  std::snprintf(expected, sizeof expected, "iso %g (default: Otsu", double(float(suggested)));
  EXPECT_THAT(render.err, HasSubstr(expected));
}

// Samples known exactly: value 16 k in slice k (0 .. 240), so each of the 16 values is held by the
// same number of FCC sites. The percentiles info reports are those of these samples to within one
// bin of the recorded histogram, and the histogram counts every site once.
TEST(CliIsovalue, PercentilesAreTheSamples) {
  TempDir dir;
  const int n = 16;
  const std::string raw = dir / "slices.raw", vdb = dir / "slices.vdb";
  writeRaw(raw, n, [](int, int, int k) { return 16 * k; });
  ASSERT_EQ(runFccvdb("convert " + raw + " " + vdb + " --dims 16,16,16 --type u8 --quiet").status, 0);
  std::vector<int> samples;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if ((i + j + k) % 2 == 0) samples.push_back(16 * k);
  std::sort(samples.begin(), samples.end());
  const CommandResult info = runFccvdb("info " + vdb + " --json");
  ASSERT_EQ(info.status, 0) << info.err;
  const double binWidth = 240.0 / 256.0;
  for (const int p : {1, 5, 25, 50, 75, 95, 99}) {
    const size_t rank = size_t(std::ceil(p / 100.0 * double(samples.size()))) - 1;  // nearest rank
    const double reported = jsonValue(info.out, std::to_string(p));
    EXPECT_NEAR(reported, samples[rank], binWidth) << p << "%\n" << info.out;
  }
  // Every FCC site counted once: the metadata's counts add up to n^3 / 2.
  const std::string check =
      "counts = [int(c) for c in rows['metadata']['fcc_sample_histogram'].split()]\n"
      "assert len(counts) == 256 and sum(counts) == 16 ** 3 // 2, (len(counts), sum(counts))\n"
      "assert counts[0] == 128 and counts[255] == 128, (counts[0], counts[255])\n"
      "assert rows['sample_min'] == 0 and rows['sample_max'] == 240\n";
  EXPECT_EQ(checkJsonWithPython(dir, info.out, check), 0) << info.out;
}

// A file without the histogram (written before it existed) falls back to the middle of the range the
// surface can take, and says it has no percentiles.
TEST(CliIsovalue, WithoutAHistogramTheMiddleOfTheSurfaceRange) {
  TempDir dir;
  const std::string vdb = dir / "blobs.vdb";
  ASSERT_EQ(runFccvdb("synth blobs " + vdb + " --dims 24,24,24 --quiet").status, 0);
  EXPECT_THAT(runFccvdb("info " + vdb + " --json").out, HasSubstr("\"percentiles\": {\"1\": "));
  initializeVdb();
  openvdb::io::File in(vdb);
  in.open();
  openvdb::GridPtrVecPtr grids = in.getGrids();
  in.close();
  ASSERT_TRUE((*grids)[0]->getMetadata<openvdb::StringMetadata>("fcc_sample_histogram"));
  (*grids)[0]->removeMeta("fcc_sample_histogram");
  openvdb::io::File(vdb).write(*grids);
  const CommandResult info = runFccvdb("info " + vdb + " --json");
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_THAT(info.out, HasSubstr("\"percentiles\": null"));
  EXPECT_THAT(info.out, HasSubstr("\"suggested_iso_basis\": \"the middle of the range the surface can take\""));
  EXPECT_NEAR(jsonValue(info.out, "suggested_iso"), 0.5 * (jsonValue(info.out, "min") + jsonValue(info.out, "max")), 1e-5)
      << info.out;
  EXPECT_THAT(runFccvdb("info " + vdb).out, HasSubstr("percentiles:   none"));
}

}  // namespace
}  // namespace fcc::test
