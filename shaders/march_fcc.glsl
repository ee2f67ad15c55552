// The FCC lattice's six-direction box spline for raycast.comp: its value, and DVR through the (up to
// five) tetrahedral pieces a ray crosses in a unit cell. The isosurface's cell work (the cubic along
// the ray in each piece whose BB-coefficients straddle the isovalue, solved exactly by sparse/FccRay.h)
// is written into raycast.comp's marchBrick, where the compiler keeps it fast.

#include "FccRay.h"
#include "FccChord.h"

float valueAt(vec3 xyz) {
  FccFrame frame = fcc_locate(xyz);
  return fcc_value(gatherStencil(frame), frame);
}

#if FCC_MODE_DVR
#ifndef FCC_DVR_ONE_FETCH
#define FCC_DVR_ONE_FETCH 0
#endif
// 1: every piece a ray crosses is gathered, the central one too, and sub-stepped by itself
// (RenderOptions::dvrGatherCentral: the reference the tests compare integrateCell's chord with).
#ifndef FCC_DVR_GATHER_CENTRAL
#define FCC_DVR_GATHER_CENTRAL 0
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

// Emission-absorption through unit cell `cell` between t0 and t1 (dvr.glsl) with both end pieces
// gathered (session 18's way: the walk through the pyramid's, and integrateCell's for a chord that
// starts or ends inside the central piece); true once the ray is opaque enough to stop.
//
// A unit cell's five pieces are four corner pieces and a central one whose faces are fcc_cell_splits'
// planes, so a chord crosses the central piece's faces twice (corner, central, corner piece), once (it
// starts or ends inside the central piece) or not at all (fcc_chord_knots: where it leaves its first
// piece and enters its last; extra crossings from rounding near the chord's ends not counted). The piece at each end is
// gathered; the central stretch between them is not: the spline is C1 across the central piece's
// faces, so its cubic along the ray is the Hermite interpolant of the end pieces' values and slopes
// there (sparse/FccRay.h, fcc_central_bernstein; docs/DVR.md), exact as gathering it would be. The
// chord is then one segment for the sub-step rule (dvrChord3: its pieces' union hull, its whole
// length). Two gathers and one sub-step loop a cell, whatever the chord, so the rays of a warp run one
// walk.
bool integrateCellPieces(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  dvrBeginCell(cell, o, d);
  vec4 splits = fcc_cell_splits(cell, o, d, t0, t1);
#if FCC_DVR_GATHER_CENTRAL
  // The reference (RenderOptions::dvrGatherCentral): every piece gathered and sub-stepped by itself.
  float s0 = t0;
  for (int k = 0; k < 5 && s0 < t1; ++k) {
    float s1 = k == 0 ? splits.x : (k == 1 ? splits.y : (k == 2 ? splits.z : (k == 3 ? splits.w : t1)));
    if (s1 <= s0) continue;
    if (dvrSegment3(pieceSegment(cell, o, d, s0, s1).b, s0, s1, st)) return true;
    s0 = s1;
  }
  return false;
#else
  // ta, tb: the central stretch (one crossing: ta = tb, none; no crossing: ta = tb = t1, one piece;
  // crossings a rounding's width from the chord's ends not counted).
  vec2 knots = fcc_chord_knots(splits, t0, t1);
  float ta = knots.x, tb = knots.y;
  bool twoPieces = tb < t1;
  FccSegment entry, exit;
  for (int g = 0; g < 2; ++g) {  // one gather in the code: a warp's rays share it
    if (g == 1 && !twoPieces) break;
    FccSegment piece = pieceSegment(cell, o, d, g == 0 ? t0 : tb, g == 0 ? ta : t1);
    if (g == 0) entry = piece;
    else exit = piece;
  }
  if (!twoPieces) exit = entry;
  vec4 central = twoPieces ? fcc_central_bernstein(entry, exit, ta, tb) : entry.b;
  return dvrChord3(entry.b, central, exit.b, t0, ta, tb, t1, st);
#endif
}

