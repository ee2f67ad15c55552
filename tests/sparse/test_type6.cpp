// The type-6 cubic C1 spline (sparse/CcType6.h, `type6`) by its own properties, beyond what
// test_reconstructions checks of every reconstruction: exactly which polynomials it reproduces (the
// trilinear ones) and what it makes of the pure squares (x^2 -> x^2 + 1/4), C1 across every face of
// every tetrahedron, the 48 symmetries of the cube, the paper's Example 1, the ray form along a segment,
// and the exact sphere (at the radius the 3/4 shift gives) through the reference raycaster.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "SplineTestData.h"
#include "sparse/CcType6.h"
#include "sparse/LatticeSamples.h"
#include "sparse/Reconstruction.h"
#include "sparse/ReferenceRaycast.h"

namespace fcc {
namespace {

using test::hashedCoefficient;
using test::str;

// Tolerances for data of magnitude ~1 in float: a jump across a face larger than these is a break of
// C0 (value) or C1 (gradient), not rounding.
constexpr float kValueJump = 2e-6f;
constexpr float kGradientJump = 2e-5f;

// The 48 symmetries of the cube: p -> (s0 p[perm0], s1 p[perm1], s2 p[perm2]).
struct Symmetry {
  glm::ivec3 perm, sign;
  glm::vec3 apply(const glm::vec3& p) const { return glm::vec3(sign) * glm::vec3(p[perm.x], p[perm.y], p[perm.z]); }
  glm::ivec3 apply(const glm::ivec3& p) const { return sign * glm::ivec3(p[perm.x], p[perm.y], p[perm.z]); }
  glm::ivec3 inverse(const glm::ivec3& q) const {
    glm::ivec3 p;
    p[perm.x] = sign.x * q.x;
    p[perm.y] = sign.y * q.y;
    p[perm.z] = sign.z * q.z;
    return p;
  }
};
std::vector<Symmetry> cubeSymmetries() {
  std::vector<Symmetry> out;
  const glm::ivec3 perms[6] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& p : perms)
    for (int s = 0; s < 8; ++s) out.push_back({p, glm::ivec3(s & 1 ? -1 : 1, s & 2 ? -1 : 1, s & 4 ? -1 : 1)});
  return out;
}

const Reconstruction& type6() {
  static const auto recon = makeReconstruction("type6");
  return *recon;
}

// Trilinear polynomials (1, x, y, z, xy, yz, xz, xyz in x / 4 ...) with random coefficients: exact.
TEST(Type6, ReproducesTrilinearPolynomials) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    double k[8];
    for (double& c : k) c = u(rng);
    auto f = [&](const glm::dvec3& p) {
      const glm::dvec3 q = p / 4.0;
      return k[0] + k[1] * q.x + k[2] * q.y + k[3] * q.z + k[4] * q.x * q.y + k[5] * q.y * q.z + k[6] * q.x * q.z +
             k[7] * q.x * q.y * q.z;
    };
    auto grad = [&](const glm::dvec3& p) {
      const glm::dvec3 q = p / 4.0;
      return glm::dvec3(k[1] + k[4] * q.y + k[6] * q.z + k[7] * q.y * q.z, k[2] + k[4] * q.x + k[5] * q.z + k[7] * q.x * q.z,
                        k[3] + k[5] * q.y + k[6] * q.x + k[7] * q.x * q.y) /
             4.0;
    };
    const SiteValue at = [&](const glm::ivec3& ijk) { return float(f(glm::dvec3(ijk))); };
    test::PointSource points(10 + trial, -3.0f, 3.0f);
    for (int i = 0; i < 2000; ++i) {
      const glm::vec3 p = points.next();
      const auto s = type6().evaluate(p, at);
      ASSERT_NEAR(s.value, f(p), 2e-6) << "trial " << trial << " at " << str(p);
      ASSERT_LT(glm::length(glm::dvec3(s.gradient) - grad(p)), 2e-5) << "trial " << trial << " at " << str(p);
    }
  }
}

