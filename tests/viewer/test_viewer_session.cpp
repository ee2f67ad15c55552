// The viewer's session without a window (tests/viewer/SessionHarness.h): what its frames show and
// what its keys and mouse do.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "SessionHarness.h"

namespace fcc {
namespace {

using test::GlSuite;
using test::SessionHarness;
using test::TempDir;

class ViewerSession : public GlSuite {};

// Differing channels of two RGBA images of the harness, right of `firstColumn`.
int differingChannels(const std::vector<unsigned char>& a, const std::vector<unsigned char>& b, int firstColumn) {
  int n = 0;
  for (int y = 0; y < SessionHarness::kHeight; ++y)
    for (int x = firstColumn; x < SessionHarness::kWidth; ++x)
      for (int c = 0; c < 4; ++c) {
        const std::size_t i = (std::size_t(y) * SessionHarness::kWidth + x) * 4 + c;
        n += a[i] != b[i];
      }
  return n;
}

// `view --screenshot` saves the frame for which shownSettled() turns true: its image is final and it
// shows no "streaming" line. The first frame that settled() still drew the line (of the frame before).
TEST_F(ViewerSession, ScreenshotFrameIsSettledAndShowsNoStreamingLine) {
  TempDir dir;
  SessionHarness h(test::writeSmallBlobs(dir));
  int frames = 0, settledButShowingALine = 0, framesWithALine = 0;
  while (!h.session->shownSettled() && frames++ < 2000) {
    h.frame();
    framesWithALine += !h.session->shownStatusLine().empty();
    settledButShowingALine += h.session->settled() && !h.session->shownStatusLine().empty();
  }
  ASSERT_TRUE(h.session->shownSettled()) << "did not settle in 2000 frames";
  EXPECT_GT(framesWithALine, 0) << "the view never streamed: nothing was tested";
  EXPECT_EQ(settledButShowingALine, 1) << "the frame that first settled shows the line of the one before";
  EXPECT_EQ(h.session->shownStatusLine(), "");
  const std::vector<unsigned char> shot = h.pixels();
  const int panel = int(std::ceil(h.session->panelWidth()));
  h.frame();
  h.frame();
  EXPECT_EQ(differingChannels(shot, h.pixels(), panel), 0) << "the screenshot's frame is not the final image";
}

}  // namespace
}  // namespace fcc
