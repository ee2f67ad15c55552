#include "BoxSplineReference.h"

#include <array>
#include <cmath>

namespace fcc::spline {
namespace {

constexpr int kDirections = 6;
const std::array<glm::dvec3, kDirections> kXi = {glm::dvec3(1, 1, 0), glm::dvec3(1, 0, 1), glm::dvec3(0, 1, 1),
                                                 glm::dvec3(1, -1, 0), glm::dvec3(0, 1, -1), glm::dvec3(-1, 0, 1)};

// Box spline of the directions in `mask` (bit i = kXi[i]) at x.
double boxSpline(unsigned mask, const glm::dvec3& x) {
  int idx[kDirections];
  int m = 0;
  for (int i = 0; i < kDirections; ++i)
    if (mask & (1u << i)) idx[m++] = i;
  // Find three independent directions; without them the spline is a distribution on a plane (0 off it).
  int basis[3] = {-1, -1, -1};
  glm::dmat3 B(0.0);
  for (int a = 0; a < m && basis[0] < 0; ++a)
    for (int b = a + 1; b < m && basis[0] < 0; ++b)
      for (int c = b + 1; c < m && basis[0] < 0; ++c) {
        const glm::dmat3 M(kXi[idx[a]], kXi[idx[b]], kXi[idx[c]]);
        if (std::abs(glm::determinant(M)) > 0.5) {
          basis[0] = idx[a], basis[1] = idx[b], basis[2] = idx[c];
          B = M;
        }
      }
  if (basis[0] < 0) return 0.0;
  const glm::dvec3 t3 = glm::inverse(B) * x;
  if (m == 3) {
    // Base case: characteristic function of the half-open parallelepiped, divided by |det|.
    for (int k = 0; k < 3; ++k)
      if (t3[k] < 0.0 || t3[k] >= 1.0) return 0.0;
    return 1.0 / std::abs(glm::determinant(B));
  }
  // (m - n) M(x) = sum over xi of t_xi M_{Xi\xi}(x) + (1 - t_xi) M_{Xi\xi}(x - xi), x = sum t_xi xi.
  double t[kDirections] = {0, 0, 0, 0, 0, 0};
  for (int k = 0; k < 3; ++k) t[basis[k]] = t3[k];
  double sum = 0.0;
  for (int a = 0; a < m; ++a) {
    const int i = idx[a];
    const unsigned sub = mask & ~(1u << i);
    sum += t[i] * boxSpline(sub, x) + (1.0 - t[i]) * boxSpline(sub, x - kXi[i]);
  }
  return sum / double(m - 3);
}

}  // namespace

double boxSplineFccReference(const glm::dvec3& x) {
  if (std::abs(x.x) >= 2.0 || std::abs(x.y) >= 2.0 || std::abs(x.z) >= 2.0) return 0.0;
  return 2.0 * boxSpline(0x3fu, x + glm::dvec3(1.0));
}

}  // namespace fcc::spline
