// The Cartesian (CC) lattice's reconstructions for raycast.comp, on slots of 20^3 grid points
// [16b - 2, 16b + 18)^3 (viewer/CartesianBrickSource.h): FCC_RECON_TRILINEAR, the 8 corners of the cell,
// a cubic along the ray (sparse/CcTrilinear.h); FCC_RECON_TRICUBIC, the 4^3 B-spline coefficients
// around it, a polynomial of degree 9 along the ray whose first root is found by subdivision with the
// convex hull (sparse/CcTricubic.h); FCC_RECON_TYPE6, the type-6 cubic C1 spline: the cell cut at the
// cubes' faces and diagonal planes into parts of single tetrahedra, per part its 27 samples, 20 BB
// coefficients (their hull bounds it) and the cubic along the ray (sparse/CcType6.h). All exact to
// float precision, no fixed step.

#include "CcTrilinear.h"
#include "CcTricubic.h"
#include "CcType6.h"

// raycast.comp's, from valueAt below.
vec3 finiteDifferenceGradient(vec3 xyz, ivec3 brick);

#if FCC_RECON == FCC_RECON_TRILINEAR
FccCorners8 gatherCorners(ivec3 cell) {
  FccCorners8 c;
  for (int i = 0; i < 8; ++i) c.v[i] = coefficientAt(cc_trilinear_stencil_site(cell, i));
  return c;
}

float valueAt(vec3 xyz) {
  ivec3 cell = cc_trilinear_cell(xyz);
  return cc_trilinear_value_gradient(gatherCorners(cell), cell, xyz).value;
}

bool hitInCell(ivec3 b, ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout int prevSign, inout Hit hit) {
  FccCorners8 c = gatherCorners(cell);
  FccRange range = fcc_corners_range(c);
  if (!(range.lo <= uIso && uIso <= range.hi)) {
    prevSign = range.lo > uIso ? 1 : -1;
    return false;
  }
  vec3 origin = vec3(cell);
  vec4 bz = fcc_multiaffine_segment_bernstein(c, o + t0 * d - origin, o + t1 * d - origin, uIso);
  float u = fcc_first_root_after(bz, prevSign);
  prevSign = bz.w < 0.0 ? -1 : 1;
  if (u < 0.0) return false;
  hit.t = t0 + u * (t1 - t0);
  vec3 xyz = o + hit.t * d;
  // The cell's polynomial at the hit, with the corners already read (the rounded hit may lie a hair
  // outside the cell; the polynomial continues there).
  hit.gradient = uFiniteDifferenceNormals != 0 ? finiteDifferenceGradient(xyz, b)
                                               : cc_trilinear_value_gradient(c, cell, xyz).gradient;
  return true;
}

#if FCC_MODE_DVR
// Emission-absorption through the cell between t0 and t1 (dvr.glsl): the cubic along the ray.
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  dvrBeginCell(cell, o, d);
  FccCorners8 c = gatherCorners(cell);
  FccRange range = fcc_corners_range(c);
  if (tfZeroOn(range.lo, range.hi)) return false;
  vec3 origin = vec3(cell);
  return dvrSegment3(fcc_multiaffine_segment_bernstein(c, o + t0 * d - origin, o + t1 * d - origin, 0.0), t0, t1, st);
}

#if FCC_DVR_SHADING
// The trilinear interpolant's gradient at xyz (inside the cell).
vec3 dvrGradient(ivec3 cell, vec3 xyz) {
  return cc_trilinear_value_gradient(gatherCorners(cell), cell, clamp(xyz, vec3(cell), vec3(cell + 1))).gradient;
}
#endif
#endif

#elif FCC_RECON == FCC_RECON_TYPE6
// One tetrahedral piece: where it lies and its BB coefficients, from the 27 samples about its cube's
// centre (all within the slot's halo for a point of the brick: centre +- 1 of a cell corner).
struct Type6Piece {
  CcType6Frame frame;
  FccCubic cubic;
};

Type6Piece type6Piece(vec3 inside) {
  Type6Piece p;
  p.frame = cc_type6_locate(inside);
  FccSamples27 s;
  for (int i = 0; i < 27; ++i) s.v[i] = coefficientAt(cc_type6_stencil_site(p.frame, i));
  p.cubic = cc_type6_cubic(s);
  return p;
}

float valueAt(vec3 xyz) {
  Type6Piece p = type6Piece(xyz);
  return cc_type6_value_gradient(p.cubic, p.frame, xyz).value;
}

// The piece holding the middle of the sub-segment [s0, s1] of a cell (kept inside the cell, so the
// stencil stays inside the slot's halo whatever the rounding).
Type6Piece type6PieceOn(ivec3 cell, vec3 o, vec3 d, float s0, float s1) {
  return type6Piece(clamp(o + (0.5 * (s0 + s1)) * d, vec3(cell), vec3(cell + 1)));
}

