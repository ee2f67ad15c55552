// The world axes as the camera sees them, for the viewer's axis indicator in a corner of the image.
#pragma once

#include <glm/glm.hpp>

#include <array>

#include "Camera.h"

namespace fcc::render {

// World x, y and z (unit vectors) in the camera's frame: .x to the right of the image, .y up,
// .z towards the viewer. An axis along the view has .x = .y = 0.
std::array<glm::dvec3, 3> worldAxesInView(const Camera& camera);

}  // namespace fcc::render
