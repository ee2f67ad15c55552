// FccRay.h — exact ray/isosurface intersection for the FCC spline, in the three dialects of
// FccSpline.h (include that first). Along a ray segment inside one tetrahedral piece the spline is a
// cubic in the ray parameter; its first root is found exactly (to float precision) by splitting the
// segment at the cubic's critical points into monotone parts and bisecting the first part whose ends
// differ in sign. No fixed step: no thin feature is stepped over.
//
// Ray: xyz(t) = o + t * d in the lattice's index space. A unit cell [c, c+1]^3 is cut into its five
// pieces by four planes; fcc_cell_splits gives the parameters where the ray crosses them.
#ifndef FCC_RAY_H
#define FCC_RAY_H

FCC_NAMESPACE_BEGIN

// Bernstein coefficients on u in [0, 1] of s(o + (s0 + u (s1 - s0)) d) - iso, where the segment lies
// in the piece `frame` whose scaled BB-coefficients are `cubic`. They are the cubic's blossom at the
// segment's ends a and b: B(a,a,a), B(a,a,b), B(a,b,b), B(b,b,b), one de Casteljau step per argument
// (144 multiplications, against 240 for values at four points, and no conversion from values). The
// spline is a polynomial on the piece, so ends a rounding past its faces are harmless.
FCC_FUNC FCC_VEC4 fcc_segment_bernstein(FccCubic cubic, FccFrame frame, FCC_VEC3 o, FCC_VEC3 d, float s0,
                                        float s1, float iso) {
  FCC_VEC3 axis = FCC_VEC3_FROM_IVEC3(frame.axis);
  FCC_VEC3 qa = axis * (o + s0 * d - FCC_VEC3_FROM_IVEC3(frame.origin));
  FCC_VEC3 qb = qa + axis * d * (s1 - s0);
  FCC_VEC4 la = fcc_barycentric(qa, frame.type), lb = fcc_barycentric(qb, frame.type);
  FccQuadratic ca = fcc_decasteljau_step3(cubic, la), cb = fcc_decasteljau_step3(cubic, lb);
  FCC_VEC4 caa = fcc_decasteljau_step2(ca, la), cab = fcc_decasteljau_step2(ca, lb), cbb = fcc_decasteljau_step2(cb, lb);
  float k = 1.0f / FCC_CUBIC_DENOM;
  return FCC_MAKE_VEC4((la.x * caa.x + la.y * caa.y + la.z * caa.z + la.w * caa.w) * k - iso,
                       (lb.x * caa.x + lb.y * caa.y + lb.z * caa.z + lb.w * caa.w) * k - iso,
                       (lb.x * cab.x + lb.y * cab.y + lb.z * cab.z + lb.w * cab.w) * k - iso,
                       (lb.x * cbb.x + lb.y * cbb.y + lb.z * cbb.z + lb.w * cbb.w) * k - iso);
}

// The rate of fcc_barycentric's coordinates per unit displacement v of q (its linear part).
FCC_FUNC FCC_VEC4 fcc_barycentric_rate(FCC_VEC3 v, int type) {
  if (type == 0) return FCC_MAKE_VEC4(-(v.x + v.y + v.z), v.x, v.y, v.z);
  float r3 = 0.5f * (v.x + v.y + v.z);
  return FCC_MAKE_VEC4(v.x - r3, v.y - r3, v.z - r3, r3);
}

// fcc_segment_bernstein's coefficients (iso 0) and the cubic's slopes per unit t at the segment's
// ends, slope0 at s0 and slope1 at s1: 3 B(a,a,r) and 3 B(b,b,r), r the barycentric rate along d, from
// the blossoms the coefficients already need (a dot product each; no division by the segment's length,
// so a short segment's slopes are as exact as a long one's).
FCC_STRUCT_BEGIN(FccSegment)
  FCC_VEC4 b;
  float slope0;
  float slope1;
FCC_STRUCT_END(FccSegment)

