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
#ifndef FCC_DVR_HERMITE_CELL
#define FCC_DVR_HERMITE_CELL 0
#endif
#if FCC_DVR_HERMITE_CELL
// Measurement knob (docs/RENDERER.md; approximate images, no error check): a cell's chord as one cubic,
// the Hermite interpolant of the value and slope at its ends (docs/DVR.md, "Not done yet"), the
// entry's carried from the cell before when the ray comes straight from it: one piece evaluation a cell.
vec3 gHermiteCarry = vec3(-1e30, 0.0, 0.0);  // (t, value, slope) at the last cell's exit

vec2 valueSlopeAt(ivec3 cell, vec3 o, vec3 d, float t) {
  FccFrame frame = fcc_locate(clamp(o + t * d, vec3(cell), vec3(cell + 1)));
  FccCubic cubic = fcc_cubic(gatherStencil(frame), frame.type);
  vec4 l = fcc_barycentric(frame.q, frame.type);
  vec4 dl = fcc_barycentric(frame.q + vec3(frame.axis) * d, frame.type) - l;  // per unit t (affine)
  vec4 c = fcc_decasteljau_step2(fcc_decasteljau_step3(cubic, l), l);
  return vec2(dot(l, c), 3.0 * dot(dl, c)) * (1.0 / FCC_CUBIC_DENOM);
}

bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  dvrBeginCell(cell, o, d);
  vec2 a = gHermiteCarry.x == t0 ? gHermiteCarry.yz : valueSlopeAt(cell, o, d, t0);
  vec2 b = valueSlopeAt(cell, o, d, t1);
  gHermiteCarry = vec3(t1, b);
  float h = (t1 - t0) / 3.0;
  return dvrSegment3(vec4(a.x, a.x + h * a.y, b.x - h * b.y, b.x), t0, t1, st);
}
#else
// Emission-absorption through unit cell `cell` between t0 and t1 (dvr.glsl), piece by piece; true
// once the ray is opaque enough to stop.
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  dvrBeginCell(cell, o, d);
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
#endif  // FCC_DVR_HERMITE_CELL

#if FCC_DVR_SHADING
// The box spline's gradient at xyz (the piece there: the spline is C2, so a rounding across a piece
// boundary changes nothing that matters).
vec3 dvrGradient(ivec3 cell, vec3 xyz) {
  FccFrame frame = fcc_locate(clamp(xyz, vec3(cell), vec3(cell + 1)));
  return fcc_gradient(gatherStencil(frame), frame);
}
#endif
#endif
