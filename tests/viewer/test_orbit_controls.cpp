// The viewer's camera moves (viewer/OrbitControls.h), without a window: what each move keeps, what it
// changes by how much, and that moves undo each other.
#include <gtest/gtest.h>

#include <cmath>

#include "viewer/AxisIndicator.h"
#include "viewer/DvrLight.h"
#include "viewer/OrbitControls.h"

namespace fcc::render {
namespace {

constexpr double kTol = 1e-9;  // relative, on positions of unit scale

Camera testCamera() {
  Camera c;
  c.eye = glm::dvec3(3.0, 2.0, 5.0);
  c.lookat = glm::dvec3(0.5, -0.25, 1.0);
  c.up = glm::dvec3(0.0, 1.0, 0.0);
  c.fovYDegrees = 40.0;
  return c;
}

double elevationDegrees(const Camera& c) {
  const glm::dvec3 v = glm::normalize(c.eye - c.lookat);
  return glm::degrees(std::asin(glm::dot(v, glm::normalize(c.up))));
}

// Pixel coordinates (x right, y down, centres at +0.5) of world point p in a width x height image.
glm::dvec2 project(const Camera& c, const glm::dvec3& p, int width, int height) {
  const CameraFrame f = cameraFrame(c, double(width) / height);
  const glm::dvec3 v = p - f.eye;
  const double z = glm::dot(v, f.forward);
  const double ndcX = glm::dot(v, f.right) / glm::dot(f.right, f.right) / z;
  const double ndcY = glm::dot(v, f.up) / glm::dot(f.up, f.up) / z;
  return {(ndcX + 1.0) * 0.5 * width, (1.0 - ndcY) * 0.5 * height};
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b, const char* what) {
  EXPECT_NEAR(glm::length(a - b), 0.0, kTol * (1.0 + glm::length(b))) << what << ": (" << a.x << ", " << a.y << ", "
                                                                    << a.z << ") vs (" << b.x << ", " << b.y << ", "
                                                                    << b.z << ")";
}

TEST(OrbitControls, OrbitKeepsTheLookatPointAndDistance) {
  const Camera c = testCamera();
  const double distance = glm::length(c.eye - c.lookat);
  for (const glm::dvec2 d : {glm::dvec2(40, 0), glm::dvec2(0, -25), glm::dvec2(-130, 70)}) {
    const Camera o = orbit(c, d.x, d.y);
    expectNear(o.lookat, c.lookat, "look-at");
    EXPECT_NEAR(glm::length(o.eye - o.lookat), distance, kTol * distance) << d.x << "," << d.y;
    EXPECT_NO_THROW(cameraFrame(o, 1.0));
  }
}

TEST(OrbitControls, HorizontalOrbitTurnsAboutUpByTheStatedRate) {
  const Camera c = testCamera();
  const double dx = 100.0;
  const Camera o = orbit(c, dx, 0.0);
  EXPECT_NEAR(elevationDegrees(o), elevationDegrees(c), 1e-9);
  // The angle between the horizontal components of the view offsets.
  const glm::dvec3 up = glm::normalize(c.up);
  auto horizontal = [&](const Camera& k) {
    const glm::dvec3 v = k.eye - k.lookat;
    return glm::normalize(v - glm::dot(v, up) * up);
  };
  const double angle = glm::degrees(std::acos(std::clamp(glm::dot(horizontal(c), horizontal(o)), -1.0, 1.0)));
  EXPECT_NEAR(angle, dx * kOrbitDegreesPerPixel, 1e-6);
  // A full turn comes back; opposite moves undo each other.
  expectNear(orbit(c, 360.0 / kOrbitDegreesPerPixel, 0.0).eye, c.eye, "full turn");
  expectNear(orbit(orbit(c, 37.0, 12.0), 0.0, -12.0).eye, orbit(c, 37.0, 0.0).eye, "pitch undone");
}

TEST(OrbitControls, VerticalOrbitChangesElevationAndStopsShortOfThePoles) {
  const Camera c = testCamera();
  const double before = elevationDegrees(c);
  EXPECT_NEAR(elevationDegrees(orbit(c, 0.0, 20.0)), before + 20.0 * kOrbitDegreesPerPixel, 1e-6);
  for (const double dy : {1e4, -1e4}) {
    const Camera o = orbit(c, 0.0, dy);
    EXPECT_LT(std::abs(elevationDegrees(o)), 90.0) << dy;
    EXPECT_GT(std::abs(elevationDegrees(o)), 88.0) << dy;
    EXPECT_NO_THROW(cameraFrame(o, 1.0)) << "up must not become parallel to the view";
  }
}

TEST(OrbitControls, PanMovesThePointUnderTheCursorWithIt) {
  const Camera c = testCamera();
  const int width = 800, height = 600;
  const glm::dvec2 before = project(c, c.lookat, width, height);
  EXPECT_NEAR(before.x, width / 2.0, 1e-9);
  const double dx = 35.0, dy = -12.5;
  const Camera p = pan(c, dx, dy, height);
  expectNear(p.lookat - p.eye, c.lookat - c.eye, "view vector");
  // The old look-at point (at the look-at distance) moved on screen by exactly the mouse motion.
  const glm::dvec2 after = project(p, c.lookat, width, height);
  EXPECT_NEAR(after.x - before.x, dx, 1e-6);
  EXPECT_NEAR(after.y - before.y, dy, 1e-6);
}

// Grabbed at another depth than the look-at point's, the point at that depth follows the cursor.
TEST(OrbitControls, PanAtADepthMovesThePointAtThatDepthWithTheCursor) {
  const Camera c = testCamera();
  const int width = 800, height = 600;
  const CameraFrame f = cameraFrame(c, double(width) / height);
  const double depth = 0.4 * glm::length(c.lookat - c.eye);
  const glm::dvec3 grabbed = c.eye + depth * f.forward + 0.3 * depth * f.right;  // off centre, nearer
  const glm::dvec2 before = project(c, grabbed, width, height);
  const double dx = -21.0, dy = 17.5;
  const Camera p = pan(c, dx, dy, height, depth);
  const glm::dvec2 after = project(p, grabbed, width, height);
  EXPECT_NEAR(after.x - before.x, dx, 1e-6);
  EXPECT_NEAR(after.y - before.y, dy, 1e-6);
  const glm::dvec2 lookatMoved = project(p, c.lookat, width, height) - project(c, c.lookat, width, height);
  EXPECT_LT(std::abs(lookatMoved.x), std::abs(dx) * 0.9) << "the farther look-at point moves less";
}

TEST(OrbitControls, ZoomScalesTheDistanceAndUndoes) {
  const Camera c = testCamera();
  const double distance = glm::length(c.eye - c.lookat);
  const Camera z = zoom(c, 3.0);
  EXPECT_NEAR(glm::length(z.eye - z.lookat), distance * std::pow(kZoomPerStep, 3.0), kTol * distance);
  expectNear(glm::normalize(z.eye - z.lookat), glm::normalize(c.eye - c.lookat), "direction");
  expectNear(zoom(z, -3.0).eye, c.eye, "zoom undone");
  EXPECT_GT(glm::length(zoom(c, 500.0).eye - c.lookat), 0.0) << "zoom never reaches the look-at point";
}

// Roll turns the image about its centre: eye and look-at stay, the up vector turns about the view by
// the given angle (a point right of the centre moves down for a positive roll: the image turns
// clockwise), and rolling back undoes it.
TEST(OrbitControls, RollTurnsTheImageAboutTheViewAxis) {
  const Camera c = testCamera();
  const Camera r = roll(c, 30.0);
  expectNear(r.eye, c.eye, "eye");
  expectNear(r.lookat, c.lookat, "look-at");
  const glm::dvec3 forward = glm::normalize(c.lookat - c.eye);
  const glm::dvec3 upBefore = glm::normalize(c.up - glm::dot(c.up, forward) * forward);
  EXPECT_NEAR(glm::dot(r.up, forward), 0.0, kTol);
  EXPECT_NEAR(glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(r.up), upBefore), -1.0, 1.0))), 30.0, 1e-9);
  // A point on the image's horizontal through the centre moves down (y grows) after a positive roll.
  const CameraFrame f = cameraFrame(c, 1.0);
  const glm::dvec3 rightOfCentre = c.lookat + glm::normalize(f.right);
  EXPECT_GT(project(r, rightOfCentre, 600, 600).y, project(c, rightOfCentre, 600, 600).y + 1.0);
  expectNear(glm::normalize(roll(r, -30.0).up), upBefore, "roll undone");
  // Orbiting after a roll turns about the rolled up vector and keeps it.
  expectNear(orbit(r, 50.0, 0.0).up, r.up, "turntable about the rolled up");
}

