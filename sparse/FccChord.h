// FccChord.h — the FCC box spline along a ray through a unit cell, for direct volume rendering, in the
// three dialects of FccSpline.h (include that and FccRay.h first; docs/DVR.md, "One gather a cell").
//
// A unit cell's five pieces are four corner pieces, one at each of the cube's FCC sites, and a central
// one. A chord entering the cell through a face enters a corner piece (a face is two triangles, each
// a corner piece's face) and leaves through a corner piece; between them, if they differ, it crosses
// the central piece, whose cubic along the ray is the Hermite interpolant of its neighbours' values
// and slopes there (the spline is C1 across the central piece's faces: FccRay.h,
// fcc_central_bernstein). So the chord needs its two end pieces.
//
// Across a cube face (a plane x_a = f that holds two of the six directions) the spline is C2, and the
// two pieces that share a face triangle differ by a multiple of (x_a - f)^3:
//   s(plus side) - s(minus side) = lambda (x_a - f)^3,   lambda = -(1/6) Nabla_Y c(e + off_a),
// where e is the triangle's FCC site (the corner both pieces have there), Y the four directions with a
// non-zero a-component, Nabla_Y their forward difference of the coefficients (16 terms, 15 sites),
// off_x = (-1, 0, -1) and the other axes' by cyclic rotation (found and checked against the pieces'
// BB-forms: tests/sparse/test_chord.cpp). Along a ray crossing the face at t_f the next cell's entry
// piece is therefore the last cell's exit piece plus lambda |d_a|^3 (t - t_f)^3; 14 of lambda's 15
// sites are in the exit piece's stencil, so it costs one more coefficient instead of a piece's 19 and
// its BB-form.
//
// Cubics along the ray are kept in Taylor form about a parameter ts, c.x + c.y tau + c.z tau^2 +
// c.w tau^3 with tau = t - ts (per unit of t), computed from a piece's blossom with the ray's
// barycentric rate (no division by a segment's length, so short segments are as exact as long ones).
#ifndef FCC_CHORD_H
#define FCC_CHORD_H

FCC_NAMESPACE_BEGIN

// A unit cell's chord [t0, t1] by its end pieces: `entry` is the corner piece holding the chord's start,
// `exit` the one holding its end; the chord leaves entry's piece at ta and enters exit's at tb (t0 <=
// ta <= tb <= t1; ta = tb = t1 when entry and exit are one piece). `corners` is 0 where an end lies in
// the central piece (a ray that starts or stops inside a cell): the caller then takes the pieces the
// general way (fcc_cell_splits).
FCC_STRUCT_BEGIN(FccCellChord)
  FccFrame entry;
  FccFrame exit;
  float ta;
  float tb;
  int corners;
FCC_STRUCT_END(FccCellChord)

// How far past a corner piece's plane an end may lie (rounding) and still be taken in that piece: the
// cubic continues the central piece's value and slope across the plane (C1), off by its curvature jump
// times the distance squared.
#define FCC_CHORD_CORNER_SLACK 1e-4f

// Corner piece k (0..3) of the even unit cube: its FCC corner (offset) and its frame's reflection.
FCC_FUNC FCC_IVEC3 fcc_corner_offset(int k) {
  return k == 0 ? FCC_MAKE_IVEC3(0, 0, 0)
                : (k == 1 ? FCC_MAKE_IVEC3(1, 1, 0) : (k == 2 ? FCC_MAKE_IVEC3(1, 0, 1) : FCC_MAKE_IVEC3(0, 1, 1)));
}
FCC_FUNC FCC_IVEC3 fcc_corner_flip(int k) {
  return k == 0 ? FCC_MAKE_IVEC3(1, 1, 1)
                : (k == 1 ? FCC_MAKE_IVEC3(-1, -1, 1) : (k == 2 ? FCC_MAKE_IVEC3(-1, 1, -1) : FCC_MAKE_IVEC3(1, -1, -1)));
}

// The corner piece whose depth (how far inside its plane a point lies; depths: the four pieces') is the
// largest.
FCC_FUNC int fcc_deepest_corner(FCC_VEC4 depth) {
  int k = 0;
  float best = depth.x;
  if (depth.y > best) { k = 1; best = depth.y; }
  if (depth.z > best) { k = 2; best = depth.z; }
  if (depth.w > best) k = 3;
  return k;
}

FCC_FUNC float fcc_vec4_at(FCC_VEC4 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : (k == 2 ? v.z : v.w)); }

