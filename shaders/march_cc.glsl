// The Cartesian (CC) lattice's reconstructions for raycast.comp, on slots of 20^3 grid points
// [16b - 2, 16b + 18)^3 (viewer/CartesianBrickSource.h): FCC_RECON_TRILINEAR, the 8 corners of the cell,
// a cubic along the ray (sparse/CcTrilinear.h); FCC_RECON_TRICUBIC, the 4^3 B-spline coefficients
// around it, a polynomial of degree 9 along the ray whose first root is found by subdivision with the
// convex hull (sparse/CcTricubic.h). Both exact to float precision, no fixed step.

#include "CcTrilinear.h"
#include "CcTricubic.h"

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
