// FccSpline.h — the FCC six-direction box spline M_fcc, written once for C++17, OpenCL C 1.2 and
// GLSL 4.50 (in the spirit of NanoVDB's PNanoVDB.h).
//
// The dialect macros are in Dialect.h (C++ users include sparse/Spline.h, which brings GLM first).
//
// Coordinates: `xyz` is a position in the FCC lattice's index space (the Cartesian embedding, where
// FCC sites are the integer points with an even coordinate sum). Evaluating the spline at xyz takes
//   1. fcc_locate(xyz)            -> the canonical frame of xyz's tetrahedral piece (origin, axes, q, type),
//   2. the caller gathers the 19 coefficients c at fcc_stencil_site(frame, i) (the only dialect-specific
//      step: a texture, a buffer, a VDB accessor),
//   3. fcc_value / fcc_value_gradient(samples, frame).
// Paper: Minho Kim, "GPU Isosurface Raycasting of FCC Datasets", sections 3 and 4.1-4.2; the tables
// are derived by tools/gen_spline_tables.py (docs/SPLINE.md).
#ifndef FCC_SPLINE_H
#define FCC_SPLINE_H

#include "Dialect.h"
#include "ReconCommon.h"

FCC_NAMESPACE_BEGIN

// The 19 prefiltered coefficients of one piece's stencil, in fcc_stencil_d{x,y,z} order.
FCC_STRUCT_BEGIN(FccSamples)
  float v[19];
FCC_STRUCT_END(FccSamples)

// BB-coefficients (scaled by FCC_CUBIC_DENOM) of the cubic on one tetrahedron.
FCC_STRUCT_BEGIN(FccCubic)
  float b[20];
FCC_STRUCT_END(FccCubic)

// BB-coefficients (scaled by FCC_DERIV_DENOM) of one quadratic directional derivative.
FCC_STRUCT_BEGIN(FccQuadratic)
  float b[10];
FCC_STRUCT_END(FccQuadratic)

// Derivatives along xi_110, xi_101, xi_011, in this order (paper 4.2).
FCC_STRUCT_BEGIN(FccDerivs)
  FccQuadratic d[3];
FCC_STRUCT_END(FccDerivs)

// The canonical frame of a point's tetrahedral piece: xyz = origin + axis * q (component-wise), with
// origin an FCC site, axis in {-1,+1}^3, q in the canonical tetrahedron tau_0 (type 0: corner
// (0,0,0),(1,0,0),(0,1,0),(0,0,1)) or tau_4 (type 4: (1,0,0),(0,1,0),(0,0,1),(1,1,1)).
FCC_STRUCT_BEGIN(FccFrame)
  FCC_IVEC3 origin;
  FCC_IVEC3 axis;
  FCC_VEC3 q;
  int type;
FCC_STRUCT_END(FccFrame)

#include "FccSplineTables.h"

// The 12 nearest FCC neighbours (+-xi for the six directions), for the prefilter.
FCC_CONST_INT_ARRAY(fcc_neighbour_dx, 12) FCC_ARRAY_OPEN(int, 12) 1, 1, 0, -1, -1, 0, 1, 1, 0, -1, -1, 0 FCC_ARRAY_CLOSE;
FCC_CONST_INT_ARRAY(fcc_neighbour_dy, 12) FCC_ARRAY_OPEN(int, 12) 1, 0, 1, -1, 0, -1, -1, 0, 1, 1, 0, -1 FCC_ARRAY_CLOSE;
FCC_CONST_INT_ARRAY(fcc_neighbour_dz, 12) FCC_ARRAY_OPEN(int, 12) 0, 1, 1, 0, -1, -1, 0, -1, -1, 0, 1, 1 FCC_ARRAY_CLOSE;

// Quasi-interpolation prefilter q_fcc (paper 3.3): c_j = (36 V(j) - sum of the 12 neighbours) / 24.
FCC_FUNC float fcc_prefilter(float center, float neighbourSum) {
  return (36.0f * center - neighbourSum) * (1.0f / 24.0f);
}

FCC_FUNC FCC_IVEC3 fcc_neighbour_offset(int i) {
  return FCC_MAKE_IVEC3(fcc_neighbour_dx[i], fcc_neighbour_dy[i], fcc_neighbour_dz[i]);
}

// Finds the tetrahedral piece containing xyz and its canonical frame (paper 4.1, Figures 3-5).
FCC_FUNC FccFrame fcc_locate(FCC_VEC3 xyz) {
  FCC_VEC3 cornerF = FCC_FLOOR3(xyz);
  FCC_IVEC3 corner = FCC_IVEC3_FROM_VEC3(cornerF);
  FCC_VEC3 p = xyz - cornerF;
  FCC_IVEC3 axis = FCC_MAKE_IVEC3(1, 1, 1);
  if (((corner.x + corner.y + corner.z) & 1) != 0) {
    // An odd cube is the point reflection of an even cube through its centre; its far corner is even.
    p = FCC_MAKE_VEC3(1.0f, 1.0f, 1.0f) - p;
    corner = corner + FCC_MAKE_IVEC3(1, 1, 1);
    axis = FCC_MAKE_IVEC3(-1, -1, -1);
  }
  // Five pieces of the even cube: four corner tetrahedra at the cube's even corners, one central.
  FCC_IVEC3 offset = FCC_MAKE_IVEC3(0, 0, 0);
  FCC_IVEC3 flip = FCC_MAKE_IVEC3(1, 1, 1);
  int type = 0;
  if (p.x + p.y + p.z <= 1.0f) {
  } else if (p.x + p.y - p.z >= 1.0f) {
    offset = FCC_MAKE_IVEC3(1, 1, 0);
    flip = FCC_MAKE_IVEC3(-1, -1, 1);
  } else if (p.x - p.y + p.z >= 1.0f) {
    offset = FCC_MAKE_IVEC3(1, 0, 1);
    flip = FCC_MAKE_IVEC3(-1, 1, -1);
  } else if (-p.x + p.y + p.z >= 1.0f) {
    offset = FCC_MAKE_IVEC3(0, 1, 1);
    flip = FCC_MAKE_IVEC3(1, -1, -1);
  } else {
    type = 4;
  }
  FccFrame frame;
  frame.origin = corner + axis * offset;
  frame.axis = axis * flip;
  frame.q = FCC_VEC3_FROM_IVEC3(flip) * (p - FCC_VEC3_FROM_IVEC3(offset));
  frame.type = type;
  return frame;
}

