// The exact ray/isosurface pieces of sparse/FccRay.h, on the CPU, against slow references: the first
// root of random cubics (found by dense sampling in double precision), the plane splits of a cell
// (each sub-segment lies in one piece), and the segment's Bernstein form (equals the spline).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sparse/Spline.h"

namespace fcc::spline {
namespace {

double bernstein3(const glm::dvec4& b, double u) {
  const double v = 1.0 - u;
  return v * v * v * b.x + 3.0 * v * v * u * b.y + 3.0 * v * u * u * b.z + u * u * u * b.w;
}

// The first sign change of the cubic on [0, 1] located by 2^16 samples, refined by bisection; -1 if
// the samples see none. (Roots closer together than the sampling are what the test avoids below.)
double referenceFirstRoot(const glm::dvec4& b) {
  constexpr int kSteps = 1 << 16;
  double prev = bernstein3(b, 0.0);
  if (prev == 0.0) return 0.0;
  for (int i = 1; i <= kSteps; ++i) {
    const double u = double(i) / kSteps, g = bernstein3(b, u);
    if (g == 0.0) return u;
    if ((g < 0.0) != (prev < 0.0)) {
      double lo = double(i - 1) / kSteps, hi = u;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        if ((bernstein3(b, mid) < 0.0) == (prev < 0.0)) lo = mid;
        else hi = mid;
      }
      return 0.5 * (lo + hi);
    }
    prev = g;
  }
  return -1.0;
}

TEST(Ray, FirstRootOfRandomCubicsMatchesDenseSampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coefficient(-1.0f, 1.0f);
  constexpr double kRootTol = 1e-5;  // in u; float bisection gets ~1e-7
  int withRoot = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const glm::vec4 b(coefficient(rng), coefficient(rng), coefficient(rng), coefficient(rng));
    const double expected = referenceFirstRoot(glm::dvec4(b));
    const float u = fcc_first_root_bernstein3(b);
    if (expected < 0.0) {
      // No sign change seen: at most a double root the float search may or may not report.
      if (u >= 0.0f) {
        EXPECT_NEAR(bernstein3(glm::dvec4(b), u), 0.0, 1e-4) << trial;
      }
      continue;
    }
    ++withRoot;
    ASSERT_GE(u, 0.0f) << "missed a root; b = " << b.x << " " << b.y << " " << b.z << " " << b.w;
    EXPECT_NEAR(u, expected, kRootTol) << "b = " << b.x << " " << b.y << " " << b.z << " " << b.w;
  }
  EXPECT_GT(withRoot, 5000);
}

// Two roots closer together than any fixed step: the critical point between them separates them.
TEST(Ray, FindsTheFirstOfTwoCloseRoots) {
  for (double gap : {1e-2, 1e-3, 2e-4}) {
    const double r1 = 0.4, r2 = 0.4 + gap;
    // g(u) = (u - r1)(u - r2)(u - 3) in Bernstein form, from its values at 0, 1/3, 2/3, 1.
    auto g = [&](double u) { return (u - r1) * (u - r2) * (u - 3.0); };
    const double g0 = g(0.0), g1 = g(1.0 / 3.0), g2 = g(2.0 / 3.0), g3 = g(1.0);
    const glm::vec4 b(float(g0), float((-5 * g0 + 18 * g1 - 9 * g2 + 2 * g3) / 6),
                      float((2 * g0 - 9 * g1 + 18 * g2 - 5 * g3) / 6), float(g3));
    EXPECT_NEAR(fcc_first_root_bernstein3(b), r1, 1e-5) << "gap " << gap;
  }
}

