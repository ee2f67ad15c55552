// The exact ray/isosurface pieces of sparse/FccRay.h, on the CPU, against slow references: the first
// root of random cubics (found by dense sampling in double precision), the plane splits of a cell
// (each sub-segment lies in one piece), and the segment's Bernstein form (equals the spline).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
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

// The mean of a cubic over a sub-interval and its primitive (ReconCommon.h; DVR's sub-step values), on
// random cubics and intervals against Simpson's rule in double (exact for cubics), within float
// rounding of the coefficients.
TEST(Ray, CubicMeansAndPrimitivesAreTheirIntegrals) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> coefficient(-1.0f, 1.0f), u01(0.0f, 1.0f);
  constexpr double kTol = 2e-6;  // float rounding of values of order 1
  auto simpson = [](const glm::dvec4& b, double a, double c) {
    const double m = 0.5 * (a + c);
    auto panel = [&](double x, double y) { return (y - x) / 6.0 * (bernstein3(b, x) + 4.0 * bernstein3(b, 0.5 * (x + y)) + bernstein3(b, y)); };
    return panel(a, m) + panel(m, c);
  };
  for (int trial = 0; trial < 5000; ++trial) {
    const glm::vec4 b(coefficient(rng), coefficient(rng), coefficient(rng), coefficient(rng));
    const float ua = u01(rng), ub = u01(rng), lo = std::min(ua, ub), hi = std::max(ua, ub);
    const float um = 0.5f * (lo + hi), w = hi - lo;
    const double expectedMean = w > 0.0f ? simpson(glm::dvec4(b), lo, hi) / w : bernstein3(glm::dvec4(b), um);
    ASSERT_NEAR(fcc_bernstein3_mean(b, um, w), expectedMean, kTol)
        << "b = " << b.x << " " << b.y << " " << b.z << " " << b.w << ", [" << lo << ", " << hi << "]";
    const glm::vec4 p = fcc_bernstein3_primitive(b);
    ASSERT_NEAR(fcc_primitive3_at(p, ua), simpson(glm::dvec4(b), 0.0, ua), kTol)
        << "b = " << b.x << " " << b.y << " " << b.z << " " << b.w << ", u = " << ua;
  }
  // The whole interval: the mean of the Bernstein coefficients.
  const glm::vec4 b(0.3f, -1.0f, 2.0f, 0.5f);
  EXPECT_NEAR(fcc_primitive3_at(fcc_bernstein3_primitive(b), 1.0f), (0.3 - 1.0 + 2.0 + 0.5) / 4.0, kTol);
  // A hump's mean is not its midpoint value (what the sub-steps used to take): 1/2 against 3/4.
  const glm::vec4 hump(0.0f, 1.0f, 1.0f, 0.0f);
  EXPECT_NEAR(fcc_bernstein3_mean(hump, 0.5f, 1.0f), 0.5f, 1e-7f);
  EXPECT_NEAR(fcc_bernstein3(hump, 0.5f), 0.75f, 1e-7f);
}

// A random unit cell near the origin and a ray through it: the chord [ta, tb] from face to face, through
// a random point inside the cell.
struct CellChord {
  glm::ivec3 cell;
  glm::vec3 o, d;
  float ta, tb;
};

// The chord of the ray o + t d through unit cell `cell`: the slabs' entry and exit.
CellChord cellChord(const glm::ivec3& cell, const glm::vec3& o, const glm::vec3& d) {
  CellChord c{cell, o, d, -1e30f, 1e30f};
  for (int a = 0; a < 3; ++a) {
    const float t0 = (float(cell[a]) - o[a]) / d[a], t1 = (float(cell[a] + 1) - o[a]) / d[a];
    c.ta = std::max(c.ta, std::min(t0, t1));
    c.tb = std::min(c.tb, std::max(t0, t1));
  }
  return c;
}

