// CcType6.h — the type-6 cubic C1 quasi-interpolating spline of Sorokina and Zeilfelder (IMA J. Numer.
// Anal. 27, 2007; paper 003 renders it) on the Cartesian (CC) lattice, in the three dialects of
// Dialect.h (`type6`).
//
// The data are the samples themselves (no prefilter), taken as the centres of cubes: the cube of the
// site c is [c - 1/2, c + 1/2]^3. Six planes through its centre (x = +-y, y = +-z, x = +-z, relative to
// it) cut it into 24 congruent tetrahedra [centre, face centre, two corners of one edge of that face].
// On each the spline is a cubic in Bernstein-Bezier form whose 20 coefficients are fixed positive
// combinations of the 27 samples around c (CcType6Tables.h, generated and proven by
// tools/gen_type6_tables.py): C1 everywhere, exact on trilinear polynomials (1, x, y, z, xy, yz, xz,
// xyz), and x^2 becomes x^2 + 1/4 (per pure square, in index units): quadratics are not reproduced,
// but |p|^2 becomes |p|^2 + 3/4, so a sphere's isosurface is a sphere (of radius sqrt(r^2 - 3/4)).
//
// Every tetrahedron is the image of the canonical one, T0 = [(0,0,0), (-1/2,0,0), (-1/2,-1/2,1/2),
// (-1/2,1/2,1/2)], under a symmetry of the cube (a signed permutation of the axes, the frame below);
// the samples are read in T0's order through it, so one table serves all 24.
//
// Along a ray inside one tetrahedron the spline is a cubic in the ray parameter: its Bernstein
// coefficients are the piece's blossom at the segment's ends (as FccRay.h's), its first root exact
// (ReconCommon.h). A unit cell [c, c + 1]^3 meets 8 cubes; the 3 planes between them and 6 diagonal
// planes cut it so that each part lies in one tetrahedron (cc_type6_cell_splits, at most 9). Bounds:
// the piece's BB coefficients (convex hull), or any hull of the samples its stencil reads.
#ifndef FCC_CC_TYPE6_H
#define FCC_CC_TYPE6_H

#include "Dialect.h"
#include "ReconCommon.h"
#include "FccSpline.h"
#include "CcType6Tables.h"

FCC_NAMESPACE_BEGIN

// The 27 samples around a cube's centre in canonical order: index (dx+1) + 3 (dy+1) + 9 (dz+1) for the
// canonical offset (dx, dy, dz) (see the frame).
FCC_STRUCT_BEGIN(FccSamples27)
  float v[27];
FCC_STRUCT_END(FccSamples27)

// Where a point's tetrahedron lies: the cube's centre (a site), and the symmetry taking T0 to it. A
// canonical offset p maps to the index-space offset with component axes.x equal to signs.x * p.x,
// component axes.y to signs.y * p.y and component axes.z to signs.z * p.z. axes.x: the axis of the
// face (T0's is -x), axes.z: the axis towards the tetrahedron's edge (T0's is +z), axes.y: along the edge.
FCC_STRUCT_BEGIN(CcType6Frame)
  FCC_IVEC3 centre;
  FCC_IVEC3 axes;
  FCC_IVEC3 signs;
FCC_STRUCT_END(CcType6Frame)

FCC_FUNC CcType6Frame cc_type6_locate(FCC_VEC3 xyz) {
  CcType6Frame f;
  f.centre = FCC_IVEC3_FROM_VEC3(FCC_FLOOR3(xyz + FCC_MAKE_VEC3(0.5f, 0.5f, 0.5f)));
  FCC_VEC3 r = xyz - FCC_VEC3_FROM_IVEC3(f.centre);
  float ax = FCC_ABS(r.x), ay = FCC_ABS(r.y), az = FCC_ABS(r.z);
  int a = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
  int o1 = a == 0 ? 1 : 0;
  int o2 = a == 2 ? 1 : 2;
  int m = FCC_ABS(fcc_component(r, o1)) >= FCC_ABS(fcc_component(r, o2)) ? o1 : o2;
  int e = m == o1 ? o2 : o1;
  f.axes = FCC_MAKE_IVEC3(a, e, m);
  f.signs = FCC_MAKE_IVEC3(fcc_component(r, a) >= 0.0f ? -1 : 1, 1, fcc_component(r, m) >= 0.0f ? 1 : -1);
  return f;
}

