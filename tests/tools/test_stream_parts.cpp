// The parts of `fccvdb bench stream` that need no GPU: its camera paths (tools/StreamPaths.h) by their
// geometric properties, the hand-written SVG plots (tools/bench/SvgPlot.h), and the report's hit rate.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

#include "RunCommand.h"
#include "StreamPaths.h"
#include "StreamReport.h"
#include "bench/SvgPlot.h"
#include "viewer/OrbitControls.h"

namespace fcc::cli {
namespace {

render::Camera startCamera() {
  return render::frameBox(glm::dvec3(0.0), glm::dvec3(128.0), 40.0, 4.0 / 3.0);
}

double viewHeightAtLookat(const render::Camera& c) {
  return 2.0 * glm::length(c.eye - c.lookat) * std::tan(glm::radians(c.fovYDegrees) * 0.5);
}

TEST(StreamPaths, OrbitTurnsOnceAboutTheLookatAtAConstantDistance) {
  const render::Camera start = startCamera();
  const std::vector<render::Camera> path = orbitPath(start, 36);
  ASSERT_EQ(path.size(), 36u);
  const double d0 = glm::length(start.eye - start.lookat);
  double turned = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    EXPECT_EQ(path[i].lookat, start.lookat);
    EXPECT_NEAR(glm::length(path[i].eye - path[i].lookat), d0, 1e-9 * d0);
    const render::Camera& next = i + 1 < path.size() ? path[i + 1] : start;  // the turn closes on the start
    const glm::dvec3 a = glm::normalize(path[i].eye - start.lookat), b = glm::normalize(next.eye - start.lookat);
    turned += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
  }
  // Projected about up the steps sum to a full turn; on the sphere the eye's arcs are no longer than that.
  EXPECT_GT(turned, 0.5 * 2.0 * M_PI);
  EXPECT_LE(turned, 2.0 * M_PI + 1e-9);
}

TEST(StreamPaths, ZoomGoesInAStraightLineFromTheStartToOneBrick) {
  const render::Camera start = startCamera();
  const glm::dvec3 target(40.0, 72.0, 56.0);
  const double brick = 16.0;
  const std::vector<render::Camera> path = zoomPath(start, target, brick, 20);
  ASSERT_EQ(path.size(), 20u);
  EXPECT_NEAR(glm::length(path.front().eye - start.eye), 0.0, 1e-9);
  EXPECT_NEAR(glm::length(path.back().lookat - target), 0.0, 1e-9);
  EXPECT_NEAR(viewHeightAtLookat(path.back()), brick, 1e-9 * brick) << "the last view is one brick high";
  const glm::dvec3 line = path.back().eye - path.front().eye;
  double previousScale = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    // On the straight line between the first and last eye, in order.
    const glm::dvec3 rel = path[i].eye - path.front().eye;
    EXPECT_LT(glm::length(glm::cross(rel, line)), 1e-6 * glm::dot(line, line)) << i;
    const double h = viewHeightAtLookat(path[i]);
    if (i > 0) {
      const double scale = viewHeightAtLookat(path[i - 1]) / h;
      EXPECT_GT(scale, 1.0) << "the view narrows every frame";
      if (i > 1) {
        EXPECT_NEAR(scale, previousScale, 1e-9) << "by the same factor";
      }
      previousScale = scale;
    }
  }
}

TEST(StreamPaths, JumpsAreSeededHeldAndLookAtTheData) {
  const render::Camera start = startCamera();
  const glm::dvec3 lo(0.0), hi(128.0);
  const auto a = jumpsPath(start, lo, hi, 30, 10, 7), b = jumpsPath(start, lo, hi, 30, 10, 7), c = jumpsPath(start, lo, hi, 30, 10, 8);
  ASSERT_EQ(a.size(), 30u);
  int differentFromOtherSeed = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].eye, b[i].eye) << "the same seed gives the same path";
    differentFromOtherSeed += a[i].eye != c[i].eye;
    EXPECT_EQ(a[i].eye, a[i / 10 * 10].eye) << "held for --jump-every frames";
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(a[i].lookat[k], 32.0);
      EXPECT_LE(a[i].lookat[k], 96.0);
    }
    EXPECT_NO_THROW(render::cameraFrame(a[i], 1.0));
  }
  EXPECT_GT(differentFromOtherSeed, 0);
  EXPECT_NE(a[0].eye, a[10].eye);
  EXPECT_NE(a[10].eye, a[20].eye);
}

