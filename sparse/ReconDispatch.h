// ReconDispatch.h — every reconstruction's value and gradient, and its ray fast path (a segment's
// first root), behind one id: for the device dialects (OpenCL C, GLSL) where there are no virtual
// functions, and for the test that compiles the same functions in C++ to compare them (the evaluation
// kernels kernels/recon_eval.cl and shaders/recon_eval.comp). C++ code otherwise uses the classes of
// sparse/Reconstruction.h, which call the same header functions.
//
// The including file says how a site's coefficient is read, as PNanoVDB passes its buffer: before the
// include it defines FCC_SITE_PARAMS (extra parameters, with a leading comma, or nothing), FCC_SITE_ARGS
// (the same names as arguments) and FCC_SITE_VALUE(ijk) (an expression of those). Without
// FCC_SITE_VALUE only the ids are defined.
#ifndef FCC_RECON_DISPATCH_H
#define FCC_RECON_DISPATCH_H

#include "Dialect.h"
#include "ReconCommon.h"
#include "FccSpline.h"
#include "FccRay.h"
#include "CcTrilinear.h"
#include "CcTricubic.h"
#include "CcType6.h"
#include "BccBarycentric.h"
#include "BccShearedTrilinear.h"
#include "BccBilinear.h"

#include "ReconIds.h"

#endif  // FCC_RECON_DISPATCH_H

// The functions, once a file has said how sites are read (guarded on their own: the ids above may have
// been included before, without them).
#if defined(FCC_SITE_VALUE) && !defined(FCC_RECON_DISPATCH_FUNCTIONS)
#define FCC_RECON_DISPATCH_FUNCTIONS
FCC_NAMESPACE_BEGIN
// params: the BCC stack schemes' axis and shear signs (bcc_sheared_params_for_view); others ignore it.
FCC_FUNC FccValueGradient fcc_recon_value_gradient(int id, FCC_VEC3 xyz, FCC_IVEC3 params FCC_SITE_PARAMS) {
  if (id == FCC_RECON_TRILINEAR) {
    FCC_IVEC3 cell = cc_trilinear_cell(xyz);
    FccCorners8 c;
    for (int i = 0; i < 8; ++i) c.v[i] = FCC_SITE_VALUE(cc_trilinear_stencil_site(cell, i));
    return cc_trilinear_value_gradient(c, cell, xyz);
  }
  if (id == FCC_RECON_TRICUBIC) {
    FCC_IVEC3 cell = cc_tricubic_cell(xyz);
    FccCoeffs64 c;
    for (int i = 0; i < 64; ++i) c.v[i] = FCC_SITE_VALUE(cc_tricubic_stencil_site(cell, i));
    return cc_tricubic_value_gradient(c, cell, xyz);
  }
  if (id == FCC_RECON_TYPE6) {
    CcType6Frame frame = cc_type6_locate(xyz);
    FccSamples27 s;
    for (int i = 0; i < 27; ++i) s.v[i] = FCC_SITE_VALUE(cc_type6_stencil_site(frame, i));
    return cc_type6_value_gradient(cc_type6_cubic(s), frame, xyz);
  }
  if (id == FCC_RECON_BARYCENTRIC) {
    BccTetFrame frame = bcc_barycentric_locate(xyz);
    FccCorners4 s;
    for (int i = 0; i < 4; ++i) s.v[i] = FCC_SITE_VALUE(bcc_barycentric_stencil_site(frame, i));
    return bcc_barycentric_value_gradient(s, frame, xyz);
  }
  if (id == FCC_RECON_SHEARED_TRILINEAR) {
    BccShearedFrame frame = bcc_sheared_locate(xyz, params);
    FccCorners8 c;
    for (int i = 0; i < 8; ++i) c.v[i] = FCC_SITE_VALUE(bcc_sheared_stencil_site(frame, i));
    return bcc_sheared_value_gradient(c, frame, xyz);
  }
  if (id == FCC_RECON_BILINEAR_SPATIAL || id == FCC_RECON_BILINEAR) {
    int spatial = id == FCC_RECON_BILINEAR_SPATIAL ? 1 : 0;
    BccPlaneFrame frame = bcc_plane_locate(xyz, params.x, spatial);
    FccCorners8 s;
    for (int i = 0; i < 8; ++i) s.v[i] = FCC_SITE_VALUE(bcc_plane_stencil_site(frame, spatial != 0 ? i : (i & 3)));
    return bcc_plane_value_gradient(s, frame, xyz, spatial);
  }
  FccFrame frame = fcc_locate(xyz);
  FccSamples s;
  for (int k = 0; k < FCC_STENCIL_SIZE; ++k) s.v[k] = FCC_SITE_VALUE(fcc_stencil_site(frame, k));
  return fcc_value_gradient(s, frame);
}

