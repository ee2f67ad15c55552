// What the viewer reads under its cursor (viewer/CursorProbe.h): the nearest FCC site, and the surface
// point of a rendered pixel from its depth, where the spline takes the isovalue.
#include <gtest/gtest.h>

#include <cmath>

#include "RenderTestSupport.h"
#include "viewer/CursorProbe.h"

namespace fcc {
namespace {

using render::nearestFccSite;

TEST(CursorProbe, NearestFccSiteHasAnEvenSumAndIsNearest) {
  EXPECT_EQ(nearestFccSite(glm::dvec3(2.1, 3.9, -0.2)), glm::ivec3(2, 4, 0));
  // (1, 0, 0) is no site: the coordinate that rounded furthest goes the other way.
  EXPECT_EQ(nearestFccSite(glm::dvec3(1.1, 0.05, 0.45)), glm::ivec3(1, 0, 1));
  EXPECT_EQ(nearestFccSite(glm::dvec3(-0.6, -0.1, 0.0)), glm::ivec3(0, 0, 0));
  EXPECT_EQ(nearestFccSite(glm::dvec3(-0.6, -0.45, 0.0)), glm::ivec3(-1, -1, 0));
  for (double x = -3.0; x < 3.0; x += 0.37)
    for (double y = -2.0; y < 2.0; y += 0.41) {
      const glm::dvec3 xyz(x, y, 0.3 * x - y);
      const glm::ivec3 site = nearestFccSite(xyz);
      EXPECT_EQ((site.x + site.y + site.z) & 1, 0);
      // No site is nearer (the candidates within one unit).
      const double d = glm::length(glm::dvec3(site) - xyz);
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
          for (int k = -1; k <= 1; ++k) {
            const glm::ivec3 other = glm::ivec3(std::lround(x), std::lround(y), std::lround(xyz.z)) + glm::ivec3(i, j, k);
            if (((other.x + other.y + other.z) & 1) == 0) {
              EXPECT_LE(d, glm::length(glm::dvec3(other) - xyz) + 1e-12);
            }
          }
    }
}

class CursorProbeGl : public test::GlSuite {};

// Every hit pixel's depth puts the probe on the surface (the spline there is the isovalue, evaluated
// on the CPU from the file's bricks); misses are no hit.
TEST_F(CursorProbeGl, HitPixelsProbeToTheSurface) {
  test::TempDir dir;
  const std::string path = test::writeSmallBlobs(dir);
  const io::BrickStore store(path);
  const float iso = 0.3f;
  const render::Camera camera = test::smallBlobsCamera();
  const int w = 64, h = 48;
  const render::FrameImages images = test::renderFile(path, camera, w, h, iso);
  render::SplineProbe spline(store);
  const glm::dmat4 indexFromWorld = glm::inverse(store.worldFromIndex());
  int hits = 0, misses = 0;
  float worst = 0.0f;
  for (int py = 0; py < h; py += 3)
    for (int px = 0; px < w; px += 3) {
      const float depth = images.normalDepth[(std::size_t(py) * w + px) * 4 + 3];
      const render::CursorProbe p = render::probeSurface(spline, indexFromWorld, camera, px, py, w, h, depth);
      ASSERT_EQ(p.hit, std::isfinite(depth));
      if (!p.hit) {
        ++misses;
        continue;
      }
      ++hits;
      worst = std::max(worst, std::abs(p.valueAtPoint - iso));
      EXPECT_LE(glm::length(glm::dvec3(p.ijk) - p.xyz), 1.0);
      EXPECT_EQ(p.valueAtSite, spline.valueAt(glm::dvec3(p.ijk)));
    }
  EXPECT_GT(hits, 20);
  EXPECT_GT(misses, 0);
  EXPECT_LT(worst, 1e-3f) << "a probe is off the surface";
}

}  // namespace
}  // namespace fcc
