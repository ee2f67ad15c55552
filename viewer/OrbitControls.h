// Camera moves of the interactive viewer, as pure functions of the camera (no window, so they are
// unit-tested): orbit about the look-at point, pan in the image plane, zoom towards the look-at point.
// Mouse motion is given in pixels of a viewport `viewportHeight` pixels high.
#pragma once

#include "Camera.h"

namespace fcc::render {

// Degrees of orbit per pixel of mouse motion.
inline constexpr double kOrbitDegreesPerPixel = 0.3;
// Distance factor per wheel step (towards the look-at point for positive steps).
inline constexpr double kZoomPerStep = 0.9;

// Turns the eye about the look-at point: dx about the camera's up vector (turntable), dy about its
// right vector, clamped short of the poles so up never becomes parallel to the view. The distance to
// the look-at point and the up vector stay.
Camera orbit(const Camera& camera, double dxPixels, double dyPixels);

// Moves eye and look-at point together in the image plane so that the point under the cursor at
// `depth` along the view (world units; 0: the look-at point's) follows the cursor (dx right, dy down
// in pixels). The viewer passes the depth of the surface point grabbed, so the object moves with the
// cursor wherever it was grabbed.
Camera pan(const Camera& camera, double dxPixels, double dyPixels, int viewportHeight, double depth = 0.0);

// Turns the camera about its view direction by `degrees` (positive: counter-clockwise as the viewer
// sees the camera turn, so the image turns clockwise); eye and look-at point stay. The up vector comes
// back orthogonal to the view. Orbiting then turns about the rolled up vector.
Camera roll(const Camera& camera, double degrees);

// Scales the eye's distance to the look-at point by kZoomPerStep^steps (never through it).
Camera zoom(const Camera& camera, double steps);

}  // namespace fcc::render
