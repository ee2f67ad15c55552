// BccBarycentric.h — barycentric (piecewise linear) interpolation on the body-centred cubic (BCC)
// lattice's Delaunay tetrahedra, in the three dialects of Dialect.h (paper 002, section 3.3).
//
// BCC index space: sites are the integer points whose three coordinates have one parity (all even:
// the primary cubic grid of spacing 2; all odd: the secondary grid, the primary cubes' centres). Every
// Delaunay tetrahedron joins two primary sites one edge of a primary cube apart with the two
// secondary sites (cube centres) on either side of a face holding that edge; the face cuts it into two
// halves, one in each cube. In the primary cube with centre C and r = xyz - C in [-1, 1]^3, the half
// holding xyz is named by the axes sorted by |r|: f (largest, the face, sign s_f), j (middle, sign
// s_j: the edge on that face), k (smallest: the edge's direction). With a = s_f r_f, b = s_j r_j,
// c = r_k, the tetrahedron's vertices and barycentric weights are
//   C: 1 - (a + b) / 2,   C + 2 e_f: (a - b) / 2,   C + e_f + e_j + e_k: (b + c) / 2,   C + e_f + e_j - e_k: (b - c) / 2
// (e_f = s_f times the unit axis f, e_j likewise, e_k the unit axis k). Linear on each piece, C0,
// reproduces linear functions. The planes |r_f| = |r_j| (six through C) cut a cube into its 24 halves,
// so along a ray the first hit is exact: linear between consecutive crossings.
#ifndef FCC_BCC_BARYCENTRIC_H
#define FCC_BCC_BARYCENTRIC_H

#include "Dialect.h"
#include "ReconCommon.h"

FCC_NAMESPACE_BEGIN

FCC_STRUCT_BEGIN(BccTetFrame)
  FCC_IVEC3 center;  // the primary cube's centre (a secondary site)
  FCC_IVEC3 ef;      // signed unit axes f, j and (unsigned) k
  FCC_IVEC3 ej;
  FCC_IVEC3 ek;
FCC_STRUCT_END(BccTetFrame)

FCC_STRUCT_BEGIN(FccCorners4)
  float v[4];
FCC_STRUCT_END(FccCorners4)

FCC_FUNC BccTetFrame bcc_barycentric_locate(FCC_VEC3 xyz) {
  FCC_VEC3 corner = 2.0f * FCC_FLOOR3(xyz * 0.5f);
  BccTetFrame frame;
  frame.center = FCC_IVEC3_FROM_VEC3(corner) + FCC_MAKE_IVEC3(1, 1, 1);
  FCC_VEC3 r = xyz - FCC_VEC3_FROM_IVEC3(frame.center);
  FCC_VEC3 ar = FCC_MAKE_VEC3(FCC_ABS(r.x), FCC_ABS(r.y), FCC_ABS(r.z));
  // Largest and smallest |r| (ties broken so that f, j, k are always three different axes).
  int f = ar.x >= ar.y ? (ar.x >= ar.z ? 0 : 2) : (ar.y >= ar.z ? 1 : 2);
  int k = ar.x < ar.y ? (ar.x < ar.z ? 0 : 2) : (ar.y < ar.z ? 1 : 2);
  int j = 3 - f - k;
  int sf = fcc_component(r, f) >= 0.0f ? 1 : -1;
  int sj = fcc_component(r, j) >= 0.0f ? 1 : -1;
  frame.ef = fcc_unit_axis(f) * sf;
  frame.ej = fcc_unit_axis(j) * sj;
  frame.ek = fcc_unit_axis(k);
  return frame;
}

FCC_FUNC FCC_IVEC3 bcc_barycentric_stencil_site(BccTetFrame frame, int i) {
  if (i == 0) return frame.center;
  if (i == 1) return frame.center + 2 * frame.ef;
  if (i == 2) return frame.center + frame.ef + frame.ej + frame.ek;
  return frame.center + frame.ef + frame.ej - frame.ek;
}

// The piece's linear function (value and gradient) at xyz; outside the piece, the same function continued.
FCC_FUNC FccValueGradient bcc_barycentric_value_gradient(FccCorners4 s, BccTetFrame frame, FCC_VEC3 xyz) {
  FCC_VEC3 r = xyz - FCC_VEC3_FROM_IVEC3(frame.center);
  FCC_VEC3 ef = FCC_VEC3_FROM_IVEC3(frame.ef), ej = FCC_VEC3_FROM_IVEC3(frame.ej), ek = FCC_VEC3_FROM_IVEC3(frame.ek);
  float a = ef.x * r.x + ef.y * r.y + ef.z * r.z;
  float b = ej.x * r.x + ej.y * r.y + ej.z * r.z;
  float c = ek.x * r.x + ek.y * r.y + ek.z * r.z;
  FccValueGradient result;
  result.value = (1.0f - 0.5f * (a + b)) * s.v[0] + 0.5f * (a - b) * s.v[1] + 0.5f * (b + c) * s.v[2] + 0.5f * (b - c) * s.v[3];
  float ga = 0.5f * (s.v[1] - s.v[0]);
  float gb = 0.5f * (s.v[2] + s.v[3] - s.v[0] - s.v[1]);
  float gc = 0.5f * (s.v[2] - s.v[3]);
  result.gradient = ga * ef + gb * ej + gc * ek;
  return result;
}

// Bounds of the piece: its vertices' values.
FCC_FUNC FccRange bcc_barycentric_range(FccCorners4 s) {
  FccRange r;
  r.lo = min(min(s.v[0], s.v[1]), min(s.v[2], s.v[3]));
  r.hi = max(max(s.v[0], s.v[1]), max(s.v[2], s.v[3]));
  return r;
}

// Where the ray crosses the six planes through the centre of the primary cube holding the unit cell
// `cell` (|r_x| = |r_y| etc.), between ta and tb.
FCC_FUNC FccSplits bcc_barycentric_cell_splits(FCC_IVEC3 cell, FCC_VEC3 o, FCC_VEC3 d, float ta, float tb) {
  FCC_VEC3 c = 2.0f * FCC_FLOOR3(FCC_VEC3_FROM_IVEC3(cell) * 0.5f) + FCC_MAKE_VEC3(1.0f, 1.0f, 1.0f);
  FccSplits s = fcc_splits_none();
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(1.0f, -1.0f, 0.0f), c.x - c.y, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(1.0f, 1.0f, 0.0f), c.x + c.y, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(1.0f, 0.0f, -1.0f), c.x - c.z, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(1.0f, 0.0f, 1.0f), c.x + c.z, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(0.0f, 1.0f, -1.0f), c.y - c.z, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(0.0f, 1.0f, 1.0f), c.y + c.z, o, d, ta, tb);
  
  return s;
}

FCC_NAMESPACE_END

#endif  // FCC_BCC_BARYCENTRIC_H
