// BccShearedTrilinear.h — sheared trilinear interpolation on the BCC lattice (paper 002, section 3.4),
// in the three dialects of Dialect.h. BCC index space as in BccBarycentric.h.
//
// The BCC lattice is a sheared, scaled Cartesian lattice: with the planes of the stack normal to axis
// n (coordinates (a, b, n) after fcc_to_stack) and shear signs (sa, sb) in {-1, +1}, the map
// a'' = a - sa n, b'' = b - sb n takes its sites to the points with a'', b'' even and n integer (a site
// of plane n has a, b of n's parity, and n - sa n is even). Trilinear interpolation in the cells of that
// grid (2 x 2 x 1) is the paper's scheme: linear along the four short edges (a cell's corners in plane
// n + 1 are those of plane n moved by (sa, sb, 1)), then bilinear. C0, reproduces linear functions.
// The paper picks the stack most perpendicular to the view and shears towards the ray; a view
// direction d gives n = the axis of d's largest |component| and sa = sign(d_a d_n), sb = sign(d_b d_n)
// (bcc_sheared_params_for_view). Along a ray inside one cell it is cubic (multi-affine in the cell
// coordinates): exact hits by the trilinear blossom (CcTrilinear.h).
#ifndef FCC_BCC_SHEARED_TRILINEAR_H
#define FCC_BCC_SHEARED_TRILINEAR_H

#include "Dialect.h"
#include "ReconCommon.h"
#include "CcTrilinear.h"

FCC_NAMESPACE_BEGIN

// Stack axis in x (0, 1, 2), shear signs in y and z (+-1).
FCC_FUNC FCC_IVEC3 bcc_sheared_params_for_view(FCC_VEC3 d) {
  FCC_VEC3 ad = FCC_MAKE_VEC3(FCC_ABS(d.x), FCC_ABS(d.y), FCC_ABS(d.z));
  int n = ad.x >= ad.y ? (ad.x >= ad.z ? 0 : 2) : (ad.y >= ad.z ? 1 : 2);
  FCC_VEC3 ds = fcc_to_stack(d, n);
  return FCC_MAKE_IVEC3(n, ds.x * ds.z >= 0.0f ? 1 : -1, ds.y * ds.z >= 0.0f ? 1 : -1);
}

FCC_STRUCT_BEGIN(BccShearedFrame)
  FCC_IVEC3 cell;    // the cell's lowest corner in sheared stack coordinates (a'', b'' even)
  FCC_IVEC3 params;  // stack axis, shear signs
FCC_STRUCT_END(BccShearedFrame)

// Sheared stack coordinates of xyz.
FCC_FUNC FCC_VEC3 bcc_sheared_coords(FCC_VEC3 xyz, FCC_IVEC3 params) {
  FCC_VEC3 s = fcc_to_stack(xyz, params.x);
  return FCC_MAKE_VEC3(s.x - FCC_FLOAT(params.y) * s.z, s.y - FCC_FLOAT(params.z) * s.z, s.z);
}

FCC_FUNC BccShearedFrame bcc_sheared_locate(FCC_VEC3 xyz, FCC_IVEC3 params) {
  FCC_VEC3 h = bcc_sheared_coords(xyz, params);
  BccShearedFrame frame;
  frame.cell = FCC_IVEC3_FROM_VEC3(FCC_MAKE_VEC3(2.0f * floor(h.x * 0.5f), 2.0f * floor(h.y * 0.5f), floor(h.z)));
  frame.params = params;
  return frame;
}

// Corner i (x + 2y + 4z) of the cell, as a site in index space.
FCC_FUNC FCC_IVEC3 bcc_sheared_stencil_site(BccShearedFrame frame, int i) {
  int zn = frame.cell.z + ((i >> 2) & 1);
  FCC_IVEC3 stack = FCC_MAKE_IVEC3(frame.cell.x + 2 * (i & 1) + frame.params.y * zn,
                                   frame.cell.y + 2 * ((i >> 1) & 1) + frame.params.z * zn, zn);
  return fcc_ifrom_stack(stack, frame.params.x);
}

// Local cell coordinates of xyz in [0, 1]^3 inside the cell (the polynomial continues outside).
FCC_FUNC FCC_VEC3 bcc_sheared_local(BccShearedFrame frame, FCC_VEC3 xyz) {
  FCC_VEC3 h = bcc_sheared_coords(xyz, frame.params) - FCC_VEC3_FROM_IVEC3(frame.cell);
  return FCC_MAKE_VEC3(0.5f * h.x, 0.5f * h.y, h.z);
}

FCC_FUNC FccValueGradient bcc_sheared_value_gradient(FccCorners8 c, BccShearedFrame frame, FCC_VEC3 xyz) {
  FCC_VEC3 f = bcc_sheared_local(frame, xyz);
  FCC_VEC3 g = fcc_multiaffine_gradient(c, f);
  // Chain rule through f = ((a - sa n - ca) / 2, (b - sb n - cb) / 2, n - cn).
  FCC_VEC3 gStack = FCC_MAKE_VEC3(0.5f * g.x, 0.5f * g.y,
                                  g.z - 0.5f * FCC_FLOAT(frame.params.y) * g.x - 0.5f * FCC_FLOAT(frame.params.z) * g.y);
  FccValueGradient r;
  r.value = fcc_multiaffine(c, f);
  r.gradient = fcc_from_stack(gStack, frame.params.x);
  return r;
}

// Where the ray crosses the sheared cells' faces inside the unit cell `cell` of index space
// (a'' or b'' even: slanted planes; n integer: the unit cell's own faces), between ta and tb.
FCC_FUNC FccSplits bcc_sheared_cell_splits(FCC_IVEC3 cell, FCC_IVEC3 params, FCC_VEC3 o, FCC_VEC3 d, float ta,
                                           float tb) {
  FccSplits s = fcc_splits_none();
  FCC_VEC3 ha = bcc_sheared_coords(o + ta * d, params), hb = bcc_sheared_coords(o + tb * d, params);
  // The planes a'' = 2m and b'' = 2m in index space: normal = from_stack(1, 0, -sa) etc.
  FCC_VEC3 na = fcc_from_stack(FCC_MAKE_VEC3(1.0f, 0.0f, -FCC_FLOAT(params.y)), params.x);
  FCC_VEC3 nb = fcc_from_stack(FCC_MAKE_VEC3(0.0f, 1.0f, -FCC_FLOAT(params.z)), params.x);
  float lo = 2.0f * ceil(0.5f * min(ha.x, hb.x)), hi = max(ha.x, hb.x);
  for (int k = 0; k < 3 && lo + 2.0f * FCC_FLOAT(k) <= hi; ++k) s = fcc_splits_with_plane(s, na, lo + 2.0f * FCC_FLOAT(k), o, d, ta, tb);
  lo = 2.0f * ceil(0.5f * min(ha.y, hb.y));
  hi = max(ha.y, hb.y);
  for (int k = 0; k < 3 && lo + 2.0f * FCC_FLOAT(k) <= hi; ++k) s = fcc_splits_with_plane(s, nb, lo + 2.0f * FCC_FLOAT(k), o, d, ta, tb);
  return s;
}

FCC_NAMESPACE_END

#endif  // FCC_BCC_SHEARED_TRILINEAR_H
