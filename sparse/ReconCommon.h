// ReconCommon.h — what every reconstruction header shares, in the three dialects of Dialect.h: the
// value/gradient and interval types, vector helpers, and the first root of a polynomial in Bernstein
// form along a ray segment (cubic: by monotone pieces; any degree up to 9: by subdivision with the
// convex hull). No fixed step anywhere: a root is found or excluded by the polynomial's coefficients.
#ifndef FCC_RECON_COMMON_H
#define FCC_RECON_COMMON_H

#include "Dialect.h"

FCC_NAMESPACE_BEGIN

// A value interval [lo, hi].
FCC_STRUCT_BEGIN(FccRange)
  float lo;
  float hi;
FCC_STRUCT_END(FccRange)

FCC_STRUCT_BEGIN(FccValueGradient)
  float value;
  FCC_VEC3 gradient;  // d/dxyz, in the lattice's index space
FCC_STRUCT_END(FccValueGradient)

// Component i (0, 1, 2) of a vector: OpenCL C has no variable component index.
FCC_FUNC float fcc_component(FCC_VEC3 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }
FCC_FUNC int fcc_icomponent(FCC_IVEC3 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : v.z); }
FCC_FUNC FCC_IVEC3 fcc_unit_axis(int i) { return FCC_MAKE_IVEC3(i == 0 ? 1 : 0, i == 1 ? 1 : 0, i == 2 ? 1 : 0); }

// A lattice rotated so that axis `n` comes last: (a, b, n) = the other two axes in cyclic order, then n.
// The plane-stack reconstructions of the BCC lattice are written for planes normal to z and use these.
FCC_FUNC FCC_VEC3 fcc_to_stack(FCC_VEC3 v, int n) {
  if (n == 0) return FCC_MAKE_VEC3(v.y, v.z, v.x);
  if (n == 1) return FCC_MAKE_VEC3(v.z, v.x, v.y);
  return v;
}
FCC_FUNC FCC_VEC3 fcc_from_stack(FCC_VEC3 v, int n) {
  if (n == 0) return FCC_MAKE_VEC3(v.z, v.x, v.y);
  if (n == 1) return FCC_MAKE_VEC3(v.y, v.z, v.x);
  return v;
}
FCC_FUNC FCC_IVEC3 fcc_ifrom_stack(FCC_IVEC3 v, int n) {
  if (n == 0) return FCC_MAKE_IVEC3(v.z, v.x, v.y);
  if (n == 1) return FCC_MAKE_IVEC3(v.y, v.z, v.x);
  return v;
}

// The parameters in (ta, tb) where a ray crosses the planes that cut one cell into a reconstruction's
// pieces, sorted ascending (at most FCC_MAX_SPLITS: the type-6 spline's cell has 9 planes).
#define FCC_MAX_SPLITS 12
FCC_STRUCT_BEGIN(FccSplits)
  float t[FCC_MAX_SPLITS];
  int n;
FCC_STRUCT_END(FccSplits)

FCC_FUNC FccSplits fcc_splits_none() {
  FccSplits s;
  s.n = 0;
  for (int i = 0; i < FCC_MAX_SPLITS; ++i) s.t[i] = 0.0f;
  return s;
}

// s with t inserted in order if it lies strictly inside (ta, tb) and there is room.
FCC_FUNC FccSplits fcc_splits_with(FccSplits s, float t, float ta, float tb) {
  if (!(t > ta && t < tb) || s.n >= FCC_MAX_SPLITS) return s;
  // Its place: after every entry not above it. Entries after it move up one, the index counted up
  // (Mesa's GLSL compiler mishandled a loop counting down: see fcc_bernstein9_restrict).
  int at = 0;
  for (int i = 0; i < s.n; ++i)
    if (s.t[i] <= t) at = i + 1;
  for (int k = 0; k < s.n - at; ++k) {
    int i = s.n - k;
    s.t[i] = s.t[i - 1];
  }
  s.t[at] = t;
  s.n = s.n + 1;
  return s;
}

// s with the crossing of the ray o + t d with the plane dot(normal, p) = offset.
FCC_FUNC FccSplits fcc_splits_with_plane(FccSplits s, FCC_VEC3 normal, float offset, FCC_VEC3 o, FCC_VEC3 d, float ta,
                                         float tb) {
  float nd = normal.x * d.x + normal.y * d.y + normal.z * d.z;
  if (nd == 0.0f) return s;
  return fcc_splits_with(s, (offset - (normal.x * o.x + normal.y * o.y + normal.z * o.z)) / nd, ta, tb);
}

// Value of the Bernstein cubic with coefficients b on [0, 1] at u.
FCC_FUNC float fcc_bernstein3(FCC_VEC4 b, float u) {
  float v = 1.0f - u;
  return v * v * (v * b.x + 3.0f * u * b.y) + u * u * (3.0f * v * b.z + u * b.w);
}

// The mean of the Bernstein cubic b over [um - w / 2, um + w / 2]: its value at the midpoint plus its
// second derivative there times w^2 / 24. Exact for a cubic: about um its odd Taylor terms average to
// zero and the third derivative is constant (docs/DVR.md, "The value a sub-step takes").
FCC_FUNC float fcc_bernstein3_mean(FCC_VEC4 b, float um, float w) {
  float d0 = b.x - 2.0f * b.y + b.z, d1 = b.y - 2.0f * b.z + b.w;
  return fcc_bernstein3(b, um) + 0.25f * w * w * ((1.0f - um) * d0 + um * d1);
}

