// FccRay.h — exact ray/isosurface intersection for the FCC spline, in the three dialects of
// FccSpline.h (include that first). Along a ray segment inside one tetrahedral piece the spline is a
// cubic in the ray parameter; its first root is found exactly (to float precision) by splitting the
// segment at the cubic's critical points into monotone parts and bisecting the first part whose ends
// differ in sign. No fixed step: no thin feature is stepped over.
//
// Ray: xyz(t) = o + t * d in the lattice's index space. A unit cell [c, c+1]^3 is cut into its five
// pieces by four planes; fcc_cell_splits gives the parameters where the ray crosses them.
#ifndef FCC_RAY_H
#define FCC_RAY_H

#if defined(FCC_CPP)
namespace fcc {
namespace spline {
#endif

// Value of the Bernstein cubic with coefficients b on [0, 1] at u.
FCC_FUNC float fcc_bernstein3(FCC_VEC4 b, float u) {
  float v = 1.0f - u;
  return v * v * (v * b.x + 3.0f * u * b.y) + u * u * (3.0f * v * b.z + u * b.w);
}

// The first u in [0, 1] where the cubic with Bernstein coefficients b is zero, or -1 if it has none.
// Exact up to float rounding: the cubic is monotone between its critical points, so the first
// monotone interval whose ends differ in sign holds the first root, found by bisection.
FCC_FUNC float fcc_first_root_bernstein3(FCC_VEC4 b) {
  if (min(min(b.x, b.y), min(b.z, b.w)) > 0.0f || max(max(b.x, b.y), max(b.z, b.w)) < 0.0f) return -1.0f;
  // Derivative (over 3) in power form A u^2 + B u + C.
  float d0 = b.y - b.x, d1 = b.z - b.y, d2 = b.w - b.z;
  float A = d0 - 2.0f * d1 + d2, B = 2.0f * (d1 - d0), C = d0;
  float r1 = 2.0f, r2 = 2.0f;  // critical points in (0, 1); 2 = none
  float scale = max(FCC_ABS(A), max(FCC_ABS(B), FCC_ABS(C)));
  if (FCC_ABS(A) > 1e-7f * scale) {
    float disc = B * B - 4.0f * A * C;
    if (disc >= 0.0f) {
      float q = -0.5f * (B + (B >= 0.0f ? 1.0f : -1.0f) * sqrt(disc));
      r1 = q / A;
      r2 = q != 0.0f ? C / q : 2.0f;
    }
  } else if (B != 0.0f) {
    r1 = -C / B;
  }
  if (!(r1 > 0.0f && r1 < 1.0f)) r1 = 2.0f;
  if (!(r2 > 0.0f && r2 < 1.0f)) r2 = 2.0f;
  float k1 = min(r1, r2), k2 = max(r1, r2);
  FCC_VEC4 knots = FCC_MAKE_VEC4(0.0f, min(k1, 1.0f), min(k2, 1.0f), 1.0f);
  float ua = 0.0f, ga = b.x;
  for (int i = 1; i < 4; ++i) {
    float ub = i == 1 ? knots.y : (i == 2 ? knots.z : knots.w);
    if (ub <= ua) continue;
    float gb = fcc_bernstein3(b, ub);
    if (ga == 0.0f) return ua;
    if ((ga < 0.0f) != (gb < 0.0f) || gb == 0.0f) {
      float lo = ua, hi = ub;
      bool loNegative = ga < 0.0f;
      for (int it = 0; it < 26; ++it) {
        float mid = 0.5f * (lo + hi);
        float gm = fcc_bernstein3(b, mid);
        if (gm == 0.0f) return mid;
        if ((gm < 0.0f) == loNegative) lo = mid;
        else hi = mid;
      }
      return 0.5f * (lo + hi);
    }
    ua = ub;
    ga = gb;
  }
  return -1.0f;
}

// The first root on a piece sub-segment that continues the previous one along the ray, whose end
// value was negative (prevSign -1), non-negative (+1) or is unknown (0): a sign change at the join is
// a root at u = 0. Each piece evaluates the shared point with its own rounding, so without this a root
// within rounding of a split (a few 1e-4 voxels) could lie in neither sub-segment.
FCC_FUNC float fcc_first_root_after(FCC_VEC4 b, int prevSign) {
  if (prevSign != 0 && (b.x < 0.0f ? -1 : 1) != prevSign) return 0.0f;
  return fcc_first_root_bernstein3(b);
}

// Bernstein coefficients on u in [0, 1] of s(o + (s0 + u (s1 - s0)) d) - iso, where the segment lies
// in the piece `frame` whose scaled BB-coefficients are `cubic`. They are the cubic's blossom at the
// segment's ends a and b: B(a,a,a), B(a,a,b), B(a,b,b), B(b,b,b), one de Casteljau step per argument
// (144 multiplications, against 240 for values at four points, and no conversion from values). The
// spline is a polynomial on the piece, so ends a rounding past its faces are harmless.
FCC_FUNC FCC_VEC4 fcc_segment_bernstein(FccCubic cubic, FccFrame frame, FCC_VEC3 o, FCC_VEC3 d, float s0,
                                        float s1, float iso) {
  FCC_VEC3 axis = FCC_VEC3_FROM_IVEC3(frame.axis);
  FCC_VEC3 qa = axis * (o + s0 * d - FCC_VEC3_FROM_IVEC3(frame.origin));
  FCC_VEC3 qb = qa + axis * d * (s1 - s0);
  FCC_VEC4 la = fcc_barycentric(qa, frame.type), lb = fcc_barycentric(qb, frame.type);
  FccQuadratic ca = fcc_decasteljau_step3(cubic, la), cb = fcc_decasteljau_step3(cubic, lb);
  FCC_VEC4 caa = fcc_decasteljau_step2(ca, la), cab = fcc_decasteljau_step2(ca, lb), cbb = fcc_decasteljau_step2(cb, lb);
  float k = 1.0f / FCC_CUBIC_DENOM;
  return FCC_MAKE_VEC4((la.x * caa.x + la.y * caa.y + la.z * caa.z + la.w * caa.w) * k - iso,
                       (lb.x * caa.x + lb.y * caa.y + lb.z * caa.z + lb.w * caa.w) * k - iso,
                       (lb.x * cab.x + lb.y * cab.y + lb.z * cab.z + lb.w * cab.w) * k - iso,
                       (lb.x * cbb.x + lb.y * cbb.y + lb.z * cbb.z + lb.w * cbb.w) * k - iso);
}

// The parameters in (ta, tb) where the ray crosses the four planes that cut the unit cell at integer
// corner `cell` into its pieces, sorted; entries past the last crossing are tb.
FCC_FUNC FCC_VEC4 fcc_cell_splits(FCC_IVEC3 cell, FCC_VEC3 o, FCC_VEC3 d, float ta, float tb) {
  // Local coordinates p in the cell; an odd cell is the point reflection of an even one (p -> 1 - p).
  FCC_VEC3 p = o - FCC_VEC3_FROM_IVEC3(cell);
  FCC_VEC3 dir = d;
  if (((cell.x + cell.y + cell.z) & 1) != 0) {
    p = FCC_MAKE_VEC3(1.0f, 1.0f, 1.0f) - p;
    dir = -d;
  }
  // Planes n . p = 1 with n = (1,1,1), (1,1,-1), (1,-1,1), (-1,1,1).
  FCC_VEC4 np = FCC_MAKE_VEC4(p.x + p.y + p.z, p.x + p.y - p.z, p.x - p.y + p.z, -p.x + p.y + p.z);
  FCC_VEC4 nd = FCC_MAKE_VEC4(dir.x + dir.y + dir.z, dir.x + dir.y - dir.z, dir.x - dir.y + dir.z,
                              -dir.x + dir.y + dir.z);
  FCC_VEC4 s = FCC_MAKE_VEC4(tb, tb, tb, tb);
  float t;
  t = nd.x != 0.0f ? (1.0f - np.x) / nd.x : tb;
  s.x = (t > ta && t < tb) ? t : tb;
  t = nd.y != 0.0f ? (1.0f - np.y) / nd.y : tb;
  s.y = (t > ta && t < tb) ? t : tb;
  t = nd.z != 0.0f ? (1.0f - np.z) / nd.z : tb;
  s.z = (t > ta && t < tb) ? t : tb;
  t = nd.w != 0.0f ? (1.0f - np.w) / nd.w : tb;
  s.w = (t > ta && t < tb) ? t : tb;
  // Sorting network for four values.
  float lo, hi;
  lo = min(s.x, s.y); hi = max(s.x, s.y); s.x = lo; s.y = hi;
  lo = min(s.z, s.w); hi = max(s.z, s.w); s.z = lo; s.w = hi;
  lo = min(s.x, s.z); hi = max(s.x, s.z); s.x = lo; s.z = hi;
  lo = min(s.y, s.w); hi = max(s.y, s.w); s.y = lo; s.w = hi;
  lo = min(s.y, s.z); hi = max(s.y, s.z); s.y = lo; s.z = hi;
  return s;
}

#if defined(FCC_CPP)
}  // namespace spline
}  // namespace fcc
#endif

#endif  // FCC_RAY_H
