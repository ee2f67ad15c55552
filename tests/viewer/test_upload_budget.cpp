// viewer/UploadBudget.h: a frame's upload time is what the frame budget leaves after the last frame's
// other work, within [least, most], and never grows when the other work grows.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "viewer/UploadBudget.h"

namespace fcc::render {
namespace {

constexpr double kBudget = 1.0 / 60.0, kMost = 0.004;

TEST(UploadBudget, UnknownOrCheapRestGivesTheCap) {
  EXPECT_EQ(uploadSecondsWithin(kBudget, -1.0, kMost), kMost);
  EXPECT_EQ(uploadSecondsWithin(kBudget, std::numeric_limits<double>::quiet_NaN(), kMost), kMost);
  EXPECT_EQ(uploadSecondsWithin(kBudget, 0.0, kMost), kMost);
  EXPECT_EQ(uploadSecondsWithin(kBudget, 0.005, kMost), kMost);  // an orbit's frame on the H200
}

TEST(UploadBudget, LongRestLeavesWhatTheBudgetHasLeftAndAtLeastTheFloor) {
  // The zoom's slow frames on the H200: about 13.5 ms besides the uploads.
  const double rest = 0.0135;
  const double upload = uploadSecondsWithin(kBudget, rest, kMost);
  EXPECT_NEAR(upload, kBudget * (1.0 - kUploadHeadroom) - rest, 1e-15);
  EXPECT_LE(rest + upload, kBudget * (1.0 - kUploadHeadroom) + 1e-15);
  // A pass that alone fills the budget still gets the floor; a cap below the floor is kept.
  EXPECT_EQ(uploadSecondsWithin(kBudget, 0.030, kMost), kLeastUploadSeconds);
  EXPECT_EQ(uploadSecondsWithin(kBudget, 0.030, 0.0002), 0.0002);
  EXPECT_EQ(uploadSecondsWithin(kBudget, 0.030, 0.0), 0.0);
}

TEST(UploadBudget, NeverMoreWhenTheRestGrows) {
  double previous = kMost;
  for (double rest = 0.0; rest < 0.04; rest += 0.0001) {
    const double upload = uploadSecondsWithin(kBudget, rest, kMost);
    EXPECT_LE(upload, previous) << "rest " << rest;
    EXPECT_GE(upload, kLeastUploadSeconds) << "rest " << rest;
    EXPECT_LE(upload, kMost) << "rest " << rest;
    previous = upload;
  }
}

// The viewer's frame budget follows the display's refresh rate; GLFW's 0 (unknown) is 60 Hz, and a
// reported rate outside [24, 500] Hz is taken at its bound.
TEST(UploadBudget, FrameBudgetFollowsTheRefreshRate) {
  EXPECT_DOUBLE_EQ(frameBudgetForRefresh(60), 1.0 / 60.0);
  EXPECT_DOUBLE_EQ(frameBudgetForRefresh(144), 1.0 / 144.0);
  EXPECT_DOUBLE_EQ(frameBudgetForRefresh(0), 1.0 / 60.0);
  EXPECT_DOUBLE_EQ(frameBudgetForRefresh(-1), 1.0 / 60.0);
  EXPECT_DOUBLE_EQ(frameBudgetForRefresh(1), 1.0 / 24.0);
  EXPECT_DOUBLE_EQ(frameBudgetForRefresh(100000), 1.0 / 500.0);
  // A faster display leaves less upload time for the same rest of the frame.
  EXPECT_LT(uploadSecondsWithin(frameBudgetForRefresh(144), 0.004, kMost), uploadSecondsWithin(frameBudgetForRefresh(60), 0.004, kMost));
}

}  // namespace
}  // namespace fcc::render