// The frame of corner piece k of a cell whose even-cube corner is `corner` and reflection `axis`
// (fcc_locate's, for a point of that piece; q is left at the piece's corner).
FCC_FUNC FccFrame fcc_corner_frame(FCC_IVEC3 corner, FCC_IVEC3 axis, int k) {
  FccFrame frame;
  frame.origin = corner + axis * fcc_corner_offset(k);
  frame.axis = axis * fcc_corner_flip(k);
  frame.q = FCC_MAKE_VEC3(0.0f, 0.0f, 0.0f);
  frame.type = 0;
  return frame;
}

FCC_FUNC FccCellChord fcc_cell_chord(FCC_IVEC3 cell, FCC_VEC3 o, FCC_VEC3 d, float t0, float t1) {
  // The even cube's frame (an odd cell is the point reflection of an even one: its far corner).
  bool odd = ((cell.x + cell.y + cell.z) & 1) != 0;
  FCC_IVEC3 corner = odd ? cell + FCC_MAKE_IVEC3(1, 1, 1) : cell;
  FCC_IVEC3 axis = odd ? FCC_MAKE_IVEC3(-1, -1, -1) : FCC_MAKE_IVEC3(1, 1, 1);
  // Depth in corner piece k: 1 - (1,1,1).p for k = 0, n_k.p - 1 for the other three planes
  // (fcc_cell_planes); linear along the ray: depth(t) = base + t rate.
  FccCellPlanes planes = fcc_cell_planes(cell, o, d);
  FCC_VEC4 base = FCC_MAKE_VEC4(1.0f - planes.at.x, planes.at.y - 1.0f, planes.at.z - 1.0f, planes.at.w - 1.0f);
  FCC_VEC4 rate = FCC_MAKE_VEC4(-planes.rate.x, planes.rate.y, planes.rate.z, planes.rate.w);
  FCC_VEC4 depth0 = base + t0 * rate, depth1 = base + t1 * rate;
  int kEntry = fcc_deepest_corner(depth0), kExit = fcc_deepest_corner(depth1);
  FccCellChord chord;
  chord.entry = fcc_corner_frame(corner, axis, kEntry);
  chord.exit = fcc_corner_frame(corner, axis, kExit);
  chord.corners = (fcc_vec4_at(depth0, kEntry) >= -FCC_CHORD_CORNER_SLACK &&
                   fcc_vec4_at(depth1, kExit) >= -FCC_CHORD_CORNER_SLACK) ? 1 : 0;
  // Where the entry piece's depth falls to 0 (if it falls) and the exit piece's rises from 0.
  float rEntry = fcc_vec4_at(rate, kEntry), rExit = fcc_vec4_at(rate, kExit);
  float ta = rEntry < 0.0f ? -fcc_vec4_at(base, kEntry) / rEntry : t1;
  float tb = rExit > 0.0f ? -fcc_vec4_at(base, kExit) / rExit : t0;
  ta = min(max(ta, t0), t1);
  tb = min(max(tb, t0), t1);
  if (kEntry == kExit) {
    ta = t1;
    tb = t1;
  } else if (ta > tb) {  // a ray grazing the central piece's edge: rounding crossed the planes
    ta = 0.5f * (ta + tb);
    tb = ta;
  }
  chord.ta = ta;
  chord.tb = tb;
  return chord;
}

// The cubic of piece `frame` (BB-coefficients `cubic`) along the ray, in Taylor form about ts: its
// blossom B(a,a,a), 3 B(a,a,r), 3 B(a,r,r), B(r,r,r) at the point a = o + ts d and the barycentric rate r
// of d. The piece is a polynomial: ts may lie a rounding outside it.
FCC_FUNC FCC_VEC4 fcc_piece_taylor(FccCubic cubic, FccFrame frame, FCC_VEC3 o, FCC_VEC3 d, float ts) {
  FCC_VEC3 axis = FCC_VEC3_FROM_IVEC3(frame.axis);
  FCC_VEC4 la = fcc_barycentric(axis * (o + ts * d - FCC_VEC3_FROM_IVEC3(frame.origin)), frame.type);
  FCC_VEC4 r = fcc_barycentric_rate(axis * d, frame.type);
  FccQuadratic ca = fcc_decasteljau_step3(cubic, la), cr = fcc_decasteljau_step3(cubic, r);
  FCC_VEC4 caa = fcc_decasteljau_step2(ca, la), cra = fcc_decasteljau_step2(cr, la), crr = fcc_decasteljau_step2(cr, r);
  float k = 1.0f / FCC_CUBIC_DENOM;
  return FCC_MAKE_VEC4((la.x * caa.x + la.y * caa.y + la.z * caa.z + la.w * caa.w) * k,
                       3.0f * (r.x * caa.x + r.y * caa.y + r.z * caa.z + r.w * caa.w) * k,
                       3.0f * (r.x * cra.x + r.y * cra.y + r.z * cra.z + r.w * cra.w) * k,
                       (r.x * crr.x + r.y * crr.y + r.z * crr.z + r.w * crr.w) * k);
}