// The ray fast path of each reconstruction: the first u in [0, 1] where the piece holding the
// segment's midpoint equals iso along xyz(u) = a + u (b - a), from the piece's Bernstein form along the
// segment (what a raycaster computes per piece), or -1. The segment must lie in one piece.
FCC_FUNC float fcc_recon_segment_root(int id, FCC_VEC3 a, FCC_VEC3 b, float iso, FCC_IVEC3 params FCC_SITE_PARAMS) {
  FCC_VEC3 mid = 0.5f * (a + b);
  if (id == FCC_RECON_TRILINEAR) {
    FCC_IVEC3 cell = cc_trilinear_cell(mid);
    FccCorners8 c;
    for (int i = 0; i < 8; ++i) c.v[i] = FCC_SITE_VALUE(cc_trilinear_stencil_site(cell, i));
    FCC_VEC3 origin = FCC_VEC3_FROM_IVEC3(cell);
    return fcc_first_root_bernstein3(fcc_multiaffine_segment_bernstein(c, a - origin, b - origin, iso));
  }
  if (id == FCC_RECON_TRICUBIC) {
    FCC_IVEC3 cell = cc_tricubic_cell(mid);
    FccCoeffs64 c;
    for (int i = 0; i < 64; ++i) c.v[i] = FCC_SITE_VALUE(cc_tricubic_stencil_site(cell, i));
    FCC_VEC3 origin = FCC_VEC3_FROM_IVEC3(cell);
    return fcc_first_root_bernstein9(cc_tricubic_segment_bernstein(cc_tricubic_bezier(c), a - origin, b - origin, iso));
  }
  if (id == FCC_RECON_TYPE6) {
    CcType6Frame frame = cc_type6_locate(mid);
    FccSamples27 s;
    for (int i = 0; i < 27; ++i) s.v[i] = FCC_SITE_VALUE(cc_type6_stencil_site(frame, i));
    return fcc_first_root_bernstein3(cc_type6_segment_bernstein(cc_type6_cubic(s), frame, a, b, iso));
  }
  if (id == FCC_RECON_BARYCENTRIC) {
    BccTetFrame frame = bcc_barycentric_locate(mid);
    FccCorners4 s;
    for (int i = 0; i < 4; ++i) s.v[i] = FCC_SITE_VALUE(bcc_barycentric_stencil_site(frame, i));
    float va = bcc_barycentric_value_gradient(s, frame, a).value - iso;
    float vb = bcc_barycentric_value_gradient(s, frame, b).value - iso;
    return fcc_first_root_bernstein3(fcc_linear_as_bernstein3(va, vb));
  }
  if (id == FCC_RECON_SHEARED_TRILINEAR) {
    BccShearedFrame frame = bcc_sheared_locate(mid, params);
    FccCorners8 c;
    for (int i = 0; i < 8; ++i) c.v[i] = FCC_SITE_VALUE(bcc_sheared_stencil_site(frame, i));
    return fcc_first_root_bernstein3(
        fcc_multiaffine_segment_bernstein(c, bcc_sheared_local(frame, a), bcc_sheared_local(frame, b), iso));
  }
  if (id == FCC_RECON_BILINEAR_SPATIAL || id == FCC_RECON_BILINEAR) {
    int spatial = id == FCC_RECON_BILINEAR_SPATIAL ? 1 : 0;
    BccPlaneFrame frame = bcc_plane_locate(mid, params.x, spatial);
    FccCorners8 s;
    for (int i = 0; i < 8; ++i) s.v[i] = FCC_SITE_VALUE(bcc_plane_stencil_site(frame, spatial != 0 ? i : (i & 3)));
    FCC_IVEC3 cell = bcc_plane_unit_cell(mid, params.x);
    FccCorners8 c = bcc_plane_unit_cell_corners(s, frame, cell, spatial);
    FCC_VEC3 origin = FCC_VEC3_FROM_IVEC3(cell);
    return fcc_first_root_bernstein3(fcc_multiaffine_segment_bernstein(
        c, fcc_to_stack(a, params.x) - origin, fcc_to_stack(b, params.x) - origin, iso));
  }
  FccFrame frame = fcc_locate(mid);
  FccSamples s;
  for (int k = 0; k < FCC_STENCIL_SIZE; ++k) s.v[k] = FCC_SITE_VALUE(fcc_stencil_site(frame, k));
  return fcc_first_root_bernstein3(fcc_segment_bernstein(fcc_cubic(s, frame.type), frame, a, b - a, 0.0f, 1.0f, iso));
}
FCC_NAMESPACE_END
#endif
