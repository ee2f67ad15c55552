// Prefiltered tricubic B-spline reconstruction of a dense Cartesian volume (interpolating: it passes
// through the samples), for resampling onto an FCC lattice (`convert --mode resample`).
#pragma once

#include <glm/glm.hpp>

#include <vector>

namespace fcc {

class CubicBSplineVolume {
 public:
  // `values` x fastest; the coefficients are computed once (recursive filter, mirror boundaries).
  CubicBSplineVolume(const glm::ivec3& dims, const std::vector<float>& values);
  // Value at a continuous index-space position; positions outside are clamped to the volume.
  float evaluate(const glm::dvec3& xyz) const;

 private:
  float coefficient(int i, int j, int k) const;
  glm::ivec3 dims_;
  std::vector<float> coefficients_;
};

}  // namespace fcc