// Index-space offset of the canonical offset p.
FCC_FUNC FCC_IVEC3 cc_type6_offset(CcType6Frame f, FCC_IVEC3 p) {
  return fcc_unit_axis(f.axes.x) * (f.signs.x * p.x) + fcc_unit_axis(f.axes.y) * (f.signs.y * p.y) +
         fcc_unit_axis(f.axes.z) * (f.signs.z * p.z);
}

// The canonical coordinates of xyz (relative to the frame's centre; outside the tetrahedron too).
FCC_FUNC FCC_VEC3 cc_type6_canonical(CcType6Frame f, FCC_VEC3 xyz) {
  FCC_VEC3 r = xyz - FCC_VEC3_FROM_IVEC3(f.centre);
  return FCC_MAKE_VEC3(FCC_FLOAT(f.signs.x) * fcc_component(r, f.axes.x), FCC_FLOAT(f.signs.y) * fcc_component(r, f.axes.y),
                       FCC_FLOAT(f.signs.z) * fcc_component(r, f.axes.z));
}

// The site of canonical sample i (0..26).
FCC_FUNC FCC_IVEC3 cc_type6_stencil_site(CcType6Frame f, int i) {
  return f.centre + cc_type6_offset(f, FCC_MAKE_IVEC3(i % 3 - 1, (i / 3) % 3 - 1, i / 9 - 1));
}

// The piece's 20 BB coefficients (FccCubic's order, unscaled): the generated sums of the non-zero
// weights (CC_TYPE6_ROWS), not a loop over the 540-entry table, which NVIDIA's GLSL compiler copies
// into each invocation's memory (2.5 fps at 512^2 on the H200, docs/BENCHMARKS.md session 13).
FCC_FUNC FccCubic cc_type6_cubic(FccSamples27 s) {
  FccCubic c;
  CC_TYPE6_ROWS(c.b, s.v)
  return c;
}

// The same from the table, row by row: the definition the generated sums are tested against.
FCC_FUNC FccCubic cc_type6_cubic_from_table(FccSamples27 s) {
  FccCubic c;
  for (int r = 0; r < 20; ++r) {
    float acc = 0.0f;
    for (int i = 0; i < 27; ++i) acc += FCC_FLOAT(cc_type6_weights[r * 27 + i]) * s.v[i];
    c.b[r] = acc * (1.0f / FCC_TYPE6_DENOM);
  }
  return c;
}

// Barycentric coordinates with respect to T0 of the canonical point p.
FCC_FUNC FCC_VEC4 cc_type6_barycentric(FCC_VEC3 p) {
  return FCC_MAKE_VEC4(1.0f + 2.0f * p.x, -2.0f * (p.x + p.z), p.z - p.y, p.z + p.y);
}

FCC_FUNC FccValueGradient cc_type6_value_gradient(FccCubic c, CcType6Frame f, FCC_VEC3 xyz) {
  FCC_VEC4 l = cc_type6_barycentric(cc_type6_canonical(f, xyz));
  FccQuadratic q = fcc_decasteljau_step3(c, l);
  FCC_VEC4 r = fcc_decasteljau_step2(q, l);
  FccValueGradient vg;
  vg.value = l.x * r.x + l.y * r.y + l.z * r.z + l.w * r.w;
  // d/dlambda_m = 3 r_m; the barycentrics' derivatives along the canonical axes are constants.
  float gx = 6.0f * (r.x - r.y), gy = 3.0f * (r.w - r.z), gz = 3.0f * (r.z + r.w - 2.0f * r.y);
  vg.gradient = FCC_VEC3_FROM_IVEC3(fcc_unit_axis(f.axes.x)) * (FCC_FLOAT(f.signs.x) * gx) +
                 FCC_VEC3_FROM_IVEC3(fcc_unit_axis(f.axes.y)) * (FCC_FLOAT(f.signs.y) * gy) +
                 FCC_VEC3_FROM_IVEC3(fcc_unit_axis(f.axes.z)) * (FCC_FLOAT(f.signs.z) * gz);
  return vg;
}

