// CcTricubic.h — the tricubic B-spline on the Cartesian (CC) lattice, in the three dialects of
// Dialect.h. The pieces are the unit cells [c, c + 1]^3; the stencil is the 4^3 coefficients at
// c - 1 .. c + 2. The coefficients are the samples themselves (`tricubic-bspline`: an approximating,
// smoothing C2 spline that reproduces linear functions) or the samples through the interpolating
// prefilter (`tricubic`: passes through the samples, reproduces cubics; the prefilter is
// sparse/CubicBSpline.h's recursive filter, run by the caller).
//
// Along a ray inside one cell the spline is a polynomial of degree 9 in the ray parameter. Its
// Bernstein coefficients come from the cell's Bezier form: each axis' cubic restricted to the segment
// (a blossom per axis), then the tensor product raised to one variable (degree 3+3+3). Its first root
// is found by subdivision with the convex hull (ReconCommon.h), never with a fixed step; the cell's
// bounds are the min/max of its 64 Bezier coefficients.
#ifndef FCC_CC_TRICUBIC_H
#define FCC_CC_TRICUBIC_H

#include "Dialect.h"
#include "ReconCommon.h"

FCC_NAMESPACE_BEGIN

// 64 values of one cell, index a + 4 b + 16 c: B-spline coefficients at cell - 1 + (a, b, c), or the
// cell's Bezier coefficients b_abc.
FCC_STRUCT_BEGIN(FccCoeffs64)
  float v[64];
FCC_STRUCT_END(FccCoeffs64)

FCC_FUNC FCC_IVEC3 cc_tricubic_cell(FCC_VEC3 xyz) { return FCC_IVEC3_FROM_VEC3(FCC_FLOOR3(xyz)); }

FCC_FUNC FCC_IVEC3 cc_tricubic_stencil_site(FCC_IVEC3 cell, int i) {
  return cell + FCC_MAKE_IVEC3((i & 3) - 1, ((i >> 2) & 3) - 1, (i >> 4) - 1);
}

// Uniform cubic B-spline weights of the coefficients at floor(x) - 1 .. floor(x) + 2, t = x - floor(x),
// and their derivatives.
FCC_FUNC FCC_VEC4 cc_bspline_weights(float t) {
  float s = 1.0f - t;
  return FCC_MAKE_VEC4(s * s * s, (3.0f * t * t * t - 6.0f * t * t + 4.0f), (-3.0f * t * t * t + 3.0f * t * t + 3.0f * t + 1.0f),
                       t * t * t) *
         (1.0f / 6.0f);
}
FCC_FUNC FCC_VEC4 cc_bspline_derivative_weights(float t) {
  float s = 1.0f - t;
  return FCC_MAKE_VEC4(-s * s, 3.0f * t * t - 4.0f * t, -3.0f * t * t + 2.0f * t + 1.0f, t * t) * 0.5f;
}

FCC_FUNC FccValueGradient cc_tricubic_value_gradient(FccCoeffs64 c, FCC_IVEC3 cell, FCC_VEC3 xyz) {
  FCC_VEC3 f = xyz - FCC_VEC3_FROM_IVEC3(cell);
  FCC_VEC4 wx = cc_bspline_weights(f.x), wy = cc_bspline_weights(f.y), wz = cc_bspline_weights(f.z);
  FCC_VEC4 dx = cc_bspline_derivative_weights(f.x), dy = cc_bspline_derivative_weights(f.y),
           dz = cc_bspline_derivative_weights(f.z);
  float value = 0.0f, gx = 0.0f, gy = 0.0f, gz = 0.0f;
  for (int k = 0; k < 4; ++k) {
    float wzk = k == 0 ? wz.x : (k == 1 ? wz.y : (k == 2 ? wz.z : wz.w));
    float dzk = k == 0 ? dz.x : (k == 1 ? dz.y : (k == 2 ? dz.z : dz.w));
    for (int j = 0; j < 4; ++j) {
      float wyj = j == 0 ? wy.x : (j == 1 ? wy.y : (j == 2 ? wy.z : wy.w));
      float dyj = j == 0 ? dy.x : (j == 1 ? dy.y : (j == 2 ? dy.z : dy.w));
      int row = 4 * j + 16 * k;
      float rowValue = wx.x * c.v[row] + wx.y * c.v[row + 1] + wx.z * c.v[row + 2] + wx.w * c.v[row + 3];
      float rowDx = dx.x * c.v[row] + dx.y * c.v[row + 1] + dx.z * c.v[row + 2] + dx.w * c.v[row + 3];
      value += wzk * wyj * rowValue;
      gx += wzk * wyj * rowDx;
      gy += wzk * dyj * rowValue;
      gz += dzk * wyj * rowValue;
    }
  }
  FccValueGradient r;
  r.value = value;
  r.gradient = FCC_MAKE_VEC3(gx, gy, gz);
  return r;
}

// One axis of the cell's B-spline segment in Bezier form: (c0 + 4c1 + c2, 4c1 + 2c2, 2c1 + 4c2, c1 + 4c2 + c3) / 6.
FCC_FUNC FCC_VEC4 cc_bspline_to_bezier(FCC_VEC4 c) {
  return FCC_MAKE_VEC4(c.x + 4.0f * c.y + c.z, 4.0f * c.y + 2.0f * c.z, 2.0f * c.y + 4.0f * c.z, c.y + 4.0f * c.z + c.w) *
         (1.0f / 6.0f);
}

