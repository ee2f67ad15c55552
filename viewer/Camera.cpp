#include "Camera.h"

#include <cmath>
#include <string>

#include "sparse/Error.h"

namespace fcc::render {

CameraFrame cameraFrame(const Camera& camera, double aspect) {
  if (!(camera.fovYDegrees > 0.0 && camera.fovYDegrees < 180.0))
    throw ValueError("field of view " + std::to_string(camera.fovYDegrees) + " degrees: valid is (0, 180)");
  const glm::dvec3 view = camera.lookat - camera.eye;
  if (!(glm::length(view) > 0.0)) throw ValueError("camera: the eye and the look-at point coincide");
  CameraFrame f;
  f.eye = camera.eye;
  f.forward = glm::normalize(view);
  const glm::dvec3 side = glm::cross(f.forward, camera.up);
  if (!(glm::length(side) > 1e-9 * glm::length(camera.up)))
    throw ValueError("camera: the up vector is parallel to the view direction (or zero); valid is any up across the view");
  const double tanHalf = std::tan(glm::radians(camera.fovYDegrees) * 0.5);
  f.right = glm::normalize(side) * tanHalf * aspect;
  f.up = glm::normalize(glm::cross(side, f.forward)) * tanHalf;
  return f;
}

glm::dvec3 upAcross(const glm::dvec3& view) {
  const glm::dvec3 v = glm::normalize(view);
  const glm::dvec3 right = std::abs(v.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 0.0, v.x > 0.0 ? 1.0 : -1.0);
  return glm::normalize(glm::cross(right, v));  // forward x up = right - (right . v) v
}

bool viewRunsAlongUp(const Camera& camera) {
  const glm::dvec3 view = camera.lookat - camera.eye;
  return glm::length(view) > 0.0 && glm::length(glm::cross(glm::normalize(view), camera.up)) < 1e-6;
}

glm::dvec3 pixelRay(const CameraFrame& frame, int px, int py, int width, int height) {
  const double x = (px + 0.5) / width * 2.0 - 1.0;
  const double y = 1.0 - (py + 0.5) / height * 2.0;
  return glm::normalize(frame.forward + x * frame.right + y * frame.up);
}

Camera frameBox(const glm::dvec3& lo, const glm::dvec3& hi, double fovYDegrees, double aspect) {
  Camera c;
  c.fovYDegrees = fovYDegrees;
  c.lookat = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * glm::length(hi - lo), 1e-9);
  // The narrower of the two fields of view must hold the bounding sphere.
  const double halfY = glm::radians(fovYDegrees) * 0.5;
  const double halfX = std::atan(std::tan(halfY) * aspect);
  const double distance = radius / std::sin(std::min(halfX, halfY)) * 1.02;
  const glm::dvec3 direction = glm::normalize(glm::dvec3(0.55, 0.45, 0.75));
  c.eye = c.lookat + direction * distance;
  c.up = glm::dvec3(0.0, 1.0, 0.0);
  return c;
}

glm::vec3 lightTowardsWorld(const CameraFrame& frame, const glm::vec3& l) {
  const glm::vec3 sum = l.x * glm::vec3(glm::normalize(frame.right)) + l.y * glm::vec3(glm::normalize(frame.up)) -
                        l.z * glm::vec3(frame.forward);
  return glm::length(sum) > 0.0f ? glm::normalize(sum) : -glm::vec3(frame.forward);
}

glm::vec3 lightInCameraFromAngles(float azimuthDegrees, float elevationDegrees) {
  const float a = glm::radians(azimuthDegrees), e = glm::radians(elevationDegrees);
  return glm::vec3(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
}

}  // namespace fcc::render