bool hitInCell(ivec3 b, ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout int prevSign, inout Hit hit) {
  FccSplits splits = cc_type6_cell_splits(cell, o, d, t0, t1);
  float s0 = t0;
  for (int k = 0; k <= splits.n; ++k) {
    float s1 = k < splits.n ? splits.t[k] : t1;
    if (s1 <= s0) continue;
    Type6Piece p = type6PieceOn(cell, o, d, s0, s1);
    FccRange range = cc_type6_range(p.cubic);
    if (!(range.lo <= uIso && uIso <= range.hi)) {
      prevSign = range.lo > uIso ? 1 : -1;
    } else {
      vec4 bz = cc_type6_segment_bernstein(p.cubic, p.frame, o + s0 * d, o + s1 * d, uIso);
      float u = fcc_first_root_after(bz, prevSign);
      prevSign = bz.w < 0.0 ? -1 : 1;
      if (u >= 0.0) {
        hit.t = s0 + u * (s1 - s0);
        vec3 xyz = o + hit.t * d;
        // This piece's polynomial at the hit, its samples already read.
        hit.gradient = uFiniteDifferenceNormals != 0 ? finiteDifferenceGradient(xyz, b)
                                                     : cc_type6_value_gradient(p.cubic, p.frame, xyz).gradient;
        return true;
      }
    }
    s0 = s1;
  }
  return false;
}

#if FCC_MODE_DVR
// Emission-absorption through the cell between t0 and t1 (dvr.glsl): the cubic of each piece.
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  FccSplits splits = cc_type6_cell_splits(cell, o, d, t0, t1);
  float s0 = t0;
  for (int k = 0; k <= splits.n; ++k) {
    float s1 = k < splits.n ? splits.t[k] : t1;
    if (s1 <= s0) continue;
    Type6Piece p = type6PieceOn(cell, o, d, s0, s1);
    FccRange range = cc_type6_range(p.cubic);
    if (!tfZeroOn(range.lo, range.hi) &&
        dvrSegment3(cc_type6_segment_bernstein(p.cubic, p.frame, o + s0 * d, o + s1 * d, 0.0), s0, s1, st))
      return true;
    s0 = s1;
  }
  return false;
}
#endif

#else  // FCC_RECON_TRICUBIC: B-spline coefficients (prefiltered or the samples themselves)
FccCoeffs64 gatherCoefficients(ivec3 cell) {
  FccCoeffs64 c;
  for (int i = 0; i < 64; ++i) c.v[i] = coefficientAt(cc_tricubic_stencil_site(cell, i));
  return c;
}

float valueAt(vec3 xyz) {
  ivec3 cell = cc_tricubic_cell(xyz);
  return cc_tricubic_value_gradient(gatherCoefficients(cell), cell, xyz).value;
}

bool hitInCell(ivec3 b, ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout int prevSign, inout Hit hit) {
  FccCoeffs64 c = gatherCoefficients(cell);
  FccCoeffs64 bezier = cc_tricubic_bezier(c);
  FccRange range = cc_tricubic_range(bezier);
  if (!(range.lo <= uIso && uIso <= range.hi)) {
    prevSign = range.lo > uIso ? 1 : -1;
    return false;
  }
  vec3 origin = vec3(cell);
  FccBernstein9 p = cc_tricubic_segment_bernstein(bezier, o + t0 * d - origin, o + t1 * d - origin, uIso);
  // As fcc_first_root_after: a sign change at the join with the previous cell is a root at its start.
  float u = (prevSign != 0 && (p.b[0] < 0.0 ? -1 : 1) != prevSign) ? 0.0 : fcc_first_root_bernstein9(p);
  prevSign = p.b[9] < 0.0 ? -1 : 1;
  if (u < 0.0) return false;
  hit.t = t0 + u * (t1 - t0);
  vec3 xyz = o + hit.t * d;
  hit.gradient = uFiniteDifferenceNormals != 0 ? finiteDifferenceGradient(xyz, b)
                                               : cc_tricubic_value_gradient(c, cell, xyz).gradient;
  return true;
}

#if FCC_MODE_DVR
// Emission-absorption through the cell between t0 and t1 (dvr.glsl): the degree-9 polynomial along
// the ray.
#if FCC_DVR_SHADING
FccCoeffs64 gDvrCoefficients;  // the cell's, for dvrGradient: gathered once per cell, not per sub-step
#endif
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  dvrBeginCell(cell, o, d);
#if FCC_DVR_SHADING
  gDvrCoefficients = gatherCoefficients(cell);
  FccCoeffs64 bezier = cc_tricubic_bezier(gDvrCoefficients);
#else
  FccCoeffs64 bezier = cc_tricubic_bezier(gatherCoefficients(cell));
#endif
  FccRange range = cc_tricubic_range(bezier);
  if (tfZeroOn(range.lo, range.hi)) return false;
  vec3 origin = vec3(cell);
  return dvrSegment9(cc_tricubic_segment_bernstein(bezier, o + t0 * d - origin, o + t1 * d - origin, 0.0), t0, t1, st);
}

#if FCC_DVR_SHADING
// The tricubic spline's gradient at xyz (inside the cell).
vec3 dvrGradient(ivec3 cell, vec3 xyz) {
  return cc_tricubic_value_gradient(gDvrCoefficients, cell, clamp(xyz, vec3(cell), vec3(cell + 1))).gradient;
}
#endif
#endif
#endif