// A quadratic q becomes q + (its x^2, y^2 and z^2 coefficients summed) / 4, everywhere: not reproduced,
// but off by a constant (the corner coefficient is the mean of the 8 samples around the corner).
TEST(Type6, AddsAQuarterPerPureSquare) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    glm::dmat3 a;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j <= i; ++j) a[i][j] = a[j][i] = u(rng) / 16.0;
    const glm::dvec3 g(u(rng), u(rng), u(rng));
    auto f = [&](const glm::dvec3& p) { return glm::dot(p, a * p) + glm::dot(g, p) / 4.0; };
    const double shift = (a[0][0] + a[1][1] + a[2][2]) / 4.0;
    const SiteValue at = [&](const glm::ivec3& ijk) { return float(f(glm::dvec3(ijk))); };
    test::PointSource points(20 + trial, -3.0f, 3.0f);
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const glm::vec3 p = points.next();
      const auto s = type6().evaluate(p, at);
      worst = std::max(worst, std::abs(s.value - f(p) - shift));
      ASSERT_NEAR(s.value, f(p) + shift, 2e-6) << "trial " << trial << " at " << str(p);
      ASSERT_LT(glm::length(glm::dvec3(s.gradient) - (2.0 * (a * glm::dvec3(p)) + g / 4.0)), 2e-5) << str(p);
    }
    // The shift is real (the claim "reproduces 1" in the contract is tight for quadratics).
    EXPECT_GT(std::abs(shift), 1e-3);
  }
}

// Every face of every tetrahedron lies in a mirror plane of the partition (x = c +- 1/2, x = +-y, ...),
// so the piece across a face is the one holding the mirror image of this piece's centroid. At random
// points of each face both pieces' polynomials agree in value and gradient.
TEST(Type6, C1AcrossEveryFaceOfEveryTetrahedron) {
  const SiteValue at = [](const glm::ivec3& ijk) { return hashedCoefficient(ijk, 7); };
  const glm::vec3 canonical[4] = {{0.0f, 0.0f, 0.0f}, {-0.5f, 0.0f, 0.0f}, {-0.5f, -0.5f, 0.5f}, {-0.5f, 0.5f, 0.5f}};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.05f, 1.0f);
  float worstValue = 0.0f, worstGradient = 0.0f;
  int faces = 0;
  for (const glm::ivec3 centre : {glm::ivec3(0), glm::ivec3(3, -2, 5), glm::ivec3(-7, 4, 1)}) {
    for (const Symmetry& m : cubeSymmetries()) {
      glm::vec3 v[4];
      for (int i = 0; i < 4; ++i) v[i] = glm::vec3(centre) + m.apply(canonical[i]);
      const glm::vec3 centroid = 0.25f * (v[0] + v[1] + v[2] + v[3]);
      for (int drop = 0; drop < 4; ++drop) {
        const glm::vec3 a = v[(drop + 1) % 4], b = v[(drop + 2) % 4], c = v[(drop + 3) % 4];
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        const glm::vec3 mirrored = centroid - 2.0f * glm::dot(centroid - a, n) * n;
        for (int k = 0; k < 4; ++k) {
          const float wa = u(rng), wb = u(rng), wc = u(rng), sum = wa + wb + wc;
          const glm::vec3 p = (wa * a + wb * b + wc * c) / sum;
          const auto here = type6().evaluateInPiece(centroid, p, at);
          const auto there = type6().evaluateInPiece(mirrored, p, at);
          worstValue = std::max(worstValue, std::abs(here.value - there.value));
          worstGradient = std::max(worstGradient, glm::length(here.gradient - there.gradient));
          ASSERT_LT(std::abs(here.value - there.value), kValueJump) << "face point " << str(p);
          ASSERT_LT(glm::length(here.gradient - there.gradient), kGradientJump)
              << "face point " << str(p) << ": " << str(here.gradient) << " vs " << str(there.gradient);
        }
        ++faces;
      }
    }
  }
  std::printf("[   INFO   ] %d faces, worst value jump %.3g, gradient jump %.3g\n", faces, worstValue, worstGradient);
  // A check that could fail: the piece across is another piece (its polynomial differs inside).
  const auto inside = type6().evaluateInPiece(glm::vec3(-0.3f, 0.05f, 0.2f), glm::vec3(-0.3f, 0.3f, 0.2f), at);
  const auto own = type6().evaluate(glm::vec3(-0.3f, 0.3f, 0.2f), at);
  EXPECT_GT(std::abs(inside.value - own.value) + glm::length(inside.gradient - own.gradient), 1e-4f);
}