CellChord randomCellChord(std::mt19937& rng) {
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), dir(-1.0f, 1.0f);
  const glm::ivec3 cell(int(u01(rng) * 6) - 3, int(u01(rng) * 6) - 3, int(u01(rng) * 6) - 3);
  const glm::vec3 inside = glm::vec3(cell) + glm::vec3(u01(rng), u01(rng), u01(rng));
  const glm::vec3 d = glm::normalize(glm::vec3(dir(rng), dir(rng), dir(rng)));
  return cellChord(cell, inside - 5.0f * d, d);
}

TEST(Ray, CellSplitsSeparateThePieces) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 2000; ++trial) {
    const CellChord chord = randomCellChord(rng);
    const glm::vec3 o = chord.o, d = chord.d;
    const float ta = chord.ta, tb = chord.tb;
    const glm::vec4 s = fcc_cell_splits(chord.cell, o, d, ta, tb);
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

// Random coefficients on any site, hashed.
float hashedCoefficient(const glm::ivec3& ijk) {
  const uint32_t h = uint32_t(ijk.x * 73856093) ^ uint32_t(ijk.y * 19349663) ^ uint32_t(ijk.z * 83492791);
  return float(h % 2001u) / 1000.0f - 1.0f;
}

// The segment [sa, sb] of chord c's ray in the piece of c's cell holding it, on hashedCoefficient's
// data (march_fcc.glsl's pieceSegment).
FccSegment pieceSegmentOf(const CellChord& c, float sa, float sb) {
  const FccFrame frame = fcc_locate(glm::clamp(c.o + 0.5f * (sa + sb) * c.d, glm::vec3(c.cell), glm::vec3(c.cell + 1)));
  return fcc_segment_with_slopes(fcc_cubic(gatherSamples(frame, hashedCoefficient), frame.type), frame, c.o, c.d, sa, sb);
}

// The piece at x, its cubic, and the spline's value, slope and curvature along d there (fcc_ray_jet's
// job, in double, from the piece's cubic at points 0, +-h, +-2h: quotients exact for cubics).
glm::dvec3 jetOfPieceAt(const glm::vec3& inPiece, const glm::vec3& x, const glm::vec3& d) {
  const FccFrame frame = fcc_locate(inPiece);
  const FccCubic cubic = fcc_cubic(gatherSamples(frame, hashedCoefficient), frame.type);
  auto at = [&](double t) {
    const glm::dvec3 q = glm::dvec3(frame.axis) * (glm::dvec3(x) + t * glm::dvec3(d) - glm::dvec3(frame.origin));
    return double(fcc_decasteljau3(cubic, fcc_barycentric(glm::vec3(q), frame.type))) / FCC_CUBIC_DENOM;
  };
  const double h = 0.05;
  return {at(0.0), (8 * (at(h) - at(-h)) - (at(2 * h) - at(-2 * h))) / (12 * h),
          (at(h) - 2 * at(0.0) + at(-h)) / (h * h)};
}

// The box spline's smoothness, which the DVR's central-piece shortcut rests on: across a cube face
// (a plane holding two of the six directions) the pieces agree in value, slope and curvature (C2);
// across a face of the central piece (a plane holding three) in value and slope only (C1): the
// curvature jumps there in most places.
TEST(Ray, SplineIsC2AcrossCubeFacesAndC1AcrossCentralFaces) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.1f, 0.9f), dir(-1.0f, 1.0f);
  constexpr double kValueTol = 1e-5, kSlopeTol = 1e-4, kCurvatureTol = 1e-3;
  int curvatureJumps = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const bool central = trial % 2 == 0;
    // The even cell at the origin: its central piece's face x + y + z = 1; or the cube face x = 2.
    const float a = u(rng), b = u(rng);
    const glm::vec3 x = central ? glm::vec3(0.5f * a, 0.5f * b, 1.0f - 0.5f * a - 0.5f * b) : glm::vec3(2.0f, 2 + a, 2 + b);
    const glm::vec3 n = central ? glm::vec3(1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
    glm::vec3 d;
    do {  // not grazing the face: x -+ e d stays in the two pieces that share it
      d = glm::normalize(glm::vec3(dir(rng), dir(rng), dir(rng)));
    } while (std::abs(glm::dot(glm::normalize(n), d)) < 0.3f);
    if (glm::dot(d, n) < 0.0f) d = -d;
    const float e = 1e-4f;
    const glm::dvec3 before = jetOfPieceAt(x - e * d, x, d), after = jetOfPieceAt(x + e * d, x, d);
    ASSERT_NEAR(before.x, after.x, kValueTol) << "trial " << trial;
    ASSERT_NEAR(before.y, after.y, kSlopeTol) << "trial " << trial;
    if (central) {
      curvatureJumps += std::abs(before.z - after.z) > kCurvatureTol;
    } else {
      EXPECT_NEAR(before.z, after.z, kCurvatureTol) << "trial " << trial << " (cube face)";
    }
  }
  std::printf("central faces with a curvature jump: %d of 500\n", curvatureJumps);
  EXPECT_GT(curvatureJumps, 400);
}

