// The FCC lattice's six-direction box spline for raycast.comp: its value, and DVR through the (up to
// five) tetrahedral pieces a ray crosses in a unit cell. The isosurface's cell work (the cubic along
// the ray in each piece whose BB-coefficients straddle the isovalue, solved exactly by sparse/FccRay.h)
// is written into raycast.comp's marchBrick, where the compiler keeps it fast.

#include "FccRay.h"

float valueAt(vec3 xyz) {
  FccFrame frame = fcc_locate(xyz);
  return fcc_value(gatherStencil(frame), frame);
}

#if FCC_MODE_DVR
#ifndef FCC_DVR_ONE_FETCH
#define FCC_DVR_ONE_FETCH 0
#endif
#if defined(FCC_SLOT_THIRD)
// A cell's chord as one cubic where that is certified close (docs/DVR.md, "One cubic a cell"): along
// the chord the spline is C2, a cubic on each of up to five pieces whose third derivative jumps (by J_k)
// at up to four faces, so the cubic Hermite interpolant H of the value and slope at the chord's ends
// differs from it by at most (h^3 / 192) sum |J_k| (h the chord's length in t). A piece's third
// derivative along the ray is 6 B(delta, delta, delta) of its BB net, delta the ray's barycentric rates
// (relative to vertex 0): at most 6 |delta|_1^3 T, T the largest third difference, and |delta|_1 is at
// most c |d|_1 (c = 1 for type 0, 1.5 for type 4). gCellThird (slot_bounds.comp) is the largest c^3 T
// of the voxel's pieces; each |J_k| is at most twice 6 |d|_1^3 gCellThird, so
//   |s - H| <= (h |d|_1)^3 * 2 * 4 * 6 / 192 * gCellThird = chord^3 * gCellThird / 4,
// chord the chord's index-space 1-norm. Where that is within kDvrCellCubicEntries table entries, the
// cell is one segment (its hull widened by the bound for the skip and the sub-step rule) and one
// evaluation at its exit (the entry's is carried from the cell before); elsewhere its pieces, exactly.
const float kDvrCellCubicEntries = 0.5;
float gCellThird;                     // c^3 T of the cell's packed voxel (raycast.comp's marchBrick sets it)
vec3 gDvrCarry = vec3(-1e30, 0.0, 0.0);  // (t, value, slope) where the last cell's chord ended

void dvrForgetCarry() { gDvrCarry.x = -1e30; }

// The spline's value and slope (per unit t) at o + t d, from the piece of `cell` there.
vec2 valueSlopeAt(ivec3 cell, vec3 o, vec3 d, float t) {
  FccFrame frame = fcc_locate(clamp(o + t * d, vec3(cell), vec3(cell + 1)));
  FccCubic cubic = fcc_cubic(gatherStencil(frame), frame.type);
  vec4 l = fcc_barycentric(frame.q, frame.type);
  vec4 dl = fcc_barycentric(frame.q + vec3(frame.axis) * d, frame.type) - l;  // affine: the rate per unit t
  vec4 c = fcc_decasteljau_step2(fcc_decasteljau_step3(cubic, l), l);
  return vec2(dot(l, c), 3.0 * dot(dl, c)) * (1.0 / FCC_CUBIC_DENOM);
}

bool integrateCellCubic(ivec3 cell, vec3 o, vec3 d, float t0, float t1, float bound, inout DvrState st) {
  vec2 a = gDvrCarry.x == t0 ? gDvrCarry.yz : valueSlopeAt(cell, o, d, t0);
  vec2 b = valueSlopeAt(cell, o, d, t1);
  gDvrCarry = vec3(t1, b);
  float h = (t1 - t0) / 3.0;
  return dvrSegment3Within(vec4(a.x, a.x + h * a.y, b.x - h * b.y, b.x), bound, t0, t1, st);
}
#endif

// Emission-absorption through unit cell `cell` between t0 and t1 (dvr.glsl), piece by piece; true
// once the ray is opaque enough to stop.
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  dvrBeginCell(cell, o, d);
#if defined(FCC_SLOT_THIRD)
  float chord = (t1 - t0) * (abs(d.x) + abs(d.y) + abs(d.z));
  float bound = 0.25 * chord * chord * chord * gCellThird;
  if (bound * uTfScale <= kDvrCellCubicEntries) return integrateCellCubic(cell, o, d, t0, t1, bound, st);
  dvrForgetCarry();
#endif
  vec4 splits = fcc_cell_splits(cell, o, d, t0, t1);
  float s0 = t0;
  for (int k = 0; k < 5 && s0 < t1; ++k) {
    float s1 = k == 0 ? splits.x : (k == 1 ? splits.y : (k == 2 ? splits.z : (k == 3 ? splits.w : t1)));
    if (s1 <= s0) continue;
    FccFrame frame = fcc_locate(clamp(o + (0.5 * (s0 + s1)) * d, vec3(cell), vec3(cell + 1)));
#if FCC_DVR_ONE_FETCH
    // Measurement knob (docs/RENDERER.md): one fetch for all 19 coefficients (wrong images: for the
    // gather's share of the cost alone), made to differ by a uniform so that the compiler cannot fold
    // the cubic's arithmetic away.
    FccSamples one;
    float c = coefficientAt(frame.origin);
    for (int i = 0; i < 19; ++i) one.v[i] = c + float(i) * uStopTransmittance * 1e-6;
    FccCubic cubic = fcc_cubic(one, frame.type);
#else
    FccCubic cubic = fcc_cubic(gatherStencil(frame), frame.type);
#endif
    // The segment's own hull (dvrSegment3) is within the piece's: no separate check of the piece.
    if (dvrSegment3(fcc_segment_bernstein(cubic, frame, o, d, s0, s1, 0.0), s0, s1, st)) return true;
    s0 = s1;
  }
  return false;
}

#if FCC_DVR_SHADING
// The box spline's gradient at xyz (the piece there: the spline is C2, so a rounding across a piece
// boundary changes nothing that matters).
vec3 dvrGradient(ivec3 cell, vec3 xyz) {
  FccFrame frame = fcc_locate(clamp(xyz, vec3(cell), vec3(cell + 1)));
  return fcc_gradient(gatherStencil(frame), frame);
}
#endif
#endif