// The spline of data moved by a symmetry M of the cube (d'(M ijk) = d(ijk)) is the spline moved by M:
// s'(M p) = s(p), grad s'(M p) = M grad s(p).
TEST(Type6, CommutesWithThe48SymmetriesOfTheCube) {
  const SiteValue at = [](const glm::ivec3& ijk) { return hashedCoefficient(ijk, 8); };
  test::PointSource points(30, -4.0f, 4.0f);
  for (const Symmetry& m : cubeSymmetries()) {
    const SiteValue moved = [&](const glm::ivec3& ijk) { return hashedCoefficient(m.inverse(ijk), 8); };
    for (int i = 0; i < 300; ++i) {
      const glm::vec3 p = points.next();
      const auto s = type6().evaluate(p, at);
      const auto t = type6().evaluate(m.apply(p), moved);
      ASSERT_NEAR(s.value, t.value, 2e-6f) << "at " << str(p);
      ASSERT_LT(glm::length(m.apply(s.gradient) - t.gradient), 2e-5f) << "at " << str(p);
    }
  }
}

// Sorokina and Zeilfelder's Example 1: f = 1 + x + xy + xyz at the points of [0, 2]^3; on the cube
// about (1, 1, 1) the corner coefficient c_0030 of the tetrahedron towards front-left-top is 17/8.
TEST(Type6, PaperExampleOneCornerCoefficient) {
  auto f = [](const glm::ivec3& p) { return float(1 + p.x + p.x * p.y + p.x * p.y * p.z); };
  const spline::CcType6Frame frame = spline::cc_type6_locate(glm::vec3(1.0f - 0.375f, 1.0f, 1.25f));
  EXPECT_EQ(frame.centre, glm::ivec3(1));
  EXPECT_EQ(frame.axes, glm::ivec3(0, 1, 2));
  EXPECT_EQ(frame.signs, glm::ivec3(1, 1, 1));
  spline::FccSamples27 s;
  for (int i = 0; i < 27; ++i) s.v[i] = f(spline::cc_type6_stencil_site(frame, i));
  const spline::FccCubic c = spline::cc_type6_cubic(s);
  EXPECT_FLOAT_EQ(c.b[16], 17.0f / 8.0f);  // (0,0,3,0): FccCubic's 17th
}

// The generated sums of the non-zero weights (CC_TYPE6_ROWS, what every dialect evaluates) equal the
// table's row-by-row loop bit for bit, on random samples of either sign and mixed magnitudes.
TEST(Type6, UnrolledRowsEqualTheTableBitForBit) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), scale(-6.0f, 6.0f);
  for (int trial = 0; trial < 2000; ++trial) {
    spline::FccSamples27 s;
    for (int i = 0; i < 27; ++i) s.v[i] = u(rng) * std::exp2(scale(rng));
    const spline::FccCubic unrolled = spline::cc_type6_cubic(s), table = spline::cc_type6_cubic_from_table(s);
    for (int r = 0; r < 20; ++r)
      ASSERT_EQ(std::memcmp(&unrolled.b[r], &table.b[r], sizeof(float)), 0)
          << "trial " << trial << " row " << r << ": " << unrolled.b[r] << " against " << table.b[r];
  }
}