// fcc_segment_with_slopes: the segment's coefficients are fcc_segment_bernstein's, its slopes the
// cubic's derivative along the ray at both ends.
TEST(Ray, SegmentSlopesAreTheCubicsDerivativeAtItsEnds) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<float> value(-1.0f, 1.0f), u01(0.0f, 1.0f);
  for (int trial = 0; trial < 1000; ++trial) {
    const glm::vec3 p = glm::vec3(u01(rng), u01(rng), u01(rng)) * 4.0f;
    const FccFrame frame = fcc_locate(p);
    const glm::vec3 d = glm::normalize(glm::vec3(value(rng), value(rng), value(rng)));
    const FccCubic cubic = fcc_cubic(gatherSamples(frame, hashedCoefficient), frame.type);
    const float s0 = -0.2f * u01(rng), s1 = 0.2f * u01(rng) + 1e-3f;
    const FccSegment seg = fcc_segment_with_slopes(cubic, frame, p, d, s0, s1);
    const glm::vec4 b = fcc_segment_bernstein(cubic, frame, p, d, s0, s1, 0.0f);
    for (int i = 0; i < 4; ++i) EXPECT_EQ(seg.b[i], b[i]) << trial;
    EXPECT_NEAR(seg.slope0, jetOfPieceAt(p, p + s0 * d, d).y, 2e-4) << trial;
    EXPECT_NEAR(seg.slope1, jetOfPieceAt(p, p + s1 * d, d).y, 2e-4) << trial;
  }
}

// The central piece's segment from its neighbours' (fcc_central_bernstein) is the spline there: on
// random chords through random cells that cross the central piece, the cubic at five points of
// [ta, tb] against the spline evaluated there. Taking the curvature too (as a C2 spline would allow)
// is off by up to 0.06 on the same data: the test sees it.
TEST(Ray, CentralPieceFromItsNeighboursIsTheSplineAlongTheRay) {
  std::mt19937 rng(17);
  constexpr double kValueTol = 1e-4;  // coefficients in [-1, 1]; float blossoms
  int crossing = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const CellChord chord = randomCellChord(rng);
    const glm::ivec3 cell = chord.cell;
    const glm::vec3 o = chord.o, d = chord.d;
    const float t0 = chord.ta, t1 = chord.tb;
    const glm::vec4 s = fcc_cell_splits(cell, o, d, t0, t1);
    ASSERT_FALSE(s.z < t1) << "a chord from face to face crosses the central piece's faces at most twice";
    if (!(s.y < t1) || s.y - s.x < 1e-3f) continue;
    ++crossing;
    const glm::dvec4 b(fcc_central_bernstein(pieceSegmentOf(chord, t0, s.x), pieceSegmentOf(chord, s.y, t1), s.x, s.y));
    for (double u : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      const glm::vec3 x = o + float(s.x + u * (s.y - s.x)) * d;
      const double expected = evaluate(glm::clamp(x, glm::vec3(cell), glm::vec3(cell + 1)), hashedCoefficient);
      EXPECT_NEAR(bernstein3(b, u), expected, kValueTol)
          << "trial " << trial << " u " << u << " t0 " << t0 << " ta " << s.x << " tb " << s.y << " t1 " << t1;
    }
  }
  EXPECT_GT(crossing, 2000);
}

