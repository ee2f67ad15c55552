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
// 1: every piece a ray crosses is gathered, the central one too (RenderOptions::dvrGatherCentral: the
// reference the tests compare the shortcut below with). 0: a chord that crosses the central piece
// takes it from its neighbours.
#ifndef FCC_DVR_GATHER_CENTRAL
#define FCC_DVR_GATHER_CENTRAL 0
#endif
#ifndef FCC_DVR_CHORD_STEPS
#define FCC_DVR_CHORD_STEPS 0
#endif

// The piece of `cell` holding the chord's stretch [s0, s1]: its segment and the slopes at its ends.
FccSegment pieceSegment(ivec3 cell, vec3 o, vec3 d, float s0, float s1) {
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
  return fcc_segment_with_slopes(cubic, frame, o, d, s0, s1);
}

// Emission-absorption through unit cell `cell` between t0 and t1 (dvr.glsl), piece by piece; true
// once the ray is opaque enough to stop.
//
// A chord through the central piece (two crossings: corner, central, corner piece) takes two stencils
// instead of three: the spline is C1 across the central piece's faces, so its cubic along the ray is
// the Hermite interpolant of the corner pieces' values and slopes there (sparse/FccRay.h,
// fcc_central_bernstein; docs/DVR.md), exact as gathering it would be. Its iteration gathers the exit
// piece instead (kept for the next), so the loop has one gather and one segment, whatever the chord:
// the rays of a warp do not run two walks one after the other (a separate branch for such chords ran
// llvmpipe 1.6x slower than gathering every piece).
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  dvrBeginCell(cell, o, d);
  vec4 splits = fcc_cell_splits(cell, o, d, t0, t1);
#if FCC_DVR_CHORD_STEPS
  // Measurement knob (docs/RENDERER.md): a chord with at most two crossings as one segment for the
  // sub-step rule (its pieces' union hull, its whole length), each sub-step's midpoint on its piece.
  // The corner pieces [t0, ta] and [tb, t1] gathered (one crossing: ta = tb, no central stretch; none:
  // ta = tb = t1, one piece), the central one from them.
  if (!(splits.z < t1)) {
    float ta = splits.x, tb = splits.y < t1 ? splits.y : ta;
    FccSegment entry, exit;
    for (int g = 0; g < 2; ++g) {
      if (g == 1 && !(tb < t1)) break;
      FccSegment seg = pieceSegment(cell, o, d, g == 0 ? t0 : tb, g == 0 ? ta : t1);
      if (g == 0) entry = seg;
      else exit = seg;
    }
    bool hasExit = tb < t1;
    vec4 middle = hasExit ? fcc_central_bernstein(entry, exit, ta, tb) : entry.b;
    if (!hasExit) exit.b = entry.b;
    return dvrChord3(entry.b, middle, exit.b, t0, ta, tb, t1, st);
  }
#endif
  bool shortcut = FCC_DVR_GATHER_CENTRAL == 0 && splits.y < t1 && !(splits.z < t1);
  FccSegment entry, piece;
  float s0 = t0;
  for (int k = 0; k < 5 && s0 < t1; ++k) {
    float s1 = k == 0 ? splits.x : (k == 1 ? splits.y : (k == 2 ? splits.z : (k == 3 ? splits.w : t1)));
    bool central = shortcut && k == 1;  // gathers the exit piece, even where the central one is empty
    if (s1 <= s0 && !central) continue;
    if (!(shortcut && k == 2)) piece = pieceSegment(cell, o, d, central ? splits.y : s0, central ? t1 : s1);
    if (k == 0) entry = piece;
    // The segment's own hull (dvrSegment3) is within the piece's: no separate check of the piece.
    if (dvrSegment3(central ? fcc_central_bernstein(entry, piece, s0, s1) : piece.b, s0, s1, st)) return true;
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