// 0: every cell gathers both its end pieces (integrateCellPieces, session 18), a measurement knob;
// 1: one gather a cell along a chain of cells (integrateCell below).
#ifndef FCC_DVR_CHAIN
#define FCC_DVR_CHAIN 1
#endif

// Measurement knob (wrong images): 1 the chain without the face jump, 2 without rounds that gather an
// entry piece alone (the exit piece taken for it), 3 without memory reads for the pieces, 4 without
// integrateCellPieces for chords with an end in the central piece (the deepest corner piece taken:
// wrong for rays that start or stop there).
#ifndef FCC_DVR_CHAIN_PROBE
#define FCC_DVR_CHAIN_PROBE 0
#endif
// The chain is taken in raycast.comp's flat walk only (FCC_DVR_FLAT): walking a brick to its end
// (levels of detail, FCC_DVR_FLAT_WALK=0), the rounds that gather a chain's first entry piece keep the
// warp's other rays waiting, and two gathers a cell ran faster (docs/BENCHMARKS.md, session 19:
// blobs 2048^3 through the pyramid 93 fps against 78).
#if FCC_DVR_CHAIN && !FCC_DVR_GATHER_CENTRAL && FCC_DVR_FLAT
// Whether the exit piece `exitPiece` of `cell`, which the ray leaves through the face normal to axis a,
// carries into the next cell: its FCC site lies on that face (rounding at a face diagonal can pick the
// other triangle's) and the face is inside the brick (nothing carries into the next brick).
bool dvrCarriesAcross(ivec3 cell, FccFrame exitPiece, int a, float da) {
  int face = (a == 0 ? cell.x : (a == 1 ? cell.y : cell.z)) + (da > 0.0 ? 1 : 0);
  int faceInBrick = face - (a == 0 ? gDvrBrickCellLo.x : (a == 1 ? gDvrBrickCellLo.y : gDvrBrickCellLo.z));
  int siteOnAxis = a == 0 ? exitPiece.origin.x : (a == 1 ? exitPiece.origin.y : exitPiece.origin.z);
  return siteOnAxis == face && faceInBrick > 0 && faceInBrick < 16;
}

// A cell's chord from its entry and exit pieces in Taylor form (about t0 and t1): its three stretches'
// Bernstein coefficients (the central one the Hermite interpolant) through dvrChord3.
bool dvrChordFromEnds(vec4 entry, vec4 exitPiece, FccCellChord chord, float t0, float t1, inout DvrState st) {
  float ta = chord.ta, tb = chord.tb;
  vec4 bEntry = fcc_taylor_bernstein(entry, 0.0, ta - t0);
  vec4 bExit = fcc_taylor_bernstein(exitPiece, tb - t1, 0.0);
  vec4 central = fcc_hermite_bernstein(bEntry.w, fcc_taylor_slope(entry, ta - t0), bExit.x,
                                       fcc_taylor_slope(exitPiece, tb - t1), ta, tb);
  return dvrChord3(bEntry, central, bExit, t0, ta, tb, t1, st);
}

// Emission-absorption through unit cell `cell` between t0 and t1 with one gather (docs/DVR.md, "One
// gather a cell"): the chord's end pieces are corner pieces (fcc_cell_chord), its central stretch their
// Hermite interpolant, and where the walk integrated the cell before this one, this cell's entry piece
// is that cell's exit piece plus the jump across the face between them (FccChord.h: from the exit
// piece's stencil and one more coefficient), so only the exit piece is gathered. Where it did not (the
// first cell of a brick, or after cells the transfer function maps to zero), this round gathers the
// entry piece alone and the walk's next round comes back to the cell for the exit piece (gDvrCarry,
// kDvrCarryEntry): every round gathers one piece, the same code for all the rays of a warp. A chord
// with an end inside the central piece (a ray that starts or stops inside the cell) takes
// integrateCellPieces.
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  FccCellChord chord = fcc_cell_chord(cell, o, d, t0, t1);
  DvrCarry carry = gDvrCarry;
  gDvrCarry.state = kDvrCarryNone;
#if FCC_DVR_CHAIN_PROBE != 4
  if (chord.corners == 0) return integrateCellPieces(cell, o, d, t0, t1, st);
