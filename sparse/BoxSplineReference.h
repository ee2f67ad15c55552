// Slow, independent reference for M_fcc: the box spline evaluated from its definition by the
// de Boor–Höllig recurrence, in double precision. Tests compare the BB-form fast path against it.
// Valid at points in general position (off the knot planes), where the half-open convention of the
// piecewise-constant base case does not matter.
#pragma once

#include <glm/glm.hpp>

namespace fcc::spline {

// M_fcc(x) = 2 M_Xi(x + (1,1,1)) for the six FCC directions.
double boxSplineFccReference(const glm::dvec3& x);

// Sum over FCC sites j of c(j) M_fcc(xyz - j), `c(glm::ivec3) -> double`.
template <class CoefficientAt>
double splineReference(const glm::dvec3& xyz, CoefficientAt&& c) {
  const glm::ivec3 base(glm::floor(xyz));
  double sum = 0.0;
  for (int dz = -2; dz <= 3; ++dz)
    for (int dy = -2; dy <= 3; ++dy)
      for (int dx = -2; dx <= 3; ++dx) {
        const glm::ivec3 j = base + glm::ivec3(dx, dy, dz);
        if (((j.x + j.y + j.z) & 1) != 0) continue;
        const double m = boxSplineFccReference(xyz - glm::dvec3(j));
        if (m != 0.0) sum += c(j) * m;
      }
  return sum;
}

}  // namespace fcc::spline
