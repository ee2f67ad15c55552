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

// The up vector for a view along `view` (any length but 0) when the default up cannot be kept (the
// view runs along it): the one that keeps world +x to the right (looking down -y: -z up; looking up
// +y: +z up), or +y up when the view runs along x. Unit length.
glm::dvec3 upAcross(const glm::dvec3& view);
// True when the eye and look-at point differ and the view runs along camera.up (it cannot be kept).
bool viewRunsAlongUp(const Camera& camera);

// The unit world direction of the ray through the centre of pixel (px, py) of a width x height image.
glm::dvec3 pixelRay(const CameraFrame& frame, int px, int py, int width, int height);

// The isosurface's default light in camera space (RenderOptions::lightInCamera): above and right of
// the view axis, about azimuth 17, elevation 30 degrees.
inline const glm::vec3 kDefaultLightInCamera{0.3f, 0.6f, 1.0f};

// A light fixed to the camera (RenderOptions::lightInCamera): `lightInCamera` is the direction towards
// it in camera space (x right, y up, z towards the viewer; any length but 0). Its unit world direction
// in `frame` (-forward for a zero vector: the light behind the eye).
glm::vec3 lightTowardsWorld(const CameraFrame& frame, const glm::vec3& lightInCamera);
// The unit direction towards a light at `azimuthDegrees` from the view axis towards the right and
// `elevationDegrees` above it, in camera space: (0, 0) is (0, 0, 1), from behind the eye.
glm::vec3 lightInCameraFromAngles(float azimuthDegrees, float elevationDegrees);

// A camera that frames the world box [lo, hi] (its bounding sphere fits the field of view), looking
// at its centre from an oblique direction, y up.
Camera frameBox(const glm::dvec3& lo, const glm::dvec3& hi, double fovYDegrees, double aspect);

}  // namespace fcc::render
