// Property tests of the FCC box spline (sparse/FccSpline.h) against its definition.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "SplineTestData.h"
#include "sparse/BoxSplineReference.h"
#include "sparse/Spline.h"

namespace fcc::spline {
namespace {

using test::hashedCoefficient;
using test::PointSource;

// float32 evaluation of O(1) data: a few ulps of the 24-term sums.
constexpr float kFloatTol = 2e-6f;

using test::str;

// The spline of a single unit coefficient at site `at` is the kernel M_fcc(x - at).
float kernel(const glm::vec3& x) {
  return evaluate(x, [](const glm::ivec3& ijk) { return ijk == glm::ivec3(0) ? 1.0f : 0.0f; });
}

TEST(Spline, KernelFacts) {
  EXPECT_NEAR(kernel(glm::vec3(0)), 0.5f, kFloatTol);
  for (int a : {-1, 1})
    for (int b : {-1, 1})
      for (const glm::vec3& p : {glm::vec3(a, b, 0), glm::vec3(a, 0, b), glm::vec3(0, a, b)})
        EXPECT_NEAR(kernel(p), 1.0f / 24.0f, kFloatTol) << "at " << str(p);
  // The other FCC points nearby, e.g. (2,0,0), are outside the open support.
  for (const glm::vec3& p : {glm::vec3(2, 0, 0), glm::vec3(0, -2, 0), glm::vec3(2, 1, 1), glm::vec3(2, 2, 0)})
    EXPECT_NEAR(kernel(p), 0.0f, kFloatTol) << "at " << str(p);
  // Zero on and outside |x|_inf = 2.
  PointSource points(7, -2.0f, 2.0f);
  for (int i = 0; i < 2000; ++i) {
    glm::vec3 p = points.next();
    p[i % 3] = (i & 1) ? 2.0f : -2.0f;
    EXPECT_NEAR(kernel(p), 0.0f, kFloatTol) << "on the support's boundary at " << str(p);
    p[i % 3] *= 1.3f;
    EXPECT_EQ(kernel(p), 0.0f) << "outside the support at " << str(p);
  }
}

TEST(Spline, PartitionOfUnity) {
  PointSource points(1, -50.0f, 50.0f);
  for (int i = 0; i < 10000; ++i) {
    const glm::vec3 p = points.next();
    const auto r = evaluateWithGradient(p, [](const glm::ivec3&) { return 1.0f; });
    ASSERT_NEAR(r.value, 1.0f, 4e-6f) << "at " << str(p);
    ASSERT_NEAR(glm::length(r.gradient), 0.0f, 4e-6f) << "at " << str(p);
  }
}

TEST(Spline, MatchesBoxSplineDefinition) {
  // The BB-form fast path against the slow recurrence-based sum over the kernel's support.
  PointSource points(2, -4.0f, 4.0f);
  for (int i = 0; i < 1500; ++i) {
    const glm::vec3 p = points.next();
    const float fast = evaluate(p, [](const glm::ivec3& ijk) { return hashedCoefficient(ijk); });
    const double slow = splineReference(glm::dvec3(p), [](const glm::ivec3& ijk) { return double(hashedCoefficient(ijk)); });
    ASSERT_NEAR(fast, slow, 2e-6) << "at " << str(p);
  }
}

// A random quadratic polynomial and its gradient.
struct Quadratic {
  float c0;
  glm::vec3 c1;
  glm::mat3 c2;  // symmetric
  float operator()(const glm::vec3& x) const { return c0 + glm::dot(c1, x) + glm::dot(x, c2 * x); }
  glm::vec3 gradient(const glm::vec3& x) const { return c1 + 2.0f * (c2 * x); }
};

Quadratic randomQuadratic(std::mt19937& rng) {
  std::uniform_real_distribution<float> d(-1.0f, 1.0f);
  Quadratic q{d(rng), glm::vec3(d(rng), d(rng), d(rng)), glm::mat3(0.0f)};
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) q.c2[a][b] = q.c2[b][a] = 0.2f * d(rng);
  return q;
}

TEST(Spline, PrefilterReproducesQuadratics) {
  std::mt19937 rng(3);
  PointSource points(4, -3.0f, 3.0f);
  for (int trial = 0; trial < 50; ++trial) {
    const Quadratic q = randomQuadratic(rng);
    auto coefficient = [&](const glm::ivec3& ijk) {
      return prefilterAt(ijk, [&](const glm::ivec3& s) { return q(glm::vec3(s)); });
    };
    for (int i = 0; i < 100; ++i) {
      const glm::vec3 p = points.next();
      const auto r = evaluateWithGradient(p, coefficient);
      // Values up to ~8 here: a relative float32 tolerance.
      ASSERT_NEAR(r.value, q(p), 2e-5f) << "quadratic " << trial << " at " << str(p);
      const glm::vec3 g = q.gradient(p);
      ASSERT_LT(glm::length(r.gradient - g), 2e-5f) << "gradient " << str(r.gradient) << " vs " << str(g) << " at " << str(p);
    }
  }
}

TEST(Spline, WithoutPrefilterQuadraticsAreOffByAConstant) {
  // sum_j j_x^2 M(x - j) = x^2 + 1/3 (the kernel's second moment along an axis).
  PointSource points(5, -3.0f, 3.0f);
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 p = points.next();
    const float s = evaluate(p, [](const glm::ivec3& ijk) { return float(ijk.x * ijk.x); });
    ASSERT_NEAR(s - p.x * p.x, 1.0f / 3.0f, 2e-5f) << "at " << str(p);
  }
  // Linear polynomials are reproduced without the prefilter.
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 p = points.next();
    const float s = evaluate(p, [](const glm::ivec3& ijk) { return 0.5f * ijk.x - 2.0f * ijk.y + ijk.z + 3.0f; });
    ASSERT_NEAR(s, 0.5f * p.x - 2.0f * p.y + p.z + 3.0f, 2e-5f) << "at " << str(p);
  }
}

