// The BCC lattice's reconstructions (paper 002) for raycast.comp, on BCC slots (pool.glsl, FCC_SLOT_BCC:
// the two cosets' voxels [8b - 2, 8b + 10)^3): FCC_RECON_BARYCENTRIC (linear on the Delaunay
// tetrahedra, sparse/BccBarycentric.h), FCC_RECON_SHEARED_TRILINEAR (trilinear in the sheared 2 x 2 x 1
// cells, BccShearedTrilinear.h), FCC_RECON_BILINEAR_SPATIAL and FCC_RECON_BILINEAR (the plane stacks,
// BccBilinear.h). A unit cell is cut at its pieces' boundaries (the scheme's cell splits); in each part
// the piece's polynomial along the ray is a cubic at most, in Bernstein form from the header's blossom
// (the barycentric's line, raised), and its first root is exact (fcc_first_root_after), as
// sparse/ReconDispatch.h's fcc_recon_segment_root finds it and sparse/ReferenceRaycast.h checks it.
// The stack schemes depend on the view: uBccParams (stack axis, shear signs) is chosen once per frame
// from the camera's forward direction in index space (viewer/Raycaster.cpp), as a CPU reference's
// Reconstruction::setView chooses it.

#include "BccBarycentric.h"
#include "BccShearedTrilinear.h"
#include "BccBilinear.h"

uniform ivec3 uBccParams;

// raycast.comp's, from valueAt below.
vec3 finiteDifferenceGradient(vec3 xyz, ivec3 brick);

#if FCC_RECON == FCC_RECON_BILINEAR_SPATIAL
const int kBccSpatial = 1;
#else
const int kBccSpatial = 0;  // (FCC_RECON_BILINEAR: the nearest plane; the others ignore it)
#endif

// One piece: where it lies and the sites its stencil reads.
struct BccPiece {
#if FCC_RECON == FCC_RECON_BARYCENTRIC
  BccTetFrame frame;
  FccCorners4 s;
#elif FCC_RECON == FCC_RECON_SHEARED_TRILINEAR
  BccShearedFrame frame;
  FccCorners8 c;
#else
  BccPlaneFrame frame;
  FccCorners8 s;
  ivec3 unitCell;  // the stack's unit cell the piece's multi-affine form lives in
#endif
};

// The piece holding `inside` (a point strictly inside one piece: a sub-segment's middle).
BccPiece bccPiece(vec3 inside) {
  BccPiece p;
#if FCC_RECON == FCC_RECON_BARYCENTRIC
  p.frame = bcc_barycentric_locate(inside);
  for (int i = 0; i < 4; ++i) p.s.v[i] = coefficientAt(bcc_barycentric_stencil_site(p.frame, i));
#elif FCC_RECON == FCC_RECON_SHEARED_TRILINEAR
  p.frame = bcc_sheared_locate(inside, uBccParams);
  for (int i = 0; i < 8; ++i) p.c.v[i] = coefficientAt(bcc_sheared_stencil_site(p.frame, i));
#else
  p.frame = bcc_plane_locate(inside, uBccParams.x, kBccSpatial);
  // The nearest-plane scheme reads only the lower square.
  for (int i = 0; i < 8; ++i) p.s.v[i] = coefficientAt(bcc_plane_stencil_site(p.frame, kBccSpatial != 0 ? i : (i & 3)));
  p.unitCell = bcc_plane_unit_cell(inside, uBccParams.x);
#endif
  return p;
}

FccValueGradient bccValueGradient(BccPiece p, vec3 xyz) {
#if FCC_RECON == FCC_RECON_BARYCENTRIC
  return bcc_barycentric_value_gradient(p.s, p.frame, xyz);
#elif FCC_RECON == FCC_RECON_SHEARED_TRILINEAR
  return bcc_sheared_value_gradient(p.c, p.frame, xyz);
#else
  return bcc_plane_value_gradient(p.s, p.frame, xyz, kBccSpatial);
#endif
}