#endif
  dvrBeginCell(cell, o, d);
  bool known = carry.state != kDvrCarryNone;
  bool onePiece = chord.ta >= t1;
  bool prepare = !known && !onePiece && FCC_DVR_CHAIN_PROBE != 2;
  FccFrame frame = prepare ? chord.entry : chord.exit;
  // Decided before the gather, so that the face jump's one coefficient beyond the face (FccChord.h)
  // is read with the stencil.
  int a = gDvrExitAxis;
  float da = a == 0 ? d.x : (a == 1 ? d.y : d.z);
  bool carries = !prepare && dvrCarriesAcross(cell, chord.exit, a, da);
#if FCC_DVR_CHAIN_PROBE == 3
  // No memory read (wrong images): values spread over the cell's bounds (which the walk read), made
  // to vary with the corner so that the compiler cannot fold the arithmetic away.
  FccSamples samples;
  float wiggle = float((frame.origin.x + 3 * frame.origin.y + 7 * frame.origin.z) & 15) * (1.0 / 16.0);
  for (int i = 0; i < 19; ++i) samples.v[i] = mix(gDvrCellBounds.x, gDvrCellBounds.y, fract(wiggle + float(i) * 0.37));
  float beyond = gDvrCellBounds.x;
#else
#if FCC_DVR_CLOCK == 2
  dvrClock(0, st);
#endif
  FccSamples samples = gatherStencil(frame);
  // Read inside the slot whatever (the piece's corner where the face does not carry).
  float beyond = coefficientAt(carries ? fcc_face_jump_beyond_site(frame, a) : frame.origin);
#if FCC_DVR_CLOCK == 2
  // A branch on all 20 values: the stamp waits for the last of them. Constant indices, as pool.glsl's
  // gatherStencil has them: a loop's dynamic index may put the array in local memory.
  float arrived = beyond + samples.v[0] + samples.v[1] + samples.v[2] + samples.v[3] + samples.v[4] + samples.v[5] +
                  samples.v[6] + samples.v[7] + samples.v[8] + samples.v[9] + samples.v[10] + samples.v[11] +
                  samples.v[12] + samples.v[13] + samples.v[14] + samples.v[15] + samples.v[16] + samples.v[17] +
                  samples.v[18];
  if (!(arrived == uStopTransmittance * -1e30)) dvrClock(1, st);
#endif
#endif
  vec4 gathered = fcc_piece_taylor(fcc_cubic_t0(samples), frame, o, d, prepare ? t0 : t1);
#if FCC_DVR_CLOCK == 1
  // The stamp waits for the piece (a branch on it), not only for the instructions before it to issue.
  if (!(gathered.x == uStopTransmittance * -1e30)) dvrClock(1, st);
#endif
  if (prepare) {
    gDvrCarry = DvrCarry(gathered, kDvrCarryEntry);
    return false;
  }
  // The entry piece: carried (across the face, the jump is already in its cubic term; about t0), or
  // for a chord in one piece the gathered exit piece itself.
  vec4 entry = known && !onePiece ? carry.taylor : fcc_taylor_shift(gathered, t0 - t1);
  if (carries) {
    // The next cell's entry piece: this exit piece about t1 plus the face jump.
    vec4 next = gathered;
    if (FCC_DVR_CHAIN_PROBE != 1) next.w += fcc_face_jump_lambda(samples, a, beyond) * abs(da) * da * da;
    gDvrCarry = DvrCarry(next, kDvrCarryExit);
  }
  return dvrChordFromEnds(entry, gathered, chord, t0, t1, st);
}

#else
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  return integrateCellPieces(cell, o, d, t0, t1, st);
}
#endif

#if FCC_DVR_SHADING
// The box spline's gradient at xyz (the piece there: the spline is C2, so a rounding across a piece
// boundary changes nothing that matters).
vec3 dvrGradient(ivec3 cell, vec3 xyz) {
  FccFrame frame = fcc_locate(clamp(xyz, vec3(cell), vec3(cell + 1)));
  return fcc_gradient(gatherStencil(frame), frame);
}
#endif
#endif
