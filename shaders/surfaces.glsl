// Several isosurfaces at once, each with its colour and opacity (FCC_MULTI_ISO, raycast.comp): a ray
// finds, piece by piece, the earliest crossing of any surface after where it is (the exact roots of
// the piece's polynomial along the ray, as the single surface's path), shades it with that surface's
// colour, composites it front to back (premultiplied) and goes on from just past it, until the
// transmittance left is below uStopTransmittance. The single opaque surface keeps its own code in
// marchBrick (a called function there ran 8-13% slower on NVIDIA); this variant is compiled only when
// there are several surfaces or a translucent one (viewer/Raycaster.cpp, compositesSurfaces).

uniform int uSurfaceCount;          // 1 to 4
uniform vec4 uSurfaceIsos;
uniform vec4 uSurfaceOpacities;     // in [0, 1]
uniform vec3 uSurfaceColors[4];     // linear
uniform float uStopTransmittance;   // 1 - the opacity at which a ray stops

const int kMaxCrossingsPerPiece = 12;  // a cubic crosses each of 4 surfaces at most 3 times

struct SurfaceState {
  vec3 color;          // premultiplied, accumulated front to back
  float transmittance;
  vec3 normal;         // of the first crossing (world, unit); 0 before it
  float depth;         // of the first crossing; +inf before it
  ivec4 side;          // per surface: -1 the ray is where s < iso, +1 where s >= iso, 0 unknown
};

// The world direction of the pixel's ray (raycast.comp's main sets it): two-sided lighting needs it.
vec3 gDirWorld;

// Shades the crossing of surface k at t (index-space gradient g) as the single surface is shaded and
// composites it. True once the ray is opaque enough to stop.
bool compositeCrossing(int k, float t, vec3 g, inout SurfaceState st) {
  vec3 n = uNormalFromIndex * g;
  float len = length(n);
  n = len > 0.0 ? n / len : -gDirWorld;
  vec3 nFacing = dot(n, gDirWorld) > 0.0 ? -n : n;
  float diffuse = max(dot(nFacing, uLightDir), 0.0);
  vec3 shaded = uSurfaceColors[k] * (0.15 + 0.85 * diffuse);
  float a = uSurfaceOpacities[k];
  st.color += st.transmittance * a * shaded;
  st.transmittance *= 1.0 - a;
  if (isinf(st.depth)) {
    st.depth = t;
    st.normal = n;
  }
  return st.transmittance <= uStopTransmittance;
}

// Which side of the surface a value lies on (zero counts as not below, as the single path's signs).
int sideOf(float v) { return v < 0.0 ? -1 : 1; }

// The first u in [u0, 1] where the cubic with Bernstein coefficients b (on [0, 1]) changes side from
// `side` (the side the ray was on at u0; 0: unknown, then the side at u0), or -1. A side at u0 other
// than `side` is a crossing at u0 (the join rule of fcc_first_root_after). `after` gets the end of the
// bisection's bracket, where the new side is established: the search for the next crossing starts
// there, so a root is never found twice. Monotone pieces between critical points and bisection, as
// fcc_first_root_bernstein3. `tolerance` (joinTolerance): where two pieces join, each piece's own polynomial
// gives the value there, rounded differently; a start within it of the surface on the other side
// than the one carried in is taken on the carried side, not as a crossing (else a surface through the
// join counts twice or three times: on NVIDIA, bright speckles on translucent surfaces).
float nextRoot3(vec4 b, float u0, int side, float tolerance, out float after) {
  after = u0;
  float g0 = u0 == 0.0 ? b.x : fcc_bernstein3(b, u0);
  bool neg = g0 < 0.0;
  if (side != 0 && neg != (side < 0)) {
    if (abs(g0) > tolerance) return u0;
    neg = side < 0;
  }
  if (neg ? max(max(b.x, b.y), max(b.z, b.w)) < 0.0 : min(min(b.x, b.y), min(b.z, b.w)) >= 0.0) return -1.0;
  float d0 = b.y - b.x, d1 = b.z - b.y, d2 = b.w - b.z;
  float A = d0 - 2.0 * d1 + d2, B = 2.0 * (d1 - d0), C = d0;
  float r1 = 2.0, r2 = 2.0;
  float scale = max(abs(A), max(abs(B), abs(C)));
  if (abs(A) > 1e-7 * scale) {
    float disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
      float q = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
      r1 = q / A;
      r2 = q != 0.0 ? C / q : 2.0;
    }
  } else if (B != 0.0) {
    r1 = -C / B;
  }
  if (!(r1 > 0.0 && r1 < 1.0)) r1 = 2.0;
  if (!(r2 > 0.0 && r2 < 1.0)) r2 = 2.0;
  vec3 knots = vec3(min(min(r1, r2), 1.0), min(max(r1, r2), 1.0), 1.0);
  float ua = u0;
  for (int i = 0; i < 3; ++i) {
    float ub = knots[i];
    if (ub <= ua) continue;
    float gb = ub == 1.0 ? b.w : fcc_bernstein3(b, ub);
    if ((gb < 0.0) != neg) {
      float lo = ua, hi = ub;
      for (int it = 0; it < 26; ++it) {
        float mid = 0.5 * (lo + hi);
        if ((fcc_bernstein3(b, mid) < 0.0) == neg) lo = mid;
        else hi = mid;
      }
      after = hi;
      return 0.5 * (lo + hi);
    }
    ua = ub;
  }
  return -1.0;
}