// Evaluates the polynomial piece that contains `inside` at the point `at`; false if `at` is not on that
// piece's closure (`inside` fell into a piece beyond a nearby edge).
bool evaluatePiece(const glm::vec3& inside, const glm::vec3& at, FccValueGradient& out) {
  FccFrame frame = fcc_locate(inside);
  frame.q = glm::vec3(frame.axis) * (at - glm::vec3(frame.origin));
  const glm::vec4 l = fcc_barycentric(frame.q, frame.type);
  if (glm::min(glm::min(l.x, l.y), glm::min(l.z, l.w)) < -1e-5f) return false;
  const FccSamples s = gatherSamples(frame, [](const glm::ivec3& ijk) { return hashedCoefficient(ijk, 9); });
  out = fcc_value_gradient(s, frame);
  return true;
}

TEST(Spline, C1AcrossCubeAndTetrahedronFaces) {
  // Points on knot planes: cube faces (x = k) and the tetrahedra's faces (x +- y +- z = k).
  const std::array<glm::vec3, 7> normals = {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1),
                                            glm::vec3(1, 1, 1), glm::vec3(1, 1, -1), glm::vec3(1, -1, 1),
                                            glm::vec3(-1, 1, 1)};
  constexpr float kSide = 1e-3f;  // how far inside each piece its frame is chosen
  PointSource points(6, -2.0f, 2.0f);
  int checked = 0;
  for (int i = 0; i < 7000; ++i) {
    const glm::vec3 n = normals[i % 7];
    glm::vec3 p = points.next();
    // Project onto the nearest plane n.x = k of this family.
    const float k = std::round(glm::dot(n, p));
    p -= n * ((glm::dot(n, p) - k) / glm::dot(n, n));
    const glm::vec3 step = kSide * glm::normalize(n);
    FccValueGradient a, b;
    if (!evaluatePiece(p + step, p, a) || !evaluatePiece(p - step, p, b)) continue;
    ++checked;
    ASSERT_NEAR(a.value, b.value, 1e-5f) << "value jumps across plane n=" << str(n) << " at " << str(p);
    ASSERT_LT(glm::length(a.gradient - b.gradient), 1e-5f)
        << "gradient jumps across plane n=" << str(n) << " at " << str(p) << ": " << str(a.gradient) << " vs " << str(b.gradient);
  }
  EXPECT_GT(checked, 6500) << "too few points were away from edges to test";
}

