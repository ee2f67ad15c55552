#include "AxisIndicator.h"

namespace fcc::render {

std::array<glm::dvec3, 3> worldAxesInView(const Camera& camera) {
  const CameraFrame f = cameraFrame(camera, 1.0);
  const glm::dvec3 right = glm::normalize(f.right), up = glm::normalize(f.up), back = -f.forward;
  std::array<glm::dvec3, 3> axes;
  for (int k = 0; k < 3; ++k) {
    glm::dvec3 e(0.0);
    e[k] = 1.0;
    axes[std::size_t(k)] = glm::dvec3(glm::dot(e, right), glm::dot(e, up), glm::dot(e, back));
  }
  return axes;
}

}  // namespace fcc::render