// The blossom of the cubic with Bezier coefficients p at (t1, t2, t3).
FCC_FUNC float fcc_blossom3(FCC_VEC4 p, float t1, float t2, float t3) {
  float a0 = p.x + t1 * (p.y - p.x), a1 = p.y + t1 * (p.z - p.y), a2 = p.z + t1 * (p.w - p.z);
  float b0 = a0 + t2 * (a1 - a0), b1 = a1 + t2 * (a2 - a1);
  return b0 + t3 * (b1 - b0);
}

// Bezier coefficients on u in [0, 1] of the cubic p along t = ta + u (tb - ta).
FCC_FUNC FCC_VEC4 fcc_restrict_cubic(FCC_VEC4 p, float ta, float tb) {
  return FCC_MAKE_VEC4(fcc_blossom3(p, ta, ta, ta), fcc_blossom3(p, ta, ta, tb), fcc_blossom3(p, ta, tb, tb),
                       fcc_blossom3(p, tb, tb, tb));
}

// Applies one axis' map of four values (B-spline to Bezier when ta < 0, else the restriction to
// [ta, tb]) to every line of the 4^3 block along `axis` (stride 1, 4 or 16).
FCC_FUNC FccCoeffs64 cc_tricubic_axis_map(FccCoeffs64 c, int axis, float ta, float tb, int toBezier) {
  int stride = axis == 0 ? 1 : (axis == 1 ? 4 : 16);
  FccCoeffs64 r;
  for (int line = 0; line < 16; ++line) {
    int lo = line & 3, hi = line >> 2;
    // The line's first index: the two other axes' digits at their places.
    int base = axis == 0 ? 4 * lo + 16 * hi : (axis == 1 ? lo + 16 * hi : lo + 4 * hi);
    FCC_VEC4 v = FCC_MAKE_VEC4(c.v[base], c.v[base + stride], c.v[base + 2 * stride], c.v[base + 3 * stride]);
    FCC_VEC4 m = toBezier != 0 ? cc_bspline_to_bezier(v) : fcc_restrict_cubic(v, ta, tb);
    r.v[base] = m.x;
    r.v[base + stride] = m.y;
    r.v[base + 2 * stride] = m.z;
    r.v[base + 3 * stride] = m.w;
  }
  return r;
}

// The cell's 64 Bezier coefficients from its 64 B-spline coefficients.
FCC_FUNC FccCoeffs64 cc_tricubic_bezier(FccCoeffs64 c) {
  FccCoeffs64 r = cc_tricubic_axis_map(c, 0, 0.0f, 0.0f, 1);
  r = cc_tricubic_axis_map(r, 1, 0.0f, 0.0f, 1);
  return cc_tricubic_axis_map(r, 2, 0.0f, 0.0f, 1);
}

// Bounds of the spline on its cell (convex hull of the Bezier coefficients).
FCC_FUNC FccRange cc_tricubic_range(FccCoeffs64 bezier) {
  FccRange r;
  r.lo = bezier.v[0];
  r.hi = bezier.v[0];
  for (int i = 1; i < 64; ++i) {
    r.lo = min(r.lo, bezier.v[i]);
    r.hi = max(r.hi, bezier.v[i]);
  }
  return r;
}

// Bernstein coefficients (degree 9) on u in [0, 1] of the spline minus iso along the segment from
// local coordinates fa to fb of the cell whose Bezier coefficients are `bezier`.
FCC_FUNC FccBernstein9 cc_tricubic_segment_bernstein(FccCoeffs64 bezier, FCC_VEC3 fa, FCC_VEC3 fb, float iso) {
  FccCoeffs64 q = cc_tricubic_axis_map(bezier, 0, fa.x, fb.x, 0);
  q = cc_tricubic_axis_map(q, 1, fa.y, fb.y, 0);
  q = cc_tricubic_axis_map(q, 2, fa.z, fb.z, 0);
  // B3_i B3_j B3_k = C(3,i) C(3,j) C(3,k) / C(9, i+j+k) B9_{i+j+k}.
  FccBernstein9 p;
  p.n = 9;
  for (int m = 0; m < 10; ++m) p.b[m] = 0.0f;
  for (int i = 0; i < 64; ++i) {
    int a = i & 3, b = (i >> 2) & 3, c = i >> 4;
    float w = (a == 0 || a == 3 ? 1.0f : 3.0f) * (b == 0 || b == 3 ? 1.0f : 3.0f) * (c == 0 || c == 3 ? 1.0f : 3.0f);
    p.b[a + b + c] += w * q.v[i];
  }
  for (int m = 0; m < 10; ++m) {
    float binom9 = (m == 0 || m == 9) ? 1.0f : ((m == 1 || m == 8) ? 9.0f : ((m == 2 || m == 7) ? 36.0f : ((m == 3 || m == 6) ? 84.0f : 126.0f)));
    p.b[m] = p.b[m] / binom9 - iso;
  }
  return p;
}

FCC_NAMESPACE_END

#endif  // FCC_CC_TRICUBIC_H
