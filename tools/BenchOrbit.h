// The camera orbit `bench render` and `bench view` time: frame `frame` of `frames` positions, turned
// about the camera's up vector through the look-at point (the viewer's turntable orbit), over
// `degrees` in all (a full turn, or an arc such as a user's drag).
#pragma once

#include "viewer/OrbitControls.h"

namespace fcc::cli {

inline render::Camera orbitStep(const render::Camera& start, int frame, int frames, double degrees = 360.0) {
  return render::orbit(start, degrees / render::kOrbitDegreesPerPixel * frame / frames, 0.0);
}

}  // namespace fcc::cli