TEST(Spline, CubeSymmetries) {
  // For each of the 48 symmetries S (axis permutation and signs), data c'(j) = c(S^-1 j) has spline
  // s'(x) = s(S^-1 x) and gradient S grad s(S^-1 x).
  const std::array<glm::ivec3, 6> perms = {glm::ivec3(0, 1, 2), glm::ivec3(0, 2, 1), glm::ivec3(1, 0, 2),
                                           glm::ivec3(1, 2, 0), glm::ivec3(2, 0, 1), glm::ivec3(2, 1, 0)};
  PointSource points(8, -3.0f, 3.0f);
  for (const glm::ivec3& perm : perms)
    for (int signs = 0; signs < 8; ++signs) {
      const glm::ivec3 sign((signs & 1) ? -1 : 1, (signs & 2) ? -1 : 1, (signs & 4) ? -1 : 1);
      glm::mat3 S(0.0f);  // (S x)[r] = sign[r] * x[perm[r]]
      for (int r = 0; r < 3; ++r) S[perm[r]][r] = float(sign[r]);
      const glm::mat3 Sinv = glm::transpose(S);
      auto original = [](const glm::ivec3& ijk) { return hashedCoefficient(ijk, 11); };
      auto transformed = [&](const glm::ivec3& ijk) { return original(glm::ivec3(glm::round(Sinv * glm::vec3(ijk)))); };
      for (int i = 0; i < 100; ++i) {
        const glm::vec3 x = points.next();
        const auto a = evaluateWithGradient(x, transformed);
        const auto b = evaluateWithGradient(Sinv * x, original);
        ASSERT_NEAR(a.value, b.value, kFloatTol * 4) << "perm " << str(glm::vec3(perm)) << " signs " << signs << " at " << str(x);
        ASSERT_LT(glm::length(a.gradient - S * b.gradient), 1e-5f) << "perm " << str(glm::vec3(perm)) << " signs " << signs;
      }
    }
}

TEST(Spline, GradientMatchesCentralDifferences) {
  PointSource points(10, -3.0f, 3.0f);
  auto c = [](const glm::ivec3& ijk) { return hashedCoefficient(ijk, 12); };
  auto slow = [&](const glm::dvec3& x) { return splineReference(x, [&](const glm::ivec3& ijk) { return double(c(ijk)); }); };
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 p = points.next();
    const auto r = evaluateWithGradient(p, c);
    // Central differences of the double-precision reference: O(h^2) truncation of a cubic.
    constexpr double h = 1e-4;
    for (int a = 0; a < 3; ++a) {
      glm::dvec3 e(0.0);
      e[a] = h;
      const double fd = (slow(glm::dvec3(p) + e) - slow(glm::dvec3(p) - e)) / (2 * h);
      ASSERT_NEAR(r.gradient[a], fd, 2e-5) << "axis " << a << " at " << str(p);
    }
  }
}

}  // namespace
}  // namespace fcc::spline

namespace fcc::spline {
namespace {

TEST(SplineBounds, CubeBoundsContainTheSpline) {
  // Conservative: at 10^6 random points the spline lies within its cube's BB-coefficient bounds.
  constexpr float kTol = 1e-6f;  // float round-off of the value against the scaled coefficients
  auto c = [](const glm::ivec3& ijk) { return test::hashedCoefficient(ijk, 13); };
  PointSource points(14, -6.0f, 6.0f);
  for (int i = 0; i < 1000000; ++i) {
    const glm::vec3 p = points.next();
    const FccRange b = cubeBounds(glm::ivec3(glm::floor(p)), c);
    const float v = evaluate(p, c);
    ASSERT_GE(v, b.lo - kTol) << "at " << str(p);
    ASSERT_LE(v, b.hi + kTol) << "at " << str(p);
  }
}

TEST(SplineBounds, PieceCentroidsLieInTheirOwnPieces) {
  // Each of a cube's five centroids locates to a different piece of that cube, inside it.
  for (const glm::ivec3 corner : {glm::ivec3(0, 0, 0), glm::ivec3(1, 0, 0), glm::ivec3(-3, 2, 5), glm::ivec3(4, -1, -2)}) {
    std::vector<glm::ivec4> seen;  // (origin, axis and type folded into one int)
    for (int piece = 0; piece < 5; ++piece) {
      const glm::vec3 x = fcc_piece_centroid(corner, piece);
      EXPECT_EQ(glm::ivec3(glm::floor(x)), corner) << "piece " << piece;
      const FccFrame f = fcc_locate(x);
      const glm::vec4 l = fcc_barycentric(f.q, f.type);
      EXPECT_GT(glm::min(glm::min(l.x, l.y), glm::min(l.z, l.w)), 0.1f) << "piece " << piece << " at " << str(x);
      const glm::ivec4 id(f.origin, (f.axis.x + 1) * 9 + (f.axis.y + 1) * 3 + (f.axis.z + 1) + 27 * f.type);
      for (const glm::ivec4& other : seen) EXPECT_NE(other, id) << "two centroids in one piece, piece " << piece;
      seen.push_back(id);
    }
  }
}

TEST(SplineBounds, TightForConstantData) {
  const FccRange b = cubeBounds(glm::ivec3(3, -2, 7), [](const glm::ivec3&) { return 0.75f; });
  EXPECT_NEAR(b.lo, 0.75f, 1e-6f);
  EXPECT_NEAR(b.hi, 0.75f, 1e-6f);
}

}  // namespace
}  // namespace fcc::spline
