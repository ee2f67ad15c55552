// sparse/FccChord.h on the CPU against slow references: the face jump between the pieces on either
// side of a cube face (from their BB-forms), a cell chord's end pieces and knots (by locating points),
// and the Taylor form of a piece along a ray (its segment Bernstein form).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "sparse/Spline.h"

namespace fcc::spline {
namespace {

float hashedCoefficient(const glm::ivec3& ijk) {
  const uint32_t h = uint32_t(ijk.x * 73856093) ^ uint32_t(ijk.y * 19349663) ^ uint32_t(ijk.z * 83492791);
  return float(h % 2001u) / 1000.0f - 1.0f;
}

// The cubic of the piece holding `inPiece`, continued past its faces, at x (double accumulation of the
// float BB-form).
double pieceAt(const glm::vec3& inPiece, const glm::vec3& x) {
  const FccFrame frame = fcc_locate(inPiece);
  const FccCubic cubic = fcc_cubic(gatherSamples(frame, hashedCoefficient), frame.type);
  const glm::vec3 q = glm::vec3(frame.axis) * (x - glm::vec3(frame.origin));
  return double(fcc_decasteljau3(cubic, fcc_barycentric(q, frame.type))) / FCC_CUBIC_DENOM;
}

// The slow reference: lambda = -(1/6) Nabla_Y c(e + off_a), the forward difference of the coefficients
// along the four directions with a non-zero a-component, 16 terms.
double referenceLambda(const glm::ivec3& e, int axis) {
  const glm::ivec3 directions[6] = {{1, 1, 0}, {1, 0, 1}, {0, 1, 1}, {1, -1, 0}, {0, 1, -1}, {-1, 0, 1}};
  glm::ivec3 y[4];
  int n = 0;
  for (const glm::ivec3& xi : directions)
    if (xi[axis] != 0) y[n++] = xi;
  const glm::ivec3 offX(-1, 0, -1);
  const glm::ivec3 off = axis == 0 ? offX : (axis == 1 ? glm::ivec3(offX.z, offX.x, offX.y) : glm::ivec3(offX.y, offX.z, offX.x));
  double sum = 0.0;
  for (int subset = 0; subset < 16; ++subset) {
    glm::ivec3 site = e + off;
    int count = 0;
    for (int b = 0; b < 4; ++b)
      if ((subset >> b) & 1) {
        site += y[b];
        ++count;
      }
    sum += ((4 - count) % 2 == 0 ? 1.0 : -1.0) * hashedCoefficient(site);
  }
  return -sum / 6.0;
}

// fcc_face_jump_lambda from the corner piece at e on one side of the face (its stencil and the one
// site beyond).
float stencilLambda(const glm::vec3& inCornerPiece, int axis) {
  const FccFrame frame = fcc_locate(inCornerPiece);
  return fcc_face_jump_lambda(gatherSamples(frame, hashedCoefficient), axis,
                              hashedCoefficient(fcc_face_jump_beyond_site(frame, axis)));
}

// Across a cube face x_a = f the two pieces sharing a face triangle differ by lambda (x_a - f)^3, lambda
// the fourth difference at the triangle's FCC site: checked at points off the face on both sides, far
// from the triangle's edges (where a probe could land in another piece); and fcc_face_jump_lambda's
// form from either piece's stencil is that difference.
TEST(Chord, PiecesAcrossACubeFaceDifferByTheFaceJump) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::uniform_int_distribution<int> site(-6, 6);
  constexpr double kTol = 2e-5;
  int checked = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int axis = trial % 3, b1 = (axis + 1) % 3, b2 = (axis + 2) % 3;
    // A face triangle: the FCC site e on the face, and a point of the triangle around e toward one
    // of its four neighbours' sides (|y| + |z| <= 1 around e, one quadrant).
    glm::ivec3 e(site(rng), site(rng), site(rng));
    if ((e.x + e.y + e.z) & 1) e[b1] += 1;
    const float su = u01(rng) < 0.5f ? -1.0f : 1.0f, sv = u01(rng) < 0.5f ? -1.0f : 1.0f;
    float y = u01(rng), z = u01(rng);
    if (y + z > 0.9f || y < 0.05f || z < 0.05f) continue;  // inside the triangle, away from its edges
    glm::vec3 onFace(e);
    onFace[b1] += su * y;
    onFace[b2] += sv * z;
    glm::vec3 n(0.0f);
    n[axis] = 1.0f;
    const glm::vec3 plusSide = onFace + 0.01f * n, minusSide = onFace - 0.01f * n;
    const double lambda = referenceLambda(e, axis);
    // The stencil's form, from the corner piece at e on either side.
    ASSERT_EQ(fcc_locate(plusSide).origin, e);
    ASSERT_EQ(fcc_locate(minusSide).origin, e);
    EXPECT_NEAR(stencilLambda(plusSide, axis), lambda, 1e-5) << "axis " << axis << " (plus side)";
    EXPECT_NEAR(stencilLambda(minusSide, axis), lambda, 1e-5) << "axis " << axis << " (minus side)";
    for (float h : {0.5f, -0.7f}) {
      const glm::vec3 x = onFace + h * n + 0.1f * glm::vec3(0.3f, -0.2f, 0.5f) * (glm::vec3(1.0f) - n);
      const double jump = pieceAt(plusSide, x) - pieceAt(minusSide, x);
      ASSERT_NEAR(jump, lambda * h * h * h, kTol)
          << "axis " << axis << " e " << e.x << "," << e.y << "," << e.z << " point " << onFace.x << "," << onFace.y
          << "," << onFace.z << " h " << h;
    }
    ++checked;
  }
  EXPECT_GT(checked, 800);
}