// How far from a surface a piece's start may lie on the far side and still be taken as the side
// carried in from the piece before (nextRoot3): rounding of the pieces' coefficients, relative to the
// field's values there.
float joinTolerance(float lo, float hi) { return 1e-5 * max(abs(lo), abs(hi)); }

// The earliest crossing of any surface in [u0, 1] of a piece along which the field is the cubic bz
// (Bernstein, on [0, 1]) and lies within [lo, hi]: its surface (-1: none), u and `after`.
int nextCrossing3(vec4 bz, float lo, float hi, float u0, ivec4 side, out float u, out float after) {
  int best = -1;
  u = 2.0;
  after = 2.0;
  for (int k = 0; k < uSurfaceCount; ++k) {
    float iso = uSurfaceIsos[k];
    if (!(lo <= iso && iso <= hi)) continue;
    float a;
    float r = nextRoot3(bz - vec4(iso), u0, side[k], joinTolerance(lo, hi), a);
    if (r >= 0.0 && r < u) {
      u = r;
      after = a;
      best = k;
    }
  }
  return best;
}

// Every surface's side at the end of a piece: by the end value, or by the bounds where they exclude it.
ivec4 sidesAtEnd(float end, float lo, float hi) {
  ivec4 s;
  for (int k = 0; k < 4; ++k) {
    float iso = uSurfaceIsos[k];
    s[k] = !(lo <= iso && iso <= hi) ? (lo > iso ? 1 : -1) : sideOf(end - iso);
  }
  return s;
}

// Whether [lo, hi] holds any surface's value.
bool holdsAnySurface(float lo, float hi) {
  for (int k = 0; k < uSurfaceCount; ++k)
    if (lo <= uSurfaceIsos[k] && uSurfaceIsos[k] <= hi) return true;
  return false;
}

#if FCC_RECON == FCC_RECON_TRICUBIC
// nextRoot3 for a polynomial of degree <= 9: the part on [u0, 1] (fcc_bernstein9_restrict), searched
// depth first, left half first, by the convex hull (fcc_first_root_bernstein9's subdivision): an
// interval whose coefficients change sign once and whose ends lie on different sides holds exactly one
// crossing, bisected on p; one shorter than 2^-20 that cannot be decided counts as a crossing if its
// ends differ (a touch is not one).
float nextRoot9(FccBernstein9 p, float u0, int side, float tolerance, out float after) {
  after = u0;
  float g0 = u0 == 0.0 ? p.b[0] : fcc_bernstein9_at(p, u0);
  bool neg = g0 < 0.0;
  if (side != 0 && neg != (side < 0)) {  // nextRoot3's join rule
    if (abs(g0) > tolerance) return u0;
    neg = side < 0;
  }
  FccBernstein9 rest = u0 > 0.0 ? fcc_bernstein9_restrict(p, u0, 1.0) : p;
  rest.b[0] = neg ? min(g0, -1e-30) : max(g0, 0.0);  // the side the search starts from
  float stackLo[24];
  float stackHi[24];
  stackLo[0] = 0.0;
  stackHi[0] = 1.0;
  int top = 1;
  while (top > 0) {
    top = top - 1;
    float lo = stackLo[top], hi = stackHi[top];
    FccBernstein9 q = fcc_bernstein9_restrict(rest, lo, hi);
    float mn = q.b[0], mx = q.b[0];
    int changes = 0;
    for (int i = 1; i <= q.n; ++i) {
      mn = min(mn, q.b[i]);
      mx = max(mx, q.b[i]);
      if ((q.b[i] < 0.0) != (q.b[i - 1] < 0.0)) changes = changes + 1;
    }
    if (mx < 0.0 || mn >= 0.0) continue;  // one side throughout
    bool ends = (q.b[0] < 0.0) != (q.b[q.n] < 0.0);
    if ((changes == 1 && ends) || ((hi - lo < 9.5367e-7 || top + 2 > 24) && ends)) {
      // Bisected on p itself, over the interval's place in [u0, 1]: the sides seen here are those
      // the next search (and the caller's side update) evaluate, so a crossing is never seen twice.
      float w = 1.0 - u0;
      float a = u0 + lo * w, c = u0 + hi * w;
      bool aNeg = lo == 0.0 ? neg : fcc_bernstein9_at(p, a) < 0.0;
      if ((fcc_bernstein9_at(p, c) < 0.0) != aNeg) {
        for (int it = 0; it < 26; ++it) {
          float mid = 0.5 * (a + c);
          if ((fcc_bernstein9_at(p, mid) < 0.0) == aNeg) a = mid;
          else c = mid;
        }
        after = c;
        return 0.5 * (a + c);
      }
    }
    if (hi - lo < 9.5367e-7 || top + 2 > 24) continue;
    float mid = 0.5 * (lo + hi);
    stackLo[top] = mid;
    stackHi[top] = hi;
    stackLo[top + 1] = lo;
    stackHi[top + 1] = mid;
    top = top + 2;
  }
  return -1.0;
}