// Bounds of the piece: its BB coefficients' min and max (convex hull).
FCC_FUNC FccRange cc_type6_range(FccCubic c) {
  FccRange r;
  r.lo = c.b[0];
  r.hi = c.b[0];
  for (int i = 1; i < 20; ++i) {
    r.lo = min(r.lo, c.b[i]);
    r.hi = max(r.hi, c.b[i]);
  }
  return r;
}

// Bernstein coefficients on u in [0, 1] of the piece minus iso along the segment from xyz a to b: the
// blossom B(a,a,a), B(a,a,b), B(a,b,b), B(b,b,b), one de Casteljau step per argument.
FCC_FUNC FCC_VEC4 cc_type6_segment_bernstein(FccCubic c, CcType6Frame f, FCC_VEC3 a, FCC_VEC3 b, float iso) {
  FCC_VEC4 la = cc_type6_barycentric(cc_type6_canonical(f, a)), lb = cc_type6_barycentric(cc_type6_canonical(f, b));
  FccQuadratic ca = fcc_decasteljau_step3(c, la), cb = fcc_decasteljau_step3(c, lb);
  FCC_VEC4 caa = fcc_decasteljau_step2(ca, la), cab = fcc_decasteljau_step2(ca, lb), cbb = fcc_decasteljau_step2(cb, lb);
  return FCC_MAKE_VEC4(la.x * caa.x + la.y * caa.y + la.z * caa.z + la.w * caa.w - iso,
                       lb.x * caa.x + lb.y * caa.y + lb.z * caa.z + lb.w * caa.w - iso,
                       lb.x * cab.x + lb.y * cab.y + lb.z * cab.z + lb.w * cab.w - iso,
                       lb.x * cbb.x + lb.y * cbb.y + lb.z * cbb.z + lb.w * cbb.w - iso);
}

// Where the ray o + t d crosses, in (ta, tb), the planes that cut the unit cell [cell, cell + 1]^3 into
// parts of single tetrahedra: the cubes' faces x = cell.x + 1/2 (and y, z), and per pair of axes the
// one diagonal plane of each cube that passes through the cell's inside (x - y = cell.x - cell.y and
// x + y = cell.x + cell.y + 1; the others touch only its edges). Sorted; at most 9.
FCC_FUNC FccSplits cc_type6_cell_splits(FCC_IVEC3 cell, FCC_VEC3 o, FCC_VEC3 d, float ta, float tb) {
  FccSplits s = fcc_splits_none();
  FCC_VEC3 c = FCC_VEC3_FROM_IVEC3(cell);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(1.0f, 0.0f, 0.0f), c.x + 0.5f, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(0.0f, 1.0f, 0.0f), c.y + 0.5f, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(0.0f, 0.0f, 1.0f), c.z + 0.5f, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(1.0f, -1.0f, 0.0f), c.x - c.y, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(1.0f, 1.0f, 0.0f), c.x + c.y + 1.0f, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(0.0f, 1.0f, -1.0f), c.y - c.z, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(0.0f, 1.0f, 1.0f), c.y + c.z + 1.0f, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(1.0f, 0.0f, -1.0f), c.x - c.z, o, d, ta, tb);
  s = fcc_splits_with_plane(s, FCC_MAKE_VEC3(1.0f, 0.0f, 1.0f), c.x + c.z + 1.0f, o, d, ta, tb);
  return s;
}

FCC_NAMESPACE_END

#endif  // FCC_CC_TYPE6_H
