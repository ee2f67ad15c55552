// Prefiltered tricubic B-spline reconstruction of a dense Cartesian volume (interpolating: it passes
// through the samples), for resampling onto an FCC lattice (`convert --mode resample`).
#pragma once

#include <glm/glm.hpp>

#include <cstddef>
#include <vector>

namespace fcc {

// The interpolation prefilter of one line of `n` samples, `stride` apart, in place (Unser 1999; the
// line mirrored at its ends): samples become cubic B-spline coefficients. Its impulse response decays
// as |z|^k, z = sqrt(3) - 2, below float precision after kBSplinePrefilterReach samples, so a line
// padded by that much on each side gives its inner coefficients as an infinite line would.
void bsplinePrefilterLine(float* c, int n, ptrdiff_t stride);
inline constexpr int kBSplinePrefilterReach = 14;

// The same filter on `count` lines at once, line j starting at c + j * lineStride: the recursions run
// side by side (the inner loop over the lines), which hides their latency and, for lines next to each
// other in memory (lineStride 1), vectorises. Each line's result is bsplinePrefilterLine's, bit for bit.
void bsplinePrefilterLines(float* c, int n, ptrdiff_t stride, int count, ptrdiff_t lineStride);

// The four cubic B-spline weights of the coefficients at floor(x) - 1 .. floor(x) + 2, t = x - floor(x).
void cubicBSplineWeights(double t, double w[4]);

// Their derivatives with respect to t.
void cubicBSplineDerivativeWeights(double t, double w[4]);

// The tricubic B-spline at position `xyz` from the coefficients `coefficientAt(glm::ivec3)` gives at the
// 4^3 integer points floor(xyz) - 1 .. floor(xyz) + 2: one sum, in one order, for every caller.
template <class CoefficientAt>
double cubicBSplineAt(const glm::dvec3& xyz, CoefficientAt&& coefficientAt) {
  const glm::dvec3 f = glm::floor(xyz);
  const glm::ivec3 base = glm::ivec3(f) - 1;
  double wx[4], wy[4], wz[4];
  cubicBSplineWeights(xyz.x - f.x, wx);
  cubicBSplineWeights(xyz.y - f.y, wy);
  cubicBSplineWeights(xyz.z - f.z, wz);
  double sum = 0.0;
  for (int c = 0; c < 4; ++c)
    for (int b = 0; b < 4; ++b) {
      double row = 0.0;
      for (int a = 0; a < 4; ++a) row += wx[a] * coefficientAt(base + glm::ivec3(a, b, c));
      sum += wz[c] * wy[b] * row;
    }
  return sum;
}

class CubicBSplineVolume {
 public:
  // `values` x fastest; the coefficients are computed once (recursive filter, mirror boundaries).
  CubicBSplineVolume(const glm::ivec3& dims, const std::vector<float>& values);
  // Value at a continuous index-space position; positions outside are clamped to the volume.
  float evaluate(const glm::dvec3& xyz) const;
  // The same in double, and the exact gradient (derivative weights; zero across a clamped axis).
  double value(const glm::dvec3& xyz) const;
  glm::dvec3 gradient(const glm::dvec3& xyz) const;

 private:
  float coefficient(int i, int j, int k) const;
  glm::ivec3 dims_;
  std::vector<float> coefficients_;
};

}  // namespace fcc