struct Ray {
  glm::ivec3 cell;
  glm::vec3 o, d;
  float t0, t1;
};

// A random ray through a random cell near the origin and its chord there.
Ray randomRay(std::mt19937& rng) {
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), dir(-1.0f, 1.0f);
  Ray r;
  r.cell = glm::ivec3(int(u01(rng) * 6) - 3, int(u01(rng) * 6) - 3, int(u01(rng) * 6) - 3);
  r.d = glm::normalize(glm::vec3(dir(rng), dir(rng), dir(rng)));
  r.o = glm::vec3(r.cell) + glm::vec3(u01(rng), u01(rng), u01(rng)) - 5.0f * r.d;
  r.t0 = -1e30f;
  r.t1 = 1e30f;
  for (int a = 0; a < 3; ++a) {
    const float ta = (float(r.cell[a]) - r.o[a]) / r.d[a], tb = (float(r.cell[a] + 1) - r.o[a]) / r.d[a];
    r.t0 = std::max(r.t0, std::min(ta, tb));
    r.t1 = std::min(r.t1, std::max(ta, tb));
  }
  return r;
}

bool sameFrame(const FccFrame& a, const FccFrame& b) { return a.origin == b.origin && a.axis == b.axis && a.type == b.type; }

// A chord from face to face has corner pieces at both ends; fcc_locate finds entry's piece just after
// t0 and exit's just before t1, the central piece inside (ta, tb), and the knots agree with
// fcc_cell_splits' crossings (fcc_chord_knots).
TEST(Chord, EndPiecesAndKnotsAreThePiecesAlongTheChord) {
  std::mt19937 rng(23);
  constexpr float kKnotTol = 1e-4f;
  int central = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Ray r = randomRay(rng);
    const float len = r.t1 - r.t0;
    if (len < 1e-2f) continue;
    const FccCellChord chord = fcc_cell_chord(r.cell, r.o, r.d, r.t0, r.t1);
    ASSERT_EQ(chord.corners, 1) << "trial " << trial;
    ASSERT_LE(r.t0, chord.ta);
    ASSERT_LE(chord.ta, chord.tb);
    ASSERT_LE(chord.tb, r.t1);
    // fcc_chord_knots drops crossings within FCC_CHORD_END_GAP of an end (which fcc_cell_chord, locating
    // the end pieces, need not): compared where there are none.
    const glm::vec4 splits = fcc_cell_splits(r.cell, r.o, r.d, r.t0, r.t1);
    bool nearEnd = false;
    for (int k = 0; k < 4; ++k)
      nearEnd = nearEnd || (splits[k] < r.t1 && std::min(splits[k] - r.t0, r.t1 - splits[k]) < 2e-3f * len);
    if (!nearEnd) {
      const glm::vec2 knots = fcc_chord_knots(splits, r.t0, r.t1);
      EXPECT_NEAR(chord.ta, knots.x, kKnotTol * len) << "trial " << trial;
      EXPECT_NEAR(chord.tb, knots.y, kKnotTol * len) << "trial " << trial;
    }
    auto locateAt = [&](float t) {
      return fcc_locate(glm::clamp(r.o + t * r.d, glm::vec3(r.cell), glm::vec3(r.cell + 1)));
    };
    if (chord.ta - r.t0 > 1e-3f * len) {
      EXPECT_TRUE(sameFrame(locateAt(r.t0 + 0.5f * (chord.ta - r.t0)), chord.entry)) << "trial " << trial;
    }
    if (r.t1 - chord.tb > 1e-3f * len) {
      EXPECT_TRUE(sameFrame(locateAt(chord.tb + 0.5f * (r.t1 - chord.tb)), chord.exit)) << "trial " << trial;
    }
    if (chord.tb - chord.ta > 1e-3f * len) {
      EXPECT_EQ(locateAt(0.5f * (chord.ta + chord.tb)).type, 4) << "trial " << trial;
      ++central;
    }
  }
  EXPECT_GT(central, 500);
}