FccBernstein9 minusIso9(FccBernstein9 p, float iso) {
  for (int i = 0; i <= p.n; ++i) p.b[i] -= iso;
  return p;
}
#endif

// The crossings in the resident brick b between ta and tb, walking its unit cells (cells and pieces
// whose bounds hold no surface's value are passed over, their sides set from the bounds); true once
// the ray is opaque enough to stop. st.side carries each surface's side from brick to brick.
bool marchBrickSurfaces(ivec3 b, uint slot, vec3 o, vec3 d, vec3 invD, float ta, float tb, inout SurfaceState st) {
  selectSlot(slot, b);
  uint boundsBase = slot * uint(kSlotVoxels);
  ivec3 cellLo = b * 16, cellHi = cellLo + 15;
  float tm = 0.5 * (ta + tb);
  vec3 pStart = o + min(ta + 1e-4 * (tb - ta), tm) * d;
  ivec3 cell = clamp(ivec3(floor(pStart)), cellLo, cellHi);
  ivec3 stepDir = ivec3(sign(d));
  vec3 nextBoundary = vec3(cell) + vec3(greaterThan(d, vec3(0.0)));
  vec3 tMax = (nextBoundary - o) * invD;
  vec3 tDelta = abs(invD);
  float tCell = ta;
  for (int iter = 0; iter < 64; ++iter) {
    float tExit = min(min(min(tMax.x, tMax.y), tMax.z), tb);
    ivec3 voxel = (cell - cellLo) >> 1;
    vec2 cellBounds = slotBounds[boundsBase + uint((voxel.z * 8 + voxel.y) * 8 + voxel.x)];
    if (tExit > tCell && uSkipEmpty != 0 && !holdsAnySurface(cellBounds.x, cellBounds.y)) {
      st.side = sidesAtEnd(0.0, cellBounds.x, cellBounds.y);
    } else if (tExit > tCell) {
#if FCC_RECON == FCC_RECON_BOXSPLINE
      vec4 splits = fcc_cell_splits(cell, o, d, tCell, tExit);
      float s0 = tCell;
      for (int k = 0; k < 5 && s0 < tExit; ++k) {
        float s1 = k == 0 ? splits.x : (k == 1 ? splits.y : (k == 2 ? splits.z : (k == 3 ? splits.w : tExit)));
        if (s1 <= s0) continue;
        FccFrame frame = fcc_locate(clamp(o + (0.5 * (s0 + s1)) * d, vec3(cell), vec3(cell + 1)));
        FccSamples samples = gatherStencil(frame);
        FccCubic cubic = fcc_cubic(samples, frame.type);
        FccRange range = fcc_cubic_range(cubic);
        if (holdsAnySurface(range.lo, range.hi)) {
          vec4 bz = fcc_segment_bernstein(cubic, frame, o, d, s0, s1, 0.0);
          float u0 = 0.0;
          for (int n = 0; n < kMaxCrossingsPerPiece; ++n) {
            float u, after;
            int surface = nextCrossing3(bz, range.lo, range.hi, u0, st.side, u, after);
            if (surface < 0) break;
            float t = s0 + u * (s1 - s0);
            vec3 xyz = o + t * d;
            vec3 g;
            if (uFiniteDifferenceNormals != 0) {
              g = finiteDifferenceGradient(xyz, b);
            } else {
              frame.q = vec3(frame.axis) * (xyz - vec3(frame.origin));
              g = fcc_gradient(samples, frame);
            }
            if (compositeCrossing(surface, t, g, st)) return true;
            st.side[surface] = sideOf(fcc_bernstein3(bz - vec4(uSurfaceIsos[surface]), after));
            u0 = after;
          }
          st.side = sidesAtEnd(bz.w, range.lo, range.hi);
        } else {
          st.side = sidesAtEnd(0.0, range.lo, range.hi);
        }
        s0 = s1;
      }
#elif FCC_RECON == FCC_RECON_TRILINEAR
      FccCorners8 c = gatherCorners(cell);
      FccRange range = fcc_corners_range(c);
      if (holdsAnySurface(range.lo, range.hi)) {
        vec3 origin = vec3(cell);
        vec4 bz = fcc_multiaffine_segment_bernstein(c, o + tCell * d - origin, o + tExit * d - origin, 0.0);
        float u0 = 0.0;
        for (int n = 0; n < kMaxCrossingsPerPiece; ++n) {
          float u, after;
          int surface = nextCrossing3(bz, range.lo, range.hi, u0, st.side, u, after);
          if (surface < 0) break;
          float t = tCell + u * (tExit - tCell);
          vec3 xyz = o + t * d;
          vec3 g = uFiniteDifferenceNormals != 0 ? finiteDifferenceGradient(xyz, b)
                                                 : cc_trilinear_value_gradient(c, cell, xyz).gradient;
          if (compositeCrossing(surface, t, g, st)) return true;
          st.side[surface] = sideOf(fcc_bernstein3(bz - vec4(uSurfaceIsos[surface]), after));
          u0 = after;
        }
        st.side = sidesAtEnd(bz.w, range.lo, range.hi);
      } else {
        st.side = sidesAtEnd(0.0, range.lo, range.hi);
      }
#elif FCC_RECON == FCC_RECON_TYPE6
      // The type-6 spline (march_cc.glsl): per part of the cell in one tetrahedron, its cubic.
      FccSplits splits = cc_type6_cell_splits(cell, o, d, tCell, tExit);
      float s0 = tCell;
      for (int k = 0; k <= splits.n; ++k) {
        float s1 = k < splits.n ? splits.t[k] : tExit;
        if (s1 <= s0) continue;
        Type6Piece piece = type6PieceOn(cell, o, d, s0, s1);
        FccRange range = cc_type6_range(piece.cubic);
        if (holdsAnySurface(range.lo, range.hi)) {
          vec4 bz = cc_type6_segment_bernstein(piece.cubic, piece.frame, o + s0 * d, o + s1 * d, 0.0);
          float u0 = 0.0;
          for (int n = 0; n < kMaxCrossingsPerPiece; ++n) {
            float u, after;
            int surface = nextCrossing3(bz, range.lo, range.hi, u0, st.side, u, after);
            if (surface < 0) break;
            float t = s0 + u * (s1 - s0);
            vec3 xyz = o + t * d;
            vec3 g = uFiniteDifferenceNormals != 0 ? finiteDifferenceGradient(xyz, b)
                                                   : cc_type6_value_gradient(piece.cubic, piece.frame, xyz).gradient;
            if (compositeCrossing(surface, t, g, st)) return true;
            st.side[surface] = sideOf(fcc_bernstein3(bz - vec4(uSurfaceIsos[surface]), after));
            u0 = after;
          }
          st.side = sidesAtEnd(bz.w, range.lo, range.hi);
        } else {
          st.side = sidesAtEnd(0.0, range.lo, range.hi);
        }
        s0 = s1;
      }
#elif FCC_RECON == FCC_RECON_BARYCENTRIC || FCC_RECON == FCC_RECON_SHEARED_TRILINEAR || \
    FCC_RECON == FCC_RECON_BILINEAR_SPATIAL || FCC_RECON == FCC_RECON_BILINEAR
      // The BCC schemes (march_bcc.glsl): per part of the cell in one piece, its cubic at most.
      FccSplits splits = bccCellSplits(cell, o, d, tCell, tExit);
      float s0 = tCell;
      for (int k = 0; k <= splits.n; ++k) {
        float s1 = k < splits.n ? splits.t[k] : tExit;
        if (s1 <= s0) continue;
        BccPiece piece = bccPieceOn(cell, o, d, s0, s1);
        vec4 bz = bccSegmentBernstein(piece, o + s0 * d, o + s1 * d, 0.0);
        FccRange range = bccBernsteinRange(bz);
        // The nearest-plane scheme steps between planes: a surface whose side changes where the piece
        // starts is crossed there (the join rule), even where the piece lies wholly on its other side.
        for (int s = 0; s < uSurfaceCount; ++s)
          if (st.side[s] != 0 && sideOf(bz.x - uSurfaceIsos[s]) != st.side[s]) {
            range.lo = min(range.lo, uSurfaceIsos[s]);
            range.hi = max(range.hi, uSurfaceIsos[s]);
          }
        if (holdsAnySurface(range.lo, range.hi)) {
          float u0 = 0.0;
          for (int n = 0; n < kMaxCrossingsPerPiece; ++n) {
            float u, after;
            int surface = nextCrossing3(bz, range.lo, range.hi, u0, st.side, u, after);
            if (surface < 0) break;
            float t = s0 + u * (s1 - s0);
            vec3 xyz = o + t * d;
            vec3 g = uFiniteDifferenceNormals != 0 ? finiteDifferenceGradient(xyz, b) : bccValueGradient(piece, xyz).gradient;
            if (compositeCrossing(surface, t, g, st)) return true;
            st.side[surface] = sideOf(fcc_bernstein3(bz - vec4(uSurfaceIsos[surface]), after));
            u0 = after;
          }
          st.side = sidesAtEnd(bz.w, range.lo, range.hi);
        } else {
          st.side = sidesAtEnd(0.0, range.lo, range.hi);
        }
        s0 = s1;
      }
#else  // tricubic: the degree-9 polynomial along the ray
      FccCoeffs64 coeffs = gatherCoefficients(cell);
      FccCoeffs64 bezier = cc_tricubic_bezier(coeffs);
      FccRange range = cc_tricubic_range(bezier);
      if (holdsAnySurface(range.lo, range.hi)) {
        vec3 origin = vec3(cell);
        FccBernstein9 p = cc_tricubic_segment_bernstein(bezier, o + tCell * d - origin, o + tExit * d - origin, 0.0);
        float u0 = 0.0;
        for (int n = 0; n < kMaxCrossingsPerPiece; ++n) {
          int surface = -1;
          float u = 2.0, after = 2.0;
          for (int k = 0; k < uSurfaceCount; ++k) {
            float iso = uSurfaceIsos[k];
            if (!(range.lo <= iso && iso <= range.hi)) continue;
            float a;
            float r = nextRoot9(minusIso9(p, iso), u0, st.side[k], joinTolerance(range.lo, range.hi), a);
            if (r >= 0.0 && r < u) {
              u = r;
              after = a;
              surface = k;
            }
          }
          if (surface < 0) break;
          float t = tCell + u * (tExit - tCell);
          vec3 xyz = o + t * d;
          vec3 g = uFiniteDifferenceNormals != 0 ? finiteDifferenceGradient(xyz, b)
                                                 : cc_tricubic_value_gradient(coeffs, cell, xyz).gradient;
          if (compositeCrossing(surface, t, g, st)) return true;
          st.side[surface] = sideOf(fcc_bernstein9_at(minusIso9(p, uSurfaceIsos[surface]), after));
          u0 = after;
        }
        st.side = sidesAtEnd(p.b[p.n], range.lo, range.hi);
      } else {
        st.side = sidesAtEnd(0.0, range.lo, range.hi);
      }
#endif
    }
    if (tExit >= tb) break;
    tCell = max(tCell, tExit);
    if (tMax.x <= tMax.y && tMax.x <= tMax.z) {
      cell.x += stepDir.x;
      tMax.x += tDelta.x;
    } else if (tMax.y <= tMax.z) {
      cell.y += stepDir.y;
      tMax.y += tDelta.y;
    } else {
      cell.z += stepDir.z;
      tMax.z += tDelta.z;
    }
    if (any(lessThan(cell, cellLo)) || any(greaterThan(cell, cellHi))) break;
  }
  return false;
}
