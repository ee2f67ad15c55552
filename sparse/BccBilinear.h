// BccBilinear.h — the two plane-stack schemes of the BCC lattice (paper 002, sections 3.1 and 3.2), in
// the three dialects of Dialect.h. BCC index space as in BccBarycentric.h; the stack's planes are normal
// to axis n (coordinates (a, b, n) after fcc_to_stack): plane n holds the sites whose a and b have n's
// parity, a square grid of spacing 2, each plane shifted by (1, 1) from the last.
//
// - `bilinear`: bilinear interpolation in the nearest plane (n rounded). Discontinuous half-way between
//   planes: the paper samples only on the planes; elsewhere this is the scheme's value continued as a
//   step. Reproduces linear functions within a plane only.
// - `bilinear-spatial`: bilinear in the planes below and above, then linear between them (the paper's
//   equation (1), with its weights divided by the plane distance so they sum to one). C0, reproduces
//   linear functions; on each unit cell of index space it is multi-affine in (a, b, n), so along a ray
//   it is cubic: exact hits by the trilinear blossom of the cell's 8 corner values (CcTrilinear.h).
// Both take the stack most perpendicular to the view (bcc_sheared_params_for_view's axis).
#ifndef FCC_BCC_BILINEAR_H
#define FCC_BCC_BILINEAR_H

#include "Dialect.h"
#include "ReconCommon.h"
#include "CcTrilinear.h"

FCC_NAMESPACE_BEGIN

FCC_STRUCT_BEGIN(BccPlaneFrame)
  FCC_IVEC3 lower;  // plane n0: the lowest corner (a0, b0, n0) of its 2 x 2 square, stack coordinates
  FCC_IVEC3 upper;  // plane n0 + 1 likewise (bilinear-spatial only)
  int axis;
FCC_STRUCT_END(BccPlaneFrame)

// The square of plane n (integer) holding (a, b): its lowest corner.
FCC_FUNC FCC_IVEC3 bcc_plane_square(float a, float b, int n) {
  float p = FCC_FLOAT(n & 1);
  return FCC_MAKE_IVEC3(FCC_INT(p + 2.0f * floor(0.5f * (a - p))), FCC_INT(p + 2.0f * floor(0.5f * (b - p))), n);
}

// spatial != 0: bilinear-spatial (planes floor(n) and floor(n) + 1); 0: nearest-plane bilinear.
FCC_FUNC BccPlaneFrame bcc_plane_locate(FCC_VEC3 xyz, int axis, int spatial) {
  FCC_VEC3 s = fcc_to_stack(xyz, axis);
  int n0 = spatial != 0 ? FCC_INT(floor(s.z)) : FCC_INT(floor(s.z + 0.5f));
  BccPlaneFrame frame;
  frame.lower = bcc_plane_square(s.x, s.y, n0);
  frame.upper = bcc_plane_square(s.x, s.y, n0 + 1);
  frame.axis = axis;
  return frame;
}

// Site i: 0..3 the lower plane's square (x + 2y), 4..7 the upper plane's.
FCC_FUNC FCC_IVEC3 bcc_plane_stencil_site(BccPlaneFrame frame, int i) {
  FCC_IVEC3 base = i < 4 ? frame.lower : frame.upper;
  return fcc_ifrom_stack(base + FCC_MAKE_IVEC3(2 * (i & 1), 2 * ((i >> 1) & 1), 0), frame.axis);
}

// The scheme's polynomial on xyz's piece (continued outside it), as a multi-affine function of
// (a, b, n) given by its values at the 8 corners of the unit cell of stack coordinates at `cornerStack`.
// spatial == 0 ignores the upper plane (corners 4..7 equal 0..3).
FCC_FUNC FccCorners8 bcc_plane_unit_cell_corners(FccCorners8 s, BccPlaneFrame frame, FCC_IVEC3 cornerStack, int spatial) {
  FccCorners8 c;
  for (int i = 0; i < 8; ++i) {
    float a = FCC_FLOAT(cornerStack.x + (i & 1)), b = FCC_FLOAT(cornerStack.y + ((i >> 1) & 1));
    float u0 = 0.5f * (a - FCC_FLOAT(frame.lower.x)), v0 = 0.5f * (b - FCC_FLOAT(frame.lower.y));
    float lower = (1.0f - v0) * ((1.0f - u0) * s.v[0] + u0 * s.v[1]) + v0 * ((1.0f - u0) * s.v[2] + u0 * s.v[3]);
    float value = lower;
    if (spatial != 0) {
      float u1 = 0.5f * (a - FCC_FLOAT(frame.upper.x)), v1 = 0.5f * (b - FCC_FLOAT(frame.upper.y));
      float upper = (1.0f - v1) * ((1.0f - u1) * s.v[4] + u1 * s.v[5]) + v1 * ((1.0f - u1) * s.v[6] + u1 * s.v[7]);
      float w = FCC_FLOAT(cornerStack.z + ((i >> 2) & 1) - frame.lower.z);
      value = lower + w * (upper - lower);
    }
    c.v[i] = value;
  }
  return c;
}

// The unit cell of stack coordinates (lowest corner) that holds xyz's piece: for the nearest-plane
// scheme its n is the plane's (the piece spans n0 - 1/2 .. n0 + 1/2; the polynomial ignores n).
FCC_FUNC FCC_IVEC3 bcc_plane_unit_cell(FCC_VEC3 xyz, int axis) {
  FCC_VEC3 s = fcc_to_stack(xyz, axis);
  return FCC_IVEC3_FROM_VEC3(FCC_FLOOR3(s));
}

FCC_FUNC FccValueGradient bcc_plane_value_gradient(FccCorners8 s, BccPlaneFrame frame, FCC_VEC3 xyz, int spatial) {
  FCC_VEC3 st = fcc_to_stack(xyz, frame.axis);
  FCC_IVEC3 cell = FCC_IVEC3_FROM_VEC3(FCC_FLOOR3(st));
  FccCorners8 c = bcc_plane_unit_cell_corners(s, frame, cell, spatial);
  FCC_VEC3 f = st - FCC_VEC3_FROM_IVEC3(cell);
  FccValueGradient r;
  r.value = fcc_multiaffine(c, f);
  FCC_VEC3 g = fcc_multiaffine_gradient(c, f);
  if (spatial == 0) g.z = 0.0f;
  r.gradient = fcc_from_stack(g, frame.axis);
  return r;
}

// Where the ray crosses the nearest-plane scheme's steps (n = n0 + 1/2) inside the unit cell `cell`
// of index space; bilinear-spatial has no cuts inside a unit cell.
FCC_FUNC FccSplits bcc_plane_cell_splits(FCC_IVEC3 cell, int axis, int spatial, FCC_VEC3 o, FCC_VEC3 d, float ta, float tb) {
  FccSplits s = fcc_splits_none();
  if (spatial != 0) return s;
  FCC_VEC3 normal = FCC_VEC3_FROM_IVEC3(fcc_unit_axis(axis));
  return fcc_splits_with_plane(s, normal, FCC_FLOAT(fcc_icomponent(cell, axis)) + 0.5f, o, d, ta, tb);
}

FCC_NAMESPACE_END

#endif  // FCC_BCC_BILINEAR_H
