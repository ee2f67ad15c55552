// The cubic B-spline used for resampling (sparse/CubicBSpline.h): the interpolation prefilter
// interpolates, the side-by-side filter equals the one-line filter bit for bit, a line padded by
// kBSplinePrefilterReach gives the inner coefficients of a longer line, and the weights sum to one.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sparse/CubicBSpline.h"

namespace fcc {
namespace {

std::vector<float> randomValues(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> d(-10.0f, 10.0f);
  std::vector<float> v(n);
  for (float& x : v) x = d(rng);
  return v;
}

// The spline through coefficients c (one line) at integer position i.
double splineAt(const std::vector<float>& c, int i) {
  double w[4];
  cubicBSplineWeights(0.0, w);
  return w[0] * c[size_t(i - 1)] + w[1] * c[size_t(i)] + w[2] * c[size_t(i + 1)];  // w[3] = 0 at t = 0
}

TEST(CubicBSpline, PrefilteredLineInterpolatesItsSamples) {
  const std::vector<float> samples = randomValues(64, 1);
  std::vector<float> c = samples;
  bsplinePrefilterLine(c.data(), int(c.size()), 1);
  for (int i = 1; i < 63; ++i) EXPECT_NEAR(splineAt(c, i), samples[size_t(i)], 2e-5) << "sample " << i;
}

TEST(CubicBSpline, LinesSideBySideEqualOneLineAtATime) {
  const int n = 37, count = 23;
  for (const ptrdiff_t lineStride : {ptrdiff_t(1), ptrdiff_t(n)}) {
    const ptrdiff_t stride = lineStride == 1 ? count : 1;
    std::vector<float> a = randomValues(size_t(n) * count, 2), b = a;
    bsplinePrefilterLines(a.data(), n, stride, count, lineStride);
    for (int j = 0; j < count; ++j) bsplinePrefilterLine(b.data() + j * lineStride, n, stride);
    for (size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "element " << i << ", line stride " << lineStride;
  }
}

TEST(CubicBSpline, PaddingByTheReachGivesTheCoefficientsOfALongerLine) {
  const std::vector<float> longLine = randomValues(200, 3);
  std::vector<float> full = longLine;
  bsplinePrefilterLine(full.data(), int(full.size()), 1);
  // A window of the line padded by the reach on both sides: its inner coefficients are the long line's.
  const int first = 80, inner = 20, pad = kBSplinePrefilterReach;
  std::vector<float> window(longLine.begin() + first - pad, longLine.begin() + first + inner + pad);
  bsplinePrefilterLine(window.data(), int(window.size()), 1);
  for (int i = 0; i < inner; ++i)
    EXPECT_NEAR(window[size_t(pad + i)], full[size_t(first + i)], 1e-5 * 10.0) << "coefficient " << i;
}

TEST(CubicBSpline, WeightsArePositiveAndSumToOne) {
  for (double t = 0.0; t <= 1.0; t += 0.0625) {
    double w[4];
    cubicBSplineWeights(t, w);
    EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, 1e-15) << "t " << t;
    for (double x : w) EXPECT_GE(x, 0.0);
  }
}

}  // namespace
}  // namespace fcc