// The axis indicator: looking along -z with y up, x points right, y up, z at the viewer; a quarter
// roll turns the image clockwise, so y then points right.
TEST(AxisIndicator, WorldAxesAsTheCameraSeesThem) {
  Camera c;
  c.eye = glm::dvec3(2.0, 3.0, 9.0);
  c.lookat = glm::dvec3(2.0, 3.0, 4.0);
  const auto axes = worldAxesInView(c);
  expectNear(axes[0], glm::dvec3(1, 0, 0), "x");
  expectNear(axes[1], glm::dvec3(0, 1, 0), "y");
  expectNear(axes[2], glm::dvec3(0, 0, 1), "z");
  const auto rolled = worldAxesInView(roll(c, 90.0));
  expectNear(rolled[0], glm::dvec3(0, -1, 0), "x after a quarter roll");
  expectNear(rolled[1], glm::dvec3(1, 0, 0), "y after a quarter roll");
  expectNear(rolled[2], glm::dvec3(0, 0, 1), "z after a quarter roll");
}

// The light kit (viewer/DvrLight.h) is VTK's default: a key light above and right of the view axis
// (elevation 50, azimuth 10 degrees), a fill light below and left (-75, -10), two back lights beside
// and behind (0, +-110), all unit, with the weights 0.75, 0.25, 0.75 / 3.5 twice and the headlight's
// 0.25, over their sum.
TEST(LightKit, IsVtksDefaultKitWeightedToAddUpToOne) {
  const LightKit& kit = defaultLightKit();
  const double elevation[4] = {50.0, -75.0, 0.0, 0.0}, azimuth[4] = {10.0, -10.0, 110.0, -110.0};
  const double intensity[4] = {0.75, 0.25, 0.75 / 3.5, 0.75 / 3.5}, head = 0.25;
  const double sum = intensity[0] + intensity[1] + intensity[2] + intensity[3] + head;
  double weights = kit.headWeight;
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    const glm::dvec3 l(kit.inCamera[k]);
    EXPECT_NEAR(glm::length(l), 1.0, 1e-6);
    EXPECT_NEAR(glm::degrees(std::asin(l.y)), elevation[k], 1e-4);
    if (std::abs(elevation[k]) < 89.0) {
      EXPECT_NEAR(glm::degrees(std::atan2(l.x, l.z)), azimuth[k], 1e-4);
    }
    EXPECT_NEAR(kit.weight[k], intensity[k] / sum, 1e-6);
    weights += kit.weight[k];
  }
  EXPECT_NEAR(kit.headWeight, head / sum, 1e-6);
  EXPECT_NEAR(weights, 1.0, 1e-6);
  EXPECT_LT(kit.inCamera[2].z, 0.0) << "the back lights are behind the object";
  EXPECT_EQ(dvrLightName(DvrLight::Kit), "kit");
}

}  // namespace
}  // namespace fcc::render
