// The camera orbit `bench render` and `bench view` time: frame `frame` of `frames` positions, turned
// about the camera's up vector through the look-at point (the viewer's turntable orbit).
#pragma once

#include "viewer/OrbitControls.h"

namespace fcc::cli {

inline render::Camera orbitStep(const render::Camera& start, int frame, int frames) {
  return render::orbit(start, 360.0 / render::kOrbitDegreesPerPixel * frame / frames, 0.0);
}

}  // namespace fcc::cli
