#include "CubicBSpline.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace fcc {

// In-place interpolation prefilter of one line (Unser 1999), mirror-symmetric boundaries.
void bsplinePrefilterLine(float* c, int n, ptrdiff_t stride) {
  if (n < 2) return;
  const double z = std::sqrt(3.0) - 2.0, lambda = (1.0 - z) * (1.0 - 1.0 / z);
  auto at = [&](int i) -> float& { return c[ptrdiff_t(i) * stride]; };
  for (int i = 0; i < n; ++i) at(i) = float(at(i) * lambda);
  // Causal initialisation: truncated geometric sum of the mirrored signal.
  const int horizon = std::min(n, 30);
  double sum = at(0), zn = z;
  for (int i = 1; i < horizon; ++i, zn *= z) sum += zn * at(i);
  at(0) = float(sum);
  for (int i = 1; i < n; ++i) at(i) = float(at(i) + z * at(i - 1));
  at(n - 1) = float((z / (z * z - 1.0)) * (at(n - 1) + z * at(n - 2)));
  for (int i = n - 2; i >= 0; --i) at(i) = float(z * (at(i + 1) - at(i)));
}

void bsplinePrefilterLines(float* c, int n, ptrdiff_t stride, int count, ptrdiff_t lineStride) {
  if (n < 2 || count <= 0) return;
  const double z = std::sqrt(3.0) - 2.0, lambda = (1.0 - z) * (1.0 - 1.0 / z);
  auto row = [&](int i) { return c + ptrdiff_t(i) * stride; };  // element i of every line
  for (int i = 0; i < n; ++i) {
    float* r = row(i);
    for (int j = 0; j < count; ++j) r[j * lineStride] = float(r[j * lineStride] * lambda);
  }
  // Causal initialisation, as bsplinePrefilterLine: sum in double, element by element.
  const int horizon = std::min(n, 30);
  thread_local std::vector<double> sum;
  sum.assign(size_t(count), 0.0);
  {
    const float* r0 = row(0);
    for (int j = 0; j < count; ++j) sum[size_t(j)] = r0[j * lineStride];
  }
  double zn = z;
  for (int i = 1; i < horizon; ++i, zn *= z) {
    const float* r = row(i);
    for (int j = 0; j < count; ++j) sum[size_t(j)] += zn * r[j * lineStride];
  }
  {
    float* r0 = row(0);
    for (int j = 0; j < count; ++j) r0[j * lineStride] = float(sum[size_t(j)]);
  }
  for (int i = 1; i < n; ++i) {
    float* r = row(i);
    const float* p = row(i - 1);
    for (int j = 0; j < count; ++j) r[j * lineStride] = float(r[j * lineStride] + z * p[j * lineStride]);
  }
  {
    float* last = row(n - 1);
    const float* before = row(n - 2);
    for (int j = 0; j < count; ++j)
      last[j * lineStride] = float((z / (z * z - 1.0)) * (last[j * lineStride] + z * before[j * lineStride]));
  }
  for (int i = n - 2; i >= 0; --i) {
    float* r = row(i);
    const float* next = row(i + 1);
    for (int j = 0; j < count; ++j) r[j * lineStride] = float(z * (next[j * lineStride] - r[j * lineStride]));
  }
}

void cubicBSplineWeights(double t, double w[4]) {
  const double s = 1.0 - t;
  w[0] = s * s * s / 6.0;
  w[1] = (4.0 - 6.0 * t * t + 3.0 * t * t * t) / 6.0;
  w[2] = (4.0 - 6.0 * s * s + 3.0 * s * s * s) / 6.0;
  w[3] = t * t * t / 6.0;
}

void cubicBSplineDerivativeWeights(double t, double w[4]) {
  const double s = 1.0 - t;
  w[0] = -0.5 * s * s;
  w[1] = 1.5 * t * t - 2.0 * t;
  w[2] = -1.5 * t * t + t + 0.5;
  w[3] = 0.5 * t * t;
}

CubicBSplineVolume::CubicBSplineVolume(const glm::ivec3& dims, const std::vector<float>& values)
    : dims_(dims), coefficients_(values) {
  const ptrdiff_t sx = 1, sy = dims.x, sz = ptrdiff_t(dims.x) * dims.y;
  float* c = coefficients_.data();
  tbb::parallel_for(0, dims.z, [&](int k) {
    for (int j = 0; j < dims.y; ++j) bsplinePrefilterLine(c + k * sz + j * sy, dims.x, sx);
  });
  tbb::parallel_for(0, dims.z, [&](int k) {
    for (int i = 0; i < dims.x; ++i) bsplinePrefilterLine(c + k * sz + i * sx, dims.y, sy);
  });
  tbb::parallel_for(0, dims.y, [&](int j) {
    for (int i = 0; i < dims.x; ++i) bsplinePrefilterLine(c + j * sy + i * sx, dims.z, sz);
  });
}

float CubicBSplineVolume::coefficient(int i, int j, int k) const {
  // Mirror boundary, matching the prefilter's assumption.
  auto mirror = [](int a, int n) {
    if (n == 1) return 0;
    const int period = 2 * n - 2;
    a = ((a % period) + period) % period;
    return a < n ? a : period - a;
  };
  i = mirror(i, dims_.x), j = mirror(j, dims_.y), k = mirror(k, dims_.z);
  return coefficients_[(size_t(k) * dims_.y + j) * dims_.x + i];
}

float CubicBSplineVolume::evaluate(const glm::dvec3& xyzIn) const { return float(value(xyzIn)); }

double CubicBSplineVolume::value(const glm::dvec3& xyzIn) const {
  const glm::dvec3 xyz = glm::clamp(xyzIn, glm::dvec3(0.0), glm::dvec3(dims_ - 1));
  return cubicBSplineAt(xyz, [&](const glm::ivec3& ijk) { return coefficient(ijk.x, ijk.y, ijk.z); });
}

glm::dvec3 CubicBSplineVolume::gradient(const glm::dvec3& xyzIn) const {
  const glm::dvec3 xyz = glm::clamp(xyzIn, glm::dvec3(0.0), glm::dvec3(dims_ - 1));
  const glm::dvec3 f = glm::floor(xyz);
  const glm::ivec3 base = glm::ivec3(f) - 1;
  double w[3][4], dw[3][4];
  for (int a = 0; a < 3; ++a) {
    cubicBSplineWeights(xyz[a] - f[a], w[a]);
    cubicBSplineDerivativeWeights(xyz[a] - f[a], dw[a]);
  }
  glm::dvec3 g(0.0);
  for (int c = 0; c < 4; ++c)
    for (int b = 0; b < 4; ++b)
      for (int a = 0; a < 4; ++a) {
        const double v = coefficient(base.x + a, base.y + b, base.z + c);
        g.x += dw[0][a] * w[1][b] * w[2][c] * v;
        g.y += w[0][a] * dw[1][b] * w[2][c] * v;
        g.z += w[0][a] * w[1][b] * dw[2][c] * v;
      }
  // Clamped axes are constant outside the volume.
  for (int a = 0; a < 3; ++a)
    if (xyzIn[a] < 0.0 || xyzIn[a] > double(dims_[a] - 1)) g[a] = 0.0;
  return g;
}

}  // namespace fcc