// The FCC site whose coefficient is samples.v[i] for this frame.
FCC_FUNC FCC_IVEC3 fcc_stencil_site(FccFrame frame, int i) {
  return frame.origin + frame.axis * FCC_MAKE_IVEC3(fcc_stencil_dx[i], fcc_stencil_dy[i], fcc_stencil_dz[i]);
}

// Barycentric coordinates of q with respect to the canonical tetrahedron's vertices v0..v3.
FCC_FUNC FCC_VEC4 fcc_barycentric(FCC_VEC3 q, int type) {
  if (type == 0) return FCC_MAKE_VEC4(1.0f - q.x - q.y - q.z, q.x, q.y, q.z);
  float l3 = 0.5f * (q.x + q.y + q.z - 1.0f);
  return FCC_MAKE_VEC4(q.x - l3, q.y - l3, q.z - l3, l3);
}

FCC_FUNC FccCubic fcc_cubic(FccSamples s, int type) {
  if (type == 0) return fcc_cubic_t0(s);
  return fcc_cubic_t4(s);
}

FCC_FUNC float fcc_value(FccSamples s, FccFrame frame) {
  return fcc_decasteljau3(fcc_cubic(s, frame.type), fcc_barycentric(frame.q, frame.type)) *
         (1.0f / FCC_CUBIC_DENOM);
}

// Gradient through the quadratic derivative kernels M_xi (paper 4.2), mapped back from the canonical
// frame: the frame's axes are reflections, so each component only changes sign.
FCC_FUNC FCC_VEC3 fcc_gradient(FccSamples s, FccFrame frame) {
  FccDerivs d;
  if (frame.type == 0) d = fcc_derivs_t0(s);
  else d = fcc_derivs_t4(s);
  FCC_VEC4 l = fcc_barycentric(frame.q, frame.type);
  float d110 = fcc_decasteljau2(d.d[0], l);
  float d101 = fcc_decasteljau2(d.d[1], l);
  float d011 = fcc_decasteljau2(d.d[2], l);
  FCC_VEC3 gq = FCC_MAKE_VEC3(d110 + d101 - d011, d110 + d011 - d101, d101 + d011 - d110) *
                (0.5f / FCC_DERIV_DENOM);
  return gq * FCC_VEC3_FROM_IVEC3(frame.axis);
}

FCC_FUNC FccValueGradient fcc_value_gradient(FccSamples s, FccFrame frame) {
  FccValueGradient r;
  r.value = fcc_value(s, frame);
  r.gradient = fcc_gradient(s, frame);
  return r;
}

// Empty-space skipping (paper 4.3): the spline on a tetrahedral piece lies in the convex hull of its
// BB-coefficients, so their min and max bound it there.
FCC_FUNC FccRange fcc_cubic_range(FccCubic c) {
  FccRange r;
  r.lo = c.b[0];
  r.hi = c.b[0];
  for (int i = 1; i < 20; ++i) {
    r.lo = min(r.lo, c.b[i]);
    r.hi = max(r.hi, c.b[i]);
  }
  r.lo *= 1.0f / FCC_CUBIC_DENOM;
  r.hi *= 1.0f / FCC_CUBIC_DENOM;
  return r;
}

// A point strictly inside piece `piece` (0..4) of the unit cube at integer corner `corner`: the
// pieces' centroids. An odd cube is the point reflection of an even one, so its centroids are 1 - p.
FCC_FUNC FCC_VEC3 fcc_piece_centroid(FCC_IVEC3 corner, int piece) {
  FCC_VEC3 p = FCC_MAKE_VEC3(0.5f, 0.5f, 0.5f);
  if (piece == 0) p = FCC_MAKE_VEC3(0.25f, 0.25f, 0.25f);
  if (piece == 1) p = FCC_MAKE_VEC3(0.75f, 0.75f, 0.25f);
  if (piece == 2) p = FCC_MAKE_VEC3(0.75f, 0.25f, 0.75f);
  if (piece == 3) p = FCC_MAKE_VEC3(0.25f, 0.75f, 0.75f);
  if (((corner.x + corner.y + corner.z) & 1) != 0) p = FCC_MAKE_VEC3(1.0f, 1.0f, 1.0f) - p;
  return FCC_VEC3_FROM_IVEC3(corner) + p;
}

FCC_NAMESPACE_END

#endif  // FCC_SPLINE_H