// Taylor form c about ts, moved to ts + delta.
FCC_FUNC FCC_VEC4 fcc_taylor_shift(FCC_VEC4 c, float delta) {
  return FCC_MAKE_VEC4(c.x + delta * (c.y + delta * (c.z + delta * c.w)), c.y + delta * (2.0f * c.z + 3.0f * delta * c.w),
                       c.z + 3.0f * delta * c.w, c.w);
}

// The slope (per unit t) of Taylor form c at tau.
FCC_FUNC float fcc_taylor_slope(FCC_VEC4 c, float tau) { return c.y + tau * (2.0f * c.z + 3.0f * tau * c.w); }

// Bernstein coefficients on tau in [alpha, beta] of Taylor form c: its blossom
// P(x, y, z) = c0 + c1 (x + y + z) / 3 + c2 (xy + yz + zx) / 3 + c3 xyz at (a,a,a), (a,a,b), (a,b,b), (b,b,b).
FCC_FUNC FCC_VEC4 fcc_taylor_bernstein(FCC_VEC4 c, float alpha, float beta) {
  float a = alpha, b = beta, third = 1.0f / 3.0f;
  return FCC_MAKE_VEC4(c.x + a * (c.y + a * (c.z + a * c.w)),
                       c.x + c.y * (2.0f * a + b) * third + c.z * (a * a + 2.0f * a * b) * third + c.w * a * a * b,
                       c.x + c.y * (a + 2.0f * b) * third + c.z * (2.0f * a * b + b * b) * third + c.w * a * b * b,
                       c.x + b * (c.y + b * (c.z + b * c.w)));
}

// The face jump's sum D = Nabla_Y c(e + off_a) from the 19 coefficients of a corner piece whose corner
// e lies on the face, normal to `axis` (0, 1, 2; the frame's axes are reflections, so the canonical
// axis is the world's), and the one coefficient it lacks. D's 15 sites are e, the twelve FCC
// neighbours of e and e +- 2 along the axis (symmetric under the reflections, so either side's piece
// gives the same D): weight +1 on the eight neighbours off the face's plane, -1 on the four in it, -1
// on e +- 2 along the axis, -2 on e. The stencil holds e (sample 0), the twelve neighbours (samples
// 5-8 in the plane x = 0, 10-13 in y = 0, 15-18 in z = 0) and e + 2 along the axis into the piece
// (sample 1, 2 or 3); e - 2 along it, the side away from the piece, is `beyond`
// (fcc_face_jump_beyond_site). lambda = -D / 6.
FCC_FUNC float fcc_face_jump_lambda(FccSamples s, int axis, float beyond) {
  float inX = s.v[5] + s.v[6] + s.v[7] + s.v[8], inY = s.v[10] + s.v[11] + s.v[12] + s.v[13];
  float inZ = s.v[15] + s.v[16] + s.v[17] + s.v[18];
  float inPlane = axis == 0 ? inX : (axis == 1 ? inY : inZ);
  float along = axis == 0 ? s.v[1] : (axis == 1 ? s.v[2] : s.v[3]);
  float d = (inX + inY + inZ) - 2.0f * inPlane - along - beyond - 2.0f * s.v[0];
  return (-1.0f / 6.0f) * d;
}

// The site fcc_face_jump_lambda's `beyond` is read at: the piece's corner minus twice its frame's
// axis along `axis`.
FCC_FUNC FCC_IVEC3 fcc_face_jump_beyond_site(FccFrame frame, int axis) {
  return frame.origin - 2 * FCC_MAKE_IVEC3(axis == 0 ? frame.axis.x : 0, axis == 1 ? frame.axis.y : 0,
                                           axis == 2 ? frame.axis.z : 0);
}

FCC_NAMESPACE_END

#endif  // FCC_CHORD_H
