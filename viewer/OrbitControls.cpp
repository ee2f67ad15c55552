#include "OrbitControls.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace fcc::render {
namespace {
// Closest the view direction may come to the up vector, in degrees.
constexpr double kPoleMarginDegrees = 1.0;
// Closest the eye may come to the look-at point, relative to the scale of the coordinates.
constexpr double kClosestRelative = 1e-6;
}  // namespace

Camera orbit(const Camera& camera, double dxPixels, double dyPixels) {
  const glm::dvec3 up = glm::normalize(camera.up);
  glm::dvec3 offset = camera.eye - camera.lookat;  // look-at point to eye
  const double distance = glm::length(offset);
  // Elevation of the eye above the plane normal to up, in degrees, and the pitch that keeps it
  // within the poles.
  const double elevation = glm::degrees(std::asin(std::clamp(glm::dot(offset, up) / distance, -1.0, 1.0)));
  const double limit = 90.0 - kPoleMarginDegrees;
  const double pitch = std::clamp(elevation + dyPixels * kOrbitDegreesPerPixel, -limit, limit) - elevation;
  const double yaw = -dxPixels * kOrbitDegreesPerPixel;

  const glm::dvec3 right = glm::normalize(glm::cross(-offset, up));
  offset = glm::dvec3(glm::rotate(glm::dmat4(1.0), glm::radians(-pitch), right) * glm::dvec4(offset, 0.0));
  offset = glm::dvec3(glm::rotate(glm::dmat4(1.0), glm::radians(yaw), up) * glm::dvec4(offset, 0.0));
  Camera out = camera;
  out.eye = camera.lookat + glm::normalize(offset) * distance;
  return out;
}

Camera pan(const Camera& camera, double dxPixels, double dyPixels, int viewportHeight, double depth) {
  const CameraFrame frame = cameraFrame(camera, 1.0);
  const double distance = depth > 0.0 ? depth : glm::length(camera.lookat - camera.eye);
  // frame.up spans half the viewport height at unit distance.
  const double worldPerPixel = 2.0 * glm::length(frame.up) * distance / std::max(viewportHeight, 1);
  const glm::dvec3 shift = worldPerPixel * (-dxPixels * glm::normalize(frame.right) + dyPixels * glm::normalize(frame.up));
  Camera out = camera;
  out.eye += shift;
  out.lookat += shift;
  return out;
}

Camera roll(const Camera& camera, double degrees) {
  const glm::dvec3 forward = glm::normalize(camera.lookat - camera.eye);
  const glm::dvec3 up = glm::normalize(camera.up - glm::dot(camera.up, forward) * forward);
  Camera out = camera;
  // Rotating up about the forward axis by -degrees turns the camera counter-clockwise as seen from behind it.
  out.up = glm::normalize(glm::dvec3(glm::rotate(glm::dmat4(1.0), glm::radians(-degrees), forward) * glm::dvec4(up, 0.0)));
  return out;
}

Camera zoom(const Camera& camera, double steps) {
  const glm::dvec3 offset = camera.eye - camera.lookat;
  const double distance = glm::length(offset);
  // Stay far enough from the look-at point that the eye remains a distinct point in doubles.
  const double closest = kClosestRelative * std::max({1.0, glm::length(camera.lookat), distance});
  Camera out = camera;
  out.eye = camera.lookat + offset / distance * std::max(distance * std::pow(kZoomPerStep, steps), closest);
  return out;
}

}  // namespace fcc::render