// The Bernstein form along a segment inside a piece equals the piece along it; the BB coefficients
// bound the piece.
TEST(Type6, SegmentBernsteinEqualsThePieceAndTheCoefficientsBoundIt) {
  const SiteValue at = [](const glm::ivec3& ijk) { return hashedCoefficient(ijk, 9); };
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  for (int trial = 0; trial < 500; ++trial) {
    const glm::vec3 inside(2.0f + u(rng), -1.0f + u(rng), 4.0f + u(rng));
    const spline::CcType6Frame frame = spline::cc_type6_locate(inside);
    spline::FccSamples27 s;
    for (int i = 0; i < 27; ++i) s.v[i] = at(spline::cc_type6_stencil_site(frame, i));
    const spline::FccCubic c = spline::cc_type6_cubic(s);
    const glm::vec3 a = inside + glm::vec3(u(rng), u(rng), u(rng)), b = inside + glm::vec3(u(rng), u(rng), u(rng));
    const glm::vec4 bz = spline::cc_type6_segment_bernstein(c, frame, a, b, 0.25f);
    for (float w : {0.0f, 0.3f, 0.5f, 0.77f, 1.0f}) {
      const float direct = spline::cc_type6_value_gradient(c, frame, a + w * (b - a)).value;
      ASSERT_NEAR(spline::fcc_bernstein3(bz, w) + 0.25f, direct, 1e-5f) << "trial " << trial;
      ASSERT_NEAR(type6().evaluateInPiece(inside, a + w * (b - a), at).value, direct, 1e-6f);
    }
    const spline::FccRange range = spline::cc_type6_range(c);
    const float v = type6().evaluate(inside, at).value;
    ASSERT_GE(v, range.lo - 1e-6f);
    ASSERT_LE(v, range.hi + 1e-6f);
  }
}

// f = |p - c|^2 becomes |p - c|^2 + 3/4, so the isosurface at r^2 is the sphere of radius
// sqrt(r^2 - 3/4): the reference raycaster's hits against the exact intersection with it.
TEST(Type6, SphereIsExactAtTheShiftedRadius) {
  const glm::dvec3 c(0.3, -0.2, 0.1);
  const double r = 9.0, rShifted = std::sqrt(r * r - 0.75);
  LatticeSamples samples(Lattice::Cc, glm::ivec3(-20), glm::ivec3(41), 0.0f);
  samples.fill([&](const glm::ivec3& ijk) {
    const glm::dvec3 q = glm::dvec3(ijk) - c;
    return float(glm::dot(q, q));
  });
  const CellBounds bounds(samples);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  double worst = 0.0;
  int hits = 0;
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 target = glm::vec3(c) + 0.5f * float(r) * std::abs(u(rng)) * glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
    const glm::vec3 o = glm::vec3(c) + 18.0f * glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
    const glm::vec3 d = glm::normalize(target - o);
    const RayHit hit = firstHit(type6(), samples.accessor(), bounds, o, d, 0.0f, 40.0f, float(r * r));
    const glm::dvec3 oc = glm::dvec3(o) - c, dd(d);
    const double b = glm::dot(oc, dd), disc = b * b - (glm::dot(oc, oc) - rShifted * rShifted);
    if (disc <= 1.0) continue;
    ASSERT_TRUE(hit.hit) << "ray " << i;
    worst = std::max(worst, std::abs(double(hit.t) - (-b - std::sqrt(disc))));
    ++hits;
  }
  std::printf("[   INFO   ] type6 sphere: worst |t - t_exact| %.3g over %d hits\n", worst, hits);
  EXPECT_GT(hits, 200);
  EXPECT_LT(worst, 2e-4);
}

}  // namespace
}  // namespace fcc
