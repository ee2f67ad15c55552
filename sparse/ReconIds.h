// ReconIds.h — the ids by which the device dialects know each reconstruction (FCC_RECON_* : the
// raycaster's FCC_RECON define, sparse/ReconDispatch.h's dispatch, ReconstructionInfo::deviceId). Apart
// from the dispatch so that a shader can choose its reconstruction without compiling every one.
#ifndef FCC_RECON_IDS_H
#define FCC_RECON_IDS_H

// Ids, as sparse/Reconstruction.cpp's reconstructionId gives them (tricubic and tricubic-bspline differ
// in their prefilter only, so they share an evaluation).
#define FCC_RECON_TRILINEAR 0
#define FCC_RECON_TRICUBIC 1
#define FCC_RECON_BARYCENTRIC 2
#define FCC_RECON_SHEARED_TRILINEAR 3
#define FCC_RECON_BILINEAR_SPATIAL 4
#define FCC_RECON_BILINEAR 5
#define FCC_RECON_BOXSPLINE 6
#define FCC_RECON_TYPE6 7

#endif  // FCC_RECON_IDS_H