TEST(Ray, CellSplitsSeparateThePieces) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), dir(-1.0f, 1.0f);
  for (int trial = 0; trial < 2000; ++trial) {
    const glm::ivec3 cell(int(u01(rng) * 6) - 3, int(u01(rng) * 6) - 3, int(u01(rng) * 6) - 3);
    // A segment through the cell: from a point inside it, both ways to the cell's faces.
    const glm::vec3 inside = glm::vec3(cell) + glm::vec3(u01(rng), u01(rng), u01(rng));
    const glm::vec3 d = glm::normalize(glm::vec3(dir(rng), dir(rng), dir(rng)));
    const glm::vec3 o = inside - 5.0f * d;
    float ta = -1e30f, tb = 1e30f;
    for (int a = 0; a < 3; ++a) {
      const float t0 = (float(cell[a]) - o[a]) / d[a], t1 = (float(cell[a] + 1) - o[a]) / d[a];
      ta = std::max(ta, std::min(t0, t1));
      tb = std::min(tb, std::max(t0, t1));
    }
    const glm::vec4 s = fcc_cell_splits(cell, o, d, ta, tb);
    ASSERT_LE(s.x, s.y);
    ASSERT_LE(s.y, s.z);
    ASSERT_LE(s.z, s.w);
    const float bounds[6] = {ta, s.x, s.y, s.z, s.w, tb};
    for (int k = 0; k < 5; ++k) {
      const float s0 = bounds[k], s1 = bounds[k + 1];
      if (s1 - s0 < 1e-4f) continue;
      // Points at a quarter and three quarters of the sub-segment lie in the same piece.
      const FccFrame f1 = fcc_locate(o + (s0 + 0.25f * (s1 - s0)) * d);
      const FccFrame f2 = fcc_locate(o + (s0 + 0.75f * (s1 - s0)) * d);
      EXPECT_EQ(f1.origin, f2.origin) << "trial " << trial << " sub-segment " << k;
      EXPECT_EQ(f1.axis, f2.axis) << "trial " << trial << " sub-segment " << k;
      EXPECT_EQ(f1.type, f2.type) << "trial " << trial << " sub-segment " << k;
    }
  }
}

TEST(Ray, SegmentBernsteinFormIsTheSplineAlongTheRay) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f), u01(0.0f, 1.0f);
  // Random coefficients on a small block of sites, hashed so any site has one.
  auto coefficientAt = [](const glm::ivec3& ijk) {
    const uint32_t h = uint32_t(ijk.x * 73856093) ^ uint32_t(ijk.y * 19349663) ^ uint32_t(ijk.z * 83492791);
    return float(h % 2001u) / 1000.0f - 1.0f;
  };
  for (int trial = 0; trial < 2000; ++trial) {
    const glm::vec3 p = glm::vec3(u01(rng), u01(rng), u01(rng)) * 4.0f;
    const FccFrame frame = fcc_locate(p);
    const glm::vec3 d = glm::normalize(glm::vec3(value(rng), value(rng), value(rng)));
    const float s0 = -0.05f, s1 = 0.05f, iso = 0.1f;
    const FccCubic cubic = fcc_cubic(gatherSamples(frame, coefficientAt), frame.type);
    const glm::vec4 b = fcc_segment_bernstein(cubic, frame, p, d, s0, s1, iso);
    for (float u : {0.0f, 0.3f, 0.5f, 1.0f}) {
      const glm::vec3 x = p + (s0 + u * (s1 - s0)) * d;
      // The cubic of this piece, continued past its faces, at x.
      const glm::vec3 q = glm::vec3(frame.axis) * (x - glm::vec3(frame.origin));
      const float expected = fcc_decasteljau3(cubic, fcc_barycentric(q, frame.type)) / FCC_CUBIC_DENOM - iso;
      EXPECT_NEAR(bernstein3(glm::dvec4(b), u), expected, 2e-5) << "trial " << trial << " u " << u;
      // And inside the piece, the spline itself.
      if (u == 0.5f) {
        EXPECT_NEAR(bernstein3(glm::dvec4(b), u), evaluate(x, coefficientAt) - iso, 2e-5);
      }
    }
  }
}

}  // namespace
}  // namespace fcc::spline