// The piece's polynomial minus `iso` along [a, b], a cubic in Bernstein form on [0, 1].
vec4 bccSegmentBernstein(BccPiece p, vec3 a, vec3 b, float iso) {
#if FCC_RECON == FCC_RECON_BARYCENTRIC
  return fcc_linear_as_bernstein3(bcc_barycentric_value_gradient(p.s, p.frame, a).value - iso,
                                  bcc_barycentric_value_gradient(p.s, p.frame, b).value - iso);
#elif FCC_RECON == FCC_RECON_SHEARED_TRILINEAR
  return fcc_multiaffine_segment_bernstein(p.c, bcc_sheared_local(p.frame, a), bcc_sheared_local(p.frame, b), iso);
#else
  FccCorners8 c = bcc_plane_unit_cell_corners(p.s, p.frame, p.unitCell, kBccSpatial);
  vec3 origin = vec3(p.unitCell);
  return fcc_multiaffine_segment_bernstein(c, fcc_to_stack(a, uBccParams.x) - origin, fcc_to_stack(b, uBccParams.x) - origin, iso);
#endif
}

FccSplits bccCellSplits(ivec3 cell, vec3 o, vec3 d, float t0, float t1) {
#if FCC_RECON == FCC_RECON_BARYCENTRIC
  return bcc_barycentric_cell_splits(cell, o, d, t0, t1);
#elif FCC_RECON == FCC_RECON_SHEARED_TRILINEAR
  return bcc_sheared_cell_splits(cell, uBccParams, o, d, t0, t1);
#else
  return bcc_plane_cell_splits(cell, uBccParams.x, kBccSpatial, o, d, t0, t1);
#endif
}

// The piece holding the middle of the sub-segment [s0, s1] of a cell (kept inside the cell, so the
// stencil stays inside the slot's halo whatever the rounding).
BccPiece bccPieceOn(ivec3 cell, vec3 o, vec3 d, float s0, float s1) {
  return bccPiece(clamp(o + (0.5 * (s0 + s1)) * d, vec3(cell), vec3(cell + 1)));
}

float valueAt(vec3 xyz) { return bccValueGradient(bccPiece(xyz), xyz).value; }

// The range of a piece's cubic on its sub-segment: the hull of its Bernstein coefficients.
FccRange bccBernsteinRange(vec4 bz) {
  FccRange r;
  r.lo = min(min(bz.x, bz.y), min(bz.z, bz.w));
  r.hi = max(max(bz.x, bz.y), max(bz.z, bz.w));
  return r;
}

bool hitInCell(ivec3 b, ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout int prevSign, inout Hit hit) {
  FccSplits splits = bccCellSplits(cell, o, d, t0, t1);
  float s0 = t0;
  for (int k = 0; k <= splits.n; ++k) {
    float s1 = k < splits.n ? splits.t[k] : t1;
    if (s1 <= s0) continue;
    BccPiece p = bccPieceOn(cell, o, d, s0, s1);
    vec4 bz = bccSegmentBernstein(p, o + s0 * d, o + s1 * d, uIso);
    float u = fcc_first_root_after(bz, prevSign);
    prevSign = bz.w < 0.0 ? -1 : 1;
    if (u >= 0.0) {
      hit.t = s0 + u * (s1 - s0);
      vec3 xyz = o + hit.t * d;
      // This piece's polynomial at the hit, its sites already read.
      hit.gradient = uFiniteDifferenceNormals != 0 ? finiteDifferenceGradient(xyz, b) : bccValueGradient(p, xyz).gradient;
      return true;
    }
    s0 = s1;
  }
  return false;
}

#if FCC_MODE_DVR
// Emission-absorption through the cell between t0 and t1 (dvr.glsl): the cubic of each piece.
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  dvrBeginCell(cell, o, d);
  FccSplits splits = bccCellSplits(cell, o, d, t0, t1);
  float s0 = t0;
  for (int k = 0; k <= splits.n; ++k) {
    float s1 = k < splits.n ? splits.t[k] : t1;
    if (s1 <= s0) continue;
    vec4 bz = bccSegmentBernstein(bccPieceOn(cell, o, d, s0, s1), o + s0 * d, o + s1 * d, 0.0);
    FccRange range = bccBernsteinRange(bz);
    if (!tfZeroOn(range.lo, range.hi) && dvrSegment3(bz, s0, s1, st)) return true;
    s0 = s1;
  }
  return false;
}

#if FCC_DVR_SHADING
// The gradient of the piece at xyz (kept inside the cell).
vec3 dvrGradient(ivec3 cell, vec3 xyz) {
  vec3 p = clamp(xyz, vec3(cell), vec3(cell + 1));
  return bccValueGradient(bccPiece(p), p).gradient;
}
#endif
#endif