TEST(StreamPaths, RecordedPathReplaysInRealTimeOrOverTheFramesAskedFor) {
  render::CameraPath recorded;
  render::Camera c = startCamera();
  for (int i = 0; i <= 10; ++i) {
    recorded.points.push_back({0.1 * i, c});
    c.eye.x += 1.0;
  }
  // 1 s at 16.7 ms a frame: 60 frames after the first.
  const std::vector<render::Camera> realTime = recordedPath(recorded, 0.0167, 0);
  EXPECT_EQ(realTime.size(), std::size_t(std::floor(1.0 / 0.0167)) + 1);
  EXPECT_EQ(realTime.front().eye, recorded.points.front().camera.eye);
  // Frame k is at k * 16.7 ms: the eye has moved 10 units a second.
  EXPECT_NEAR(realTime[30].eye.x - realTime[0].eye.x, 30 * 0.0167 * 10.0, 1e-9);
  const std::vector<render::Camera> five = recordedPath(recorded, 0.0167, 5);
  ASSERT_EQ(five.size(), 5u);
  EXPECT_EQ(five.back().eye, recorded.points.back().camera.eye);
  EXPECT_NEAR(five[2].eye.x, recorded.points[5].camera.eye.x, 1e-9);
}

// A brick drawn from any level of the pyramid was resident: the hit rate counts every level's bricks
// (with --lod-bias most are coarse; counting level 0 alone gave 0 on the H200).
TEST(StreamReport, HitRateCountsBricksDrawnAtEveryLevel) {
  StreamFrame f;
  f.levelMix = {10, 20, 0, 30};
  f.missing = 20;
  EXPECT_DOUBLE_EQ(f.gpuHitRate(), 60.0 / 80.0);
  StreamRun run;
  run.frames = {f, f};
  run.frames[1].levelMix = {0, 20};
  run.frames[1].missing = 0;
  EXPECT_DOUBLE_EQ(summarize(run, 16.7).gpuHitRate, (60.0 + 20.0) / (80.0 + 20.0));
  StreamFrame none;
  EXPECT_TRUE(std::isnan(none.gpuHitRate()));
}

TEST(SvgPlot, TicksAreNiceAndCoverTheRange) {
  for (const auto& [lo, hi] : std::vector<std::pair<double, double>>{{0.0, 1.0}, {0.3, 17.2}, {-5.0, 1234.0}, {2.0, 2.0}, {1e-5, 3e-5}}) {
    const std::vector<double> t = niceTicks(lo, hi, 6);
    ASSERT_GE(t.size(), 2u);
    EXPECT_LE(t.front(), lo);
    EXPECT_GE(t.back(), hi);
    EXPECT_LE(t.size(), 16u);
    const double step = t[1] - t[0];
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1.0) < 1e-6 || std::abs(mantissa - 2.0) < 1e-6 || std::abs(mantissa - 5.0) < 1e-6) << step;
  }
  EXPECT_EQ(tickLabel(20.0, 10.0), "20");
  EXPECT_EQ(tickLabel(0.25, 0.05), "0.25");
  EXPECT_EQ(tickLabel(1.5, 0.5), "1.5");
}

TEST(SvgPlot, IsWellFormedXmlWithEverySeriesAndItsLegend) {
  SvgPlot plot;
  plot.title = "A <title> & \"quotes\"";
  plot.xLabel = "x";
  plot.yLabel = "y";
  plot.series.push_back({"line", {0, 1, 2, 3}, {1, 3, 2, NAN}});
  plot.series.push_back({"points", {0.5, 1.5}, {2, 2.5}, false, true});
  plot.references.push_back({"budget", 2.2});
  const std::string svg = svgText(plot);
  test::TempDir dir;
  const std::string path = dir / "plot.svg";
  std::ofstream(path) << svg;
  EXPECT_EQ(std::system(("python3 -c \"import sys, xml.dom.minidom as m; d = m.parse(sys.argv[1]); "
                         "assert len(d.getElementsByTagName('polyline')) == 1; "
                         "assert len(d.getElementsByTagName('circle')) == 3; "
                         "t = [n.firstChild.data for n in d.getElementsByTagName('text') if n.firstChild]; "
                         "assert 'A <title> & \\\"quotes\\\"' in t, t; assert 'line' in t and 'points' in t and 'budget' in t\" " +
                         path)
                            .c_str()),
            0)
      << svg;
  plot.logX = true;
  plot.series[0].x = {1, 10, 100, 1000};
  std::ofstream(path) << svgText(plot);
  EXPECT_EQ(std::system(("python3 -c \"import sys, xml.dom.minidom as m; m.parse(sys.argv[1])\" " + path).c_str()), 0);
}

}  // namespace
}  // namespace fcc::cli