// A chord that starts inside the central piece has no corner piece at its start.
TEST(Chord, AStartInsideTheCentralPieceIsReported) {
  const glm::ivec3 cell(2, 0, 0);  // even
  const glm::vec3 o(2.5f, 0.5f, 0.5f), d(0.6f, 0.0f, 0.8f);
  EXPECT_EQ(fcc_cell_chord(cell, o, d, 0.0f, 0.5f / 0.8f).corners, 0);
}

// The Taylor form is the piece along the ray: its Bernstein form on a segment equals the segment's
// (fcc_segment_bernstein), its slope the piece's, and a shift keeps the polynomial.
TEST(Chord, TaylorFormIsThePieceAlongTheRay) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f), dir(-1.0f, 1.0f);
  constexpr float kTol = 2e-5f;
  for (int trial = 0; trial < 2000; ++trial) {
    const glm::vec3 p = glm::vec3(u01(rng), u01(rng), u01(rng)) * 4.0f;
    const FccFrame frame = fcc_locate(p);
    const glm::vec3 d = glm::normalize(glm::vec3(dir(rng), dir(rng), dir(rng)));
    const FccCubic cubic = fcc_cubic(gatherSamples(frame, hashedCoefficient), frame.type);
    const float ts = 0.02f, s0 = -0.05f, s1 = 0.07f;
    const glm::vec4 c = fcc_piece_taylor(cubic, frame, p, d, ts);
    const glm::vec4 expected = fcc_segment_bernstein(cubic, frame, p, d, s0, s1, 0.0f);
    const glm::vec4 b = fcc_taylor_bernstein(c, s0 - ts, s1 - ts);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(b[i], expected[i], kTol) << "trial " << trial << " i " << i;
    const FccSegment seg = fcc_segment_with_slopes(cubic, frame, p, d, s0, s1);
    EXPECT_NEAR(fcc_taylor_slope(c, s0 - ts), seg.slope0, 1e-4f) << "trial " << trial;
    EXPECT_NEAR(fcc_taylor_slope(c, s1 - ts), seg.slope1, 1e-4f) << "trial " << trial;
    const glm::vec4 moved = fcc_taylor_shift(c, s1 - ts);
    const glm::vec4 bMoved = fcc_taylor_bernstein(moved, s0 - s1, 0.0f);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(bMoved[i], expected[i], kTol) << "trial " << trial << " i " << i;
  }
}

}  // namespace
}  // namespace fcc::spline
