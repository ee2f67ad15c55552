// The FCC lattice's six-direction box spline for raycast.comp: the (up to five) tetrahedral pieces a
// ray crosses in a unit cell, and in each piece whose BB-coefficients straddle the isovalue the cubic
// along the ray, solved exactly (sparse/FccRay.h).

float valueAt(vec3 xyz) {
  FccFrame frame = fcc_locate(xyz);
  return fcc_value(gatherStencil(frame), frame);
}

// The first hit in unit cell `cell` of brick b between t0 and t1 (the slot is selected).
bool hitInCell(ivec3 b, ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout int prevSign, inout Hit hit) {
  vec4 splits = fcc_cell_splits(cell, o, d, t0, t1);
  float s0 = t0;
  // Up to five sub-segments, one per piece the ray passes (in practice at most three).
  for (int k = 0; k < 5 && s0 < t1; ++k) {
    float s1 = k == 0 ? splits.x : (k == 1 ? splits.y : (k == 2 ? splits.z : (k == 3 ? splits.w : t1)));
    if (s1 <= s0) continue;
    // Kept inside this cell, so the stencil stays inside the slot's halo whatever the rounding.
    FccFrame frame = fcc_locate(clamp(o + (0.5 * (s0 + s1)) * d, vec3(cell), vec3(cell + 1)));
    FccSamples samples = gatherStencil(frame);
    FccCubic cubic = fcc_cubic(samples, frame.type);
    FccRange range = fcc_cubic_range(cubic);
    if (!(range.lo <= uIso && uIso <= range.hi)) {
      prevSign = range.lo > uIso ? 1 : -1;
    } else {
      vec4 bz = fcc_segment_bernstein(cubic, frame, o, d, s0, s1, uIso);
      float u = fcc_first_root_after(bz, prevSign);
      prevSign = bz.w < 0.0 ? -1 : 1;
      if (u >= 0.0) {
        hit.t = s0 + u * (s1 - s0);
        vec3 xyz = o + hit.t * d;
        if (uFiniteDifferenceNormals != 0) {
          hit.gradient = finiteDifferenceGradient(xyz, b);
        } else {
          // The gradient of this piece's polynomial at the hit, with the stencil already read:
          // locating the rounded hit point anew could pick a cell outside the slot's halo.
          frame.q = vec3(frame.axis) * (xyz - vec3(frame.origin));
          hit.gradient = fcc_gradient(samples, frame);
        }
        return true;
      }
    }
    s0 = s1;
  }
  return false;
}

#if FCC_MODE_DVR
// Emission-absorption through unit cell `cell` between t0 and t1 (dvr.glsl), piece by piece; true
// once the ray is opaque enough to stop.
bool integrateCell(ivec3 cell, vec3 o, vec3 d, float t0, float t1, inout DvrState st) {
  vec4 splits = fcc_cell_splits(cell, o, d, t0, t1);
  float s0 = t0;
  for (int k = 0; k < 5 && s0 < t1; ++k) {
    float s1 = k == 0 ? splits.x : (k == 1 ? splits.y : (k == 2 ? splits.z : (k == 3 ? splits.w : t1)));
    if (s1 <= s0) continue;
    FccFrame frame = fcc_locate(clamp(o + (0.5 * (s0 + s1)) * d, vec3(cell), vec3(cell + 1)));
    FccCubic cubic = fcc_cubic(gatherStencil(frame), frame.type);
    FccRange range = fcc_cubic_range(cubic);
    if (!tfZeroOn(range.lo, range.hi) && dvrSegment3(fcc_segment_bernstein(cubic, frame, o, d, s0, s1, 0.0), s0, s1, st))
      return true;
    s0 = s1;
  }
  return false;
}
#endif
