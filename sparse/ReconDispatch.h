// ReconDispatch.h — every reconstruction's value and gradient behind one id, for the device dialects
// (OpenCL C, GLSL) where there are no virtual functions: the evaluation kernels that test the dialects'
// agreement (kernels/recon_eval.cl, shaders/recon_eval.comp) use it. C++ has the classes of
// sparse/Reconstruction.h, which call the same header functions.
//
// The including file says how a site's coefficient is read, as PNanoVDB passes its buffer: before the
// include it defines FCC_SITE_PARAMS (extra parameters, with a leading comma, or nothing), FCC_SITE_ARGS
// (the same names as arguments) and FCC_SITE_VALUE(ijk) (an expression of those).
#ifndef FCC_RECON_DISPATCH_H
#define FCC_RECON_DISPATCH_H

#include "Dialect.h"
#include "ReconCommon.h"
#include "FccSpline.h"
#include "CcTrilinear.h"
#include "CcTricubic.h"
#include "BccBarycentric.h"
#include "BccShearedTrilinear.h"
#include "BccBilinear.h"

// Ids, as sparse/Reconstruction.cpp's reconstructionId gives them (tricubic and tricubic-bspline differ
// in their prefilter only, so they share an evaluation).
#define FCC_RECON_TRILINEAR 0
#define FCC_RECON_TRICUBIC 1
#define FCC_RECON_BARYCENTRIC 2
#define FCC_RECON_SHEARED_TRILINEAR 3
#define FCC_RECON_BILINEAR_SPATIAL 4
#define FCC_RECON_BILINEAR 5
#define FCC_RECON_BOXSPLINE 6

#if !defined(FCC_CPP)
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
#endif

#endif  // FCC_RECON_DISPATCH_H
