// The pinhole camera of `fccvdb render` and `fccvdb view`: world-space eye, look-at point and up
// vector, vertical field of view; rays through pixel centres, image row 0 at the top.
#pragma once

#include <glm/glm.hpp>

namespace fcc::render {

struct Camera {
  glm::dvec3 eye{0.0, 0.0, 1.0};
  glm::dvec3 lookat{0.0};
  glm::dvec3 up{0.0, 1.0, 0.0};
  double fovYDegrees = 40.0;
};

// The camera's orthonormal frame, with right/up scaled so that the ray through normalised device
// coordinates (x, y) in [-1, 1]^2 (y up) is forward + x * right + y * up.
struct CameraFrame {
  glm::dvec3 eye, forward, right, up;
};

// Throws fcc::ValueError for a degenerate camera (eye == lookat, up parallel to the view direction,
// field of view outside (0, 180)).
CameraFrame cameraFrame(const Camera& camera, double aspect);

// The unit world direction of the ray through the centre of pixel (px, py) of a width x height image.
glm::dvec3 pixelRay(const CameraFrame& frame, int px, int py, int width, int height);

// A camera that frames the world box [lo, hi] (its bounding sphere fits the field of view), looking
// at its centre from an oblique direction, y up.
Camera frameBox(const glm::dvec3& lo, const glm::dvec3& hi, double fovYDegrees, double aspect);

}  // namespace fcc::render