// fcc_chord_knots on chords whose crossings rounding makes more than two: rays from 500 to 2 000 index
// units away entering a cell within 1e-5 of a face diagonal (an edge of the central piece), at a
// random slant. The chord built from its end pieces and the central stretch between the knots is the
// spline at five points of each span, as on ordinary chords (within the same tolerance, plus what the
// far positions round to). Taking the first two crossings as the knots instead, as a first version
// did, puts a corner piece's stretch under the central Hermite interpolant on such chords: the test
// fails with it (150 points off, by up to 0.12).
TEST(Ray, ChordKnotsIgnoreCrossingsRoundingAddsNearTheEnds) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), dir(-1.0f, 1.0f);
  constexpr double kValueTol = 2e-3;  // positions 2 000 units out round to 1e-4 index units
  int moreThanTwo = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    // Even cell (the central piece's edges on face z = c.z are the anti-diagonal x + y = 1 there).
    const glm::ivec3 cell(2 * int(u01(rng) * 50), 2 * int(u01(rng) * 50), 2 * int(u01(rng) * 50));
    const float a = 0.05f + 0.9f * u01(rng), off = 2e-5f * (u01(rng) - 0.5f);
    const glm::vec3 entry = glm::vec3(cell) + glm::vec3(a, 1.0f - a + off, 0.0f);
    const glm::vec3 d = glm::normalize(glm::vec3(dir(rng), dir(rng), 0.05f + u01(rng)));
    const glm::vec3 o = entry - (500.0f + 1500.0f * u01(rng)) * d;
    const CellChord chord = cellChord(cell, o, d);
    const float t0 = chord.ta, t1 = chord.tb;
    if (!(t1 - t0 > 1e-2f)) continue;
    const glm::vec4 s = fcc_cell_splits(cell, o, d, t0, t1);
    moreThanTwo += s.z < t1;
    const glm::vec2 knots = fcc_chord_knots(s, t0, t1);
    const FccSegment first = pieceSegmentOf(chord, t0, knots.x);
    const FccSegment last = knots.y < t1 ? pieceSegmentOf(chord, knots.y, t1) : first;
    const glm::vec4 spans[3] = {first.b, knots.y < t1 ? fcc_central_bernstein(first, last, knots.x, knots.y) : first.b,
                                last.b};
    const float ends[4] = {t0, knots.x, knots.y, t1};
    for (int span = 0; span < 3; ++span) {
      if (!(ends[span + 1] - ends[span] > 1e-3f)) continue;
      for (double u : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        const glm::vec3 x = o + float(ends[span] + u * (ends[span + 1] - ends[span])) * d;
        const double expected = evaluate(glm::clamp(x, glm::vec3(cell), glm::vec3(cell + 1)), hashedCoefficient);
        ASSERT_NEAR(bernstein3(glm::dvec4(spans[span]), u), expected, kValueTol)
            << "trial " << trial << " span " << span << " u " << u << " t0 " << t0 << " splits " << s.x << " " << s.y
            << " " << s.z << " " << s.w << " t1 " << t1;
      }
    }
  }
  std::printf("chords with more than two crossings: %d\n", moreThanTwo);
  EXPECT_GT(moreThanTwo, 20) << "the test no longer makes the chords it is about";
}

}  // namespace
}  // namespace fcc::spline