// The primitive of the Bernstein cubic b on [0, 1] that is 0 at 0, in power form for Horner's rule:
// P(u) = u (p.x + u (p.y + u (p.z + u p.w))) (fcc_primitive3_at); P(1) is the sum of b over 4.
FCC_FUNC FCC_VEC4 fcc_bernstein3_primitive(FCC_VEC4 b) {
  return FCC_MAKE_VEC4(b.x, 1.5f * (b.y - b.x), b.x - 2.0f * b.y + b.z, 0.25f * (b.w - 3.0f * b.z + 3.0f * b.y - b.x));
}
FCC_FUNC float fcc_primitive3_at(FCC_VEC4 p, float u) { return u * (p.x + u * (p.y + u * (p.z + u * p.w))); }

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

// Cubic Bernstein coefficients on [0, 1] of the line through (0, v0) and (1, v1).
FCC_FUNC FCC_VEC4 fcc_linear_as_bernstein3(float v0, float v1) {
  return FCC_MAKE_VEC4(v0, (2.0f * v0 + v1) * (1.0f / 3.0f), (v0 + 2.0f * v1) * (1.0f / 3.0f), v1);
}

// A polynomial of degree <= 9 in Bernstein form on [0, 1] (degree in `n`, coefficients b[0..n]).
FCC_STRUCT_BEGIN(FccBernstein9)
  float b[10];
  int n;
FCC_STRUCT_END(FccBernstein9)

// The same polynomial on [lo, hi] (a sub-interval of [0, 1]) in Bernstein form on that interval: one
// de Casteljau split at hi keeps the left part, a second at lo / hi keeps its right part.
FCC_FUNC FccBernstein9 fcc_bernstein9_restrict(FccBernstein9 p, float lo, float hi) {
  FccBernstein9 r = p;
  int n = p.n;
  if (hi < 1.0f) {
    // Left part of a split at hi: r_k = the k-th level's first coefficient. The inner loop runs down
    // through an index counted up: Mesa's GLSL compiler (llvmpipe) skipped this loop written with a
    // decreasing induction variable (tests/sparse/DialectComparison.h, the segment roots, found it).
    for (int level = 1; level <= n; ++level)
      for (int k = 0; k <= n - level; ++k) {
        int i = n - k;
        r.b[i] = r.b[i - 1] + hi * (r.b[i] - r.b[i - 1]);
      }
  }
  float u = hi > 0.0f ? lo / hi : 0.0f;
  if (u > 0.0f) {
    // Right part of a split at u: r_k = the (n - k)-th level's last coefficient.
    for (int level = 1; level <= n; ++level)
      for (int i = 0; i <= n - level; ++i) r.b[i] = r.b[i] + u * (r.b[i + 1] - r.b[i]);
  }
  return r;
}

FCC_FUNC float fcc_bernstein9_at(FccBernstein9 p, float u) {
  FccBernstein9 r = p;
  for (int level = 1; level <= p.n; ++level)
    for (int i = 0; i <= p.n - level; ++i) r.b[i] = r.b[i] + u * (r.b[i + 1] - r.b[i]);
  return r.b[0];
}

// The first u in [0, 1] where p is zero, or -1 if it has none. Depth-first subdivision, left half
// first: an interval whose coefficients all have one sign holds no root (convex hull); one whose
// coefficients change sign exactly once holds exactly one (variation diminishing, and the ends differ
// in sign), found by bisection on values; an interval shorter than 2^-20 that still cannot be decided
// (a double or tangent root) reports its start. Only interval ends are kept on the stack: each
// interval's coefficients are recomputed from p, so no error accumulates through the levels.
FCC_FUNC float fcc_first_root_bernstein9(FccBernstein9 p) {
  float stackLo[24];
  float stackHi[24];
  stackLo[0] = 0.0f;
  stackHi[0] = 1.0f;
  int top = 1;
  float result = -1.0f;
  while (top > 0 && result < 0.0f) {
    top = top - 1;
    float lo = stackLo[top], hi = stackHi[top];
    FccBernstein9 q = fcc_bernstein9_restrict(p, lo, hi);
    float mn = q.b[0], mx = q.b[0];
    int changes = 0;
    for (int i = 1; i <= q.n; ++i) {
      mn = min(mn, q.b[i]);
      mx = max(mx, q.b[i]);
      if ((q.b[i] < 0.0f) != (q.b[i - 1] < 0.0f)) changes = changes + 1;
    }
    if (!(mn > 0.0f || mx < 0.0f)) {
      if (q.b[0] == 0.0f) {
        result = lo;
      } else if (changes == 1 && (q.b[0] < 0.0f) != (q.b[q.n] < 0.0f)) {
        float a = 0.0f, c = 1.0f;
        bool aNegative = q.b[0] < 0.0f;
        float exact = -1.0f;
        for (int it = 0; it < 26 && exact < 0.0f; ++it) {
          float mid = 0.5f * (a + c);
          float g = fcc_bernstein9_at(q, mid);
          if (g == 0.0f) exact = mid;
          else if ((g < 0.0f) == aNegative) a = mid;
          else c = mid;
        }
        result = lo + (exact >= 0.0f ? exact : 0.5f * (a + c)) * (hi - lo);
      } else if (hi - lo < 9.5367e-7f || top + 2 > 24) {
        result = lo;
      } else {
        float mid = 0.5f * (lo + hi);
        stackLo[top] = mid;
        stackHi[top] = hi;
        stackLo[top + 1] = lo;
        stackHi[top + 1] = mid;
        top = top + 2;
      }
    }
  }
  return result;
}

FCC_NAMESPACE_END

#endif  // FCC_RECON_COMMON_H
