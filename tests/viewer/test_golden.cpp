// Golden images: `fccvdb convert` then `fccvdb render` of the real volumes in ../shared/data, compared
// with committed PNGs under a per-image tolerance. FCC_UPDATE_GOLDEN=1 rewrites the goldens (after a
// change that is meant to alter the images; look at them before committing).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tests/tools/PngRead.h"
#include "tests/tools/RunCommand.h"

namespace fcc {
namespace {

using test::readPng;
using test::Rgb8;
using test::runFccvdb;
using test::TempDir;

struct Golden {
  const char* name;        // tests/data/golden/<name>.png
  const char* convert;     // arguments after `convert INPUT OUT.vdb`
  const char* input;       // in ../shared/data
  const char* render;      // arguments after `render OUT.vdb -o OUT.png`
  double maxMeanAbs;       // mean absolute difference per channel, in 8-bit steps
  double maxBadFraction;   // fraction of pixels allowed to differ by more than kBadStep in any channel
};
constexpr int kBadStep = 24;

// Tolerances: llvmpipe and GPU drivers round the last float bits differently (FMA contraction), which
// moves a silhouette pixel or two; a real change to the surface moves many.
const Golden kGoldens[] = {
    {"engine_iso100", "--dims 256,256,128 --type u8", "engine_256x256x128_uint8.raw.gz",
     "--res 128x128 --iso 100", 0.5, 0.004},
    {"sphere_levelset_iso0", "", "sphere.vdb", "--res 128x128 --iso 0", 0.5, 0.004},
    // The default camera and isovalue of a NIfTI head (issue 16): upright, the face towards the viewer
    // (the patient axes convert records), at Otsu's threshold of the samples.
    {"ch2better_upright_default", "", "ch2better.nii.gz", "--res 128x128", 0.5, 0.004},
};

class GoldenImage : public ::testing::TestWithParam<Golden> {};

TEST_P(GoldenImage, MatchesWithinTolerance) {
  const Golden& g = GetParam();
  TempDir dir;
  const std::string input = std::string(FCC_SHARED_DATA_DIR) + "/" + g.input;
  if (!std::filesystem::exists(input)) GTEST_SKIP() << input << " is missing";
  const std::string vdb = dir / "data.vdb", png = dir / "out.png";
  const auto converted = runFccvdb("convert " + input + " " + vdb + " " + g.convert + " --quiet");
  ASSERT_EQ(converted.status, 0) << converted.err;
  const auto rendered = runFccvdb("render " + vdb + " -o " + png + " " + g.render + " --quiet");
  if (test::failedForLackOfGl(rendered))
    GTEST_SKIP() << rendered.err;
  ASSERT_EQ(rendered.status, 0) << rendered.err;

  const std::string goldenPath = std::string(FCC_SOURCE_DIR) + "/tests/data/golden/" + g.name + ".png";
  if (std::getenv("FCC_UPDATE_GOLDEN")) {
    std::filesystem::copy_file(png, goldenPath, std::filesystem::copy_options::overwrite_existing);
    GTEST_SKIP() << "rewrote " << goldenPath;
  }
  Rgb8 expected, actual;
  ASSERT_TRUE(readPng(goldenPath, expected)) << goldenPath;
  ASSERT_TRUE(readPng(png, actual));
  ASSERT_EQ(actual.width, expected.width);
  ASSERT_EQ(actual.height, expected.height);
  double sumAbs = 0.0;
  int bad = 0;
  const std::size_t n = std::size_t(actual.width) * actual.height;
  for (std::size_t i = 0; i < n; ++i) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(int(actual.pixels[3 * i + c]) - int(expected.pixels[3 * i + c]));
      sumAbs += d;
      worst = std::max(worst, d);
    }
    bad += worst > kBadStep;
  }
  const double meanAbs = sumAbs / double(3 * n), badFraction = double(bad) / double(n);
  std::printf("%s: mean |difference| %.3f steps, %.4f of pixels off by more than %d\n", g.name, meanAbs, badFraction,
              kBadStep);
  EXPECT_LE(meanAbs, g.maxMeanAbs);
  EXPECT_LE(badFraction, g.maxBadFraction);
}

INSTANTIATE_TEST_SUITE_P(SharedData, GoldenImage, ::testing::ValuesIn(kGoldens),
                         [](const ::testing::TestParamInfo<Golden>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace fcc
