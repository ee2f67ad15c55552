// CcTrilinear.h — trilinear interpolation on the Cartesian (CC) lattice, in the three dialects of
// Dialect.h. Sites are every integer point of the lattice's index space; the pieces are the unit cells
// [c, c + 1]^3; the stencil is the cell's 8 corners; no prefilter (it interpolates).
//
// Along a ray inside one cell the interpolant is a product of three affine functions of the ray
// parameter: a cubic, whose Bernstein coefficients are the trilinear blossom at the segment's ends
// (cc_trilinear_segment_bernstein), so hits are exact (FccRay.h's cubic root). The same multi-affine
// blossom serves every reconstruction that is trilinear in some cell coordinates (BCC's sheared
// trilinear and bilinear-plus-spatial schemes).
#ifndef FCC_CC_TRILINEAR_H
#define FCC_CC_TRILINEAR_H

#include "Dialect.h"
#include "ReconCommon.h"

FCC_NAMESPACE_BEGIN

// Corner values of one cell, index i = x + 2 y + 4 z for the corner cell + (x, y, z).
FCC_STRUCT_BEGIN(FccCorners8)
  float v[8];
FCC_STRUCT_END(FccCorners8)

FCC_FUNC FCC_IVEC3 cc_trilinear_cell(FCC_VEC3 xyz) { return FCC_IVEC3_FROM_VEC3(FCC_FLOOR3(xyz)); }

FCC_FUNC FCC_IVEC3 cc_trilinear_stencil_site(FCC_IVEC3 cell, int i) {
  return cell + FCC_MAKE_IVEC3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
}

// The multi-affine interpolant of the corners at local coordinates f (f in [0, 1]^3 inside the cell;
// outside, the same polynomial continued).
FCC_FUNC float fcc_multiaffine(FccCorners8 c, FCC_VEC3 f) {
  float x00 = c.v[0] + f.x * (c.v[1] - c.v[0]);
  float x10 = c.v[2] + f.x * (c.v[3] - c.v[2]);
  float x01 = c.v[4] + f.x * (c.v[5] - c.v[4]);
  float x11 = c.v[6] + f.x * (c.v[7] - c.v[6]);
  float y0 = x00 + f.y * (x10 - x00);
  float y1 = x01 + f.y * (x11 - x01);
  return y0 + f.z * (y1 - y0);
}

// Its gradient with respect to f.
FCC_FUNC FCC_VEC3 fcc_multiaffine_gradient(FccCorners8 c, FCC_VEC3 f) {
  float gx = 0.0f, gy = 0.0f, gz = 0.0f;
  for (int i = 0; i < 8; ++i) {
    float wx = (i & 1) != 0 ? f.x : 1.0f - f.x;
    float wy = (i & 2) != 0 ? f.y : 1.0f - f.y;
    float wz = (i & 4) != 0 ? f.z : 1.0f - f.z;
    float sx = (i & 1) != 0 ? 1.0f : -1.0f;
    float sy = (i & 2) != 0 ? 1.0f : -1.0f;
    float sz = (i & 4) != 0 ? 1.0f : -1.0f;
    gx += c.v[i] * sx * wy * wz;
    gy += c.v[i] * wx * sy * wz;
    gz += c.v[i] * wx * wy * sz;
  }
  return FCC_MAKE_VEC3(gx, gy, gz);
}

// Bernstein coefficients on u in [0, 1] of the multi-affine interpolant minus iso along the segment
// from local coordinates fa to fb: its blossom, B(a,a,a), B(a,a,b), B(a,b,b), B(b,b,b), where each
// middle one is the mean over which coordinate takes the other end.
FCC_FUNC FCC_VEC4 fcc_multiaffine_segment_bernstein(FccCorners8 c, FCC_VEC3 fa, FCC_VEC3 fb, float iso) {
  float b1 = fcc_multiaffine(c, FCC_MAKE_VEC3(fb.x, fa.y, fa.z)) + fcc_multiaffine(c, FCC_MAKE_VEC3(fa.x, fb.y, fa.z)) +
             fcc_multiaffine(c, FCC_MAKE_VEC3(fa.x, fa.y, fb.z));
  float b2 = fcc_multiaffine(c, FCC_MAKE_VEC3(fa.x, fb.y, fb.z)) + fcc_multiaffine(c, FCC_MAKE_VEC3(fb.x, fa.y, fb.z)) +
             fcc_multiaffine(c, FCC_MAKE_VEC3(fb.x, fb.y, fa.z));
  return FCC_MAKE_VEC4(fcc_multiaffine(c, fa) - iso, b1 * (1.0f / 3.0f) - iso, b2 * (1.0f / 3.0f) - iso,
                       fcc_multiaffine(c, fb) - iso);
}

// Bounds of the interpolant on its cell: it is a convex combination of the corners.
FCC_FUNC FccRange fcc_corners_range(FccCorners8 c) {
  FccRange r;
  r.lo = c.v[0];
  r.hi = c.v[0];
  for (int i = 1; i < 8; ++i) {
    r.lo = min(r.lo, c.v[i]);
    r.hi = max(r.hi, c.v[i]);
  }
  return r;
}

FCC_FUNC FccValueGradient cc_trilinear_value_gradient(FccCorners8 c, FCC_IVEC3 cell, FCC_VEC3 xyz) {
  FCC_VEC3 f = xyz - FCC_VEC3_FROM_IVEC3(cell);
  FccValueGradient r;
  r.value = fcc_multiaffine(c, f);
  r.gradient = fcc_multiaffine_gradient(c, f);
  return r;
}

FCC_NAMESPACE_END

#endif  // FCC_CC_TRILINEAR_H