FCC_FUNC FccSegment fcc_segment_with_slopes(FccCubic cubic, FccFrame frame, FCC_VEC3 o, FCC_VEC3 d, float s0,
                                            float s1) {
  FCC_VEC3 axis = FCC_VEC3_FROM_IVEC3(frame.axis);
  FCC_VEC3 qa = axis * (o + s0 * d - FCC_VEC3_FROM_IVEC3(frame.origin));
  FCC_VEC3 qb = qa + axis * d * (s1 - s0);
  FCC_VEC4 la = fcc_barycentric(qa, frame.type), lb = fcc_barycentric(qb, frame.type);
  FCC_VEC4 r = fcc_barycentric_rate(axis * d, frame.type);
  FccQuadratic ca = fcc_decasteljau_step3(cubic, la), cb = fcc_decasteljau_step3(cubic, lb);
  FCC_VEC4 caa = fcc_decasteljau_step2(ca, la), cab = fcc_decasteljau_step2(ca, lb), cbb = fcc_decasteljau_step2(cb, lb);
  float k = 1.0f / FCC_CUBIC_DENOM;
  FccSegment seg;
  seg.b = FCC_MAKE_VEC4((la.x * caa.x + la.y * caa.y + la.z * caa.z + la.w * caa.w) * k,
                        (lb.x * caa.x + lb.y * caa.y + lb.z * caa.z + lb.w * caa.w) * k,
                        (lb.x * cab.x + lb.y * cab.y + lb.z * cab.z + lb.w * cab.w) * k,
                        (lb.x * cbb.x + lb.y * cbb.y + lb.z * cbb.z + lb.w * cbb.w) * k);
  seg.slope0 = 3.0f * (r.x * caa.x + r.y * caa.y + r.z * caa.z + r.w * caa.w) * k;
  seg.slope1 = 3.0f * (r.x * cbb.x + r.y * cbb.y + r.z * cbb.z + r.w * cbb.w) * k;
  return seg;
}

// The central piece's segment [ta, tb] of a chord that crosses it, without its stencil (docs/DVR.md,
// "A cell's chord from its end pieces"): across the central piece's faces the spline is C1 (their
// planes hold three of the six directions; across the cube's faces, which hold two, it is C2), so
// along the ray the central piece's cubic has the entry piece's value and slope at ta and the exit
// piece's at tb, and a cubic is its Hermite interpolant. `entry` is the entry piece's segment ending at
// ta, `exit` the exit piece's starting at tb (fcc_segment_with_slopes). fcc_hermite_bernstein: the
// cubic on [ta, tb] with value v0 and slope0 (per unit t) at ta, v1 and slope1 at tb.
FCC_FUNC FCC_VEC4 fcc_hermite_bernstein(float v0, float slope0, float v1, float slope1, float ta, float tb) {
  float h3 = (tb - ta) * (1.0f / 3.0f);
  return FCC_MAKE_VEC4(v0, v0 + h3 * slope0, v1 - h3 * slope1, v1);
}
FCC_FUNC FCC_VEC4 fcc_central_bernstein(FccSegment entry, FccSegment exit, float ta, float tb) {
  return fcc_hermite_bernstein(entry.b.w, entry.slope1, exit.b.x, exit.slope0, ta, tb);
}

// Where a unit cell's chord [t0, t1] leaves its first piece and enters its last, from fcc_cell_splits'
// sorted crossings: (ta, tb), the first and the last crossing. The planes are the central piece's
// faces, so a chord crosses two of them (ta < tb: corner, central, corner piece), one (ta = tb: it
// starts or ends inside the central piece) or none (ta = tb = t1: one piece). Rounding adds crossings
// where a ray enters or leaves the cell near a face diagonal (the central piece's edges): a plane the
// ray crosses just outside the cell is found just inside, far more often the farther the ray's origin
// (tests/sparse/test_ray.cpp). So crossings within FCC_CHORD_END_GAP of the chord's length from either
// end are not counted: the stretch between such a crossing and the end is then taken as part of its
// neighbour, whose cubic continues the spline's value and slope across it (C1), off by the curvature
// jump times the stretch squared, a millionth of a cell's; and what is left is at most two crossings.
#define FCC_CHORD_END_GAP 1e-3f
FCC_FUNC FCC_VEC2 fcc_chord_knots(FCC_VEC4 splits, float t0, float t1) {
  float gap = FCC_CHORD_END_GAP * (t1 - t0), lo = t0 + gap, hi = t1 - gap;
  float first = t1, last = t1;
  if (splits.w > lo && splits.w < hi) first = splits.w;
  if (splits.z > lo && splits.z < hi) first = splits.z;
  if (splits.y > lo && splits.y < hi) first = splits.y;
  if (splits.x > lo && splits.x < hi) first = splits.x;
  if (splits.x > lo && splits.x < hi) last = splits.x;
  if (splits.y > lo && splits.y < hi) last = splits.y;
  if (splits.z > lo && splits.z < hi) last = splits.z;
  if (splits.w > lo && splits.w < hi) last = splits.w;
  return FCC_MAKE_VEC2(first, last);
}

// The parameters in (ta, tb) where the ray crosses the four planes that cut the unit cell at integer
// corner `cell` into its pieces, sorted; entries past the last crossing are tb.
// The four planes n . p = 1 that cut unit cell `cell` into its pieces, n = (1,1,1), (1,1,-1),
// (1,-1,1), (-1,1,1), along the ray: n . p = at + t rate, p the even-cube coordinates (an odd cell is
// the point reflection of an even one, p -> 1 - p).
FCC_STRUCT_BEGIN(FccCellPlanes)
  FCC_VEC4 at;
  FCC_VEC4 rate;
FCC_STRUCT_END(FccCellPlanes)

FCC_FUNC FccCellPlanes fcc_cell_planes(FCC_IVEC3 cell, FCC_VEC3 o, FCC_VEC3 d) {
  FCC_VEC3 p = o - FCC_VEC3_FROM_IVEC3(cell);
  FCC_VEC3 dir = d;
  if (((cell.x + cell.y + cell.z) & 1) != 0) {
    p = FCC_MAKE_VEC3(1.0f, 1.0f, 1.0f) - p;
    dir = -d;
  }
  FccCellPlanes planes;
  planes.at = FCC_MAKE_VEC4(p.x + p.y + p.z, p.x + p.y - p.z, p.x - p.y + p.z, -p.x + p.y + p.z);
  planes.rate = FCC_MAKE_VEC4(dir.x + dir.y + dir.z, dir.x + dir.y - dir.z, dir.x - dir.y + dir.z, -dir.x + dir.y + dir.z);
  return planes;
}

FCC_FUNC FCC_VEC4 fcc_cell_splits(FCC_IVEC3 cell, FCC_VEC3 o, FCC_VEC3 d, float ta, float tb) {
  FccCellPlanes planes = fcc_cell_planes(cell, o, d);
  FCC_VEC4 np = planes.at, nd = planes.rate;
  FCC_VEC4 s = FCC_MAKE_VEC4(tb, tb, tb, tb);
  float t;
  t = nd.x != 0.0f ? (1.0f - np.x) / nd.x : tb;
  s.x = (t > ta && t < tb) ? t : tb;
  t = nd.y != 0.0f ? (1.0f - np.y) / nd.y : tb;
  s.y = (t > ta && t < tb) ? t : tb;
  t = nd.z != 0.0f ? (1.0f - np.z) / nd.z : tb;
  s.z = (t > ta && t < tb) ? t : tb;
  t = nd.w != 0.0f ? (1.0f - np.w) / nd.w : tb;
  s.w = (t > ta && t < tb) ? t : tb;
  // Sorting network for four values.
  float lo, hi;
  lo = min(s.x, s.y); hi = max(s.x, s.y); s.x = lo; s.y = hi;
  lo = min(s.z, s.w); hi = max(s.z, s.w); s.z = lo; s.w = hi;
  lo = min(s.x, s.z); hi = max(s.x, s.z); s.x = lo; s.z = hi;
  lo = min(s.y, s.w); hi = max(s.y, s.w); s.y = lo; s.w = hi;
  lo = min(s.y, s.z); hi = max(s.y, s.z); s.y = lo; s.z = hi;
  return s;
}

FCC_NAMESPACE_END

#endif  // FCC_RAY_H
