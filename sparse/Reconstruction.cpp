#include "Reconstruction.h"

#include "BccBarycentric.h"
#include "BccBilinear.h"
#include "BccShearedTrilinear.h"
#include "CcTricubic.h"
#include "CcTrilinear.h"
#include "CcType6.h"
#include "Error.h"
#include "ReconDispatch.h"

namespace fcc {

using spline::FccSplits;
using spline::FccValueGradient;

std::string_view latticeName(Lattice lattice) {
  switch (lattice) {
    case Lattice::Cc: return "cc";
    case Lattice::Bcc: return "bcc";
    case Lattice::Fcc: return "fcc";
  }
  return "?";
}

double latticeDensity(Lattice lattice) {
  switch (lattice) {
    case Lattice::Cc: return 1.0;
    case Lattice::Bcc: return 0.25;
    case Lattice::Fcc: return 0.5;
  }
  return 1.0;
}

bool isLatticeSite(Lattice lattice, const glm::ivec3& ijk) {
  switch (lattice) {
    case Lattice::Cc: return true;
    case Lattice::Bcc: return ((ijk.x ^ ijk.y) & 1) == 0 && ((ijk.y ^ ijk.z) & 1) == 0;
    case Lattice::Fcc: return ((ijk.x + ijk.y + ijk.z) & 1) == 0;
  }
  return false;
}

const std::vector<ReconstructionInfo>& reconstructionInfos() {
  static const std::vector<ReconstructionInfo> infos = {
      {"trilinear", Lattice::Cc, "trilinear interpolation of the 8 cell corners", 8, 3, 1, 0, false, Prefilter::None, FCC_RECON_TRILINEAR},
      {"tricubic", Lattice::Cc, "cubic B-spline, interpolating prefilter", 64, 9, 3, 2, false, Prefilter::CubicBSpline, FCC_RECON_TRICUBIC},
      {"tricubic-bspline", Lattice::Cc, "cubic B-spline on the samples (approximating, smoothing)", 64, 9, 1, 2, false,
       Prefilter::None, FCC_RECON_TRICUBIC},
      {"barycentric", Lattice::Bcc, "linear on the Delaunay tetrahedra (paper 002, 3.3)", 4, 1, 1, 0, false,
       Prefilter::None, FCC_RECON_BARYCENTRIC},
      {"sheared-trilinear", Lattice::Bcc, "trilinear in sheared cells (paper 002, 3.4)", 8, 3, 1, 0, true,
       Prefilter::None, FCC_RECON_SHEARED_TRILINEAR},
      {"bilinear-spatial", Lattice::Bcc, "bilinear in two planes, linear between (paper 002, 3.2)", 8, 3, 1, 0, true,
       Prefilter::None, FCC_RECON_BILINEAR_SPATIAL},
      {"bilinear", Lattice::Bcc, "bilinear in the nearest plane (paper 002, 3.1)", 4, 2, 0, -1, true, Prefilter::None, FCC_RECON_BILINEAR},
      {"boxspline", Lattice::Fcc, "six-direction box spline M_fcc, quasi-interpolating prefilter q_fcc", 19, 3, 2, 1,
       false, Prefilter::Fcc, FCC_RECON_BOXSPLINE},
      // Last, so that the tests drawing random data for each reconstruction in turn give the others what
      // they gave before it came.
      {"type6", Lattice::Cc, "type-6 cubic C1 quasi-interpolating spline, 24 tetrahedra a cube (paper 003)", 27, 3, 1, 1,
       false, Prefilter::None, FCC_RECON_TYPE6},
  };
  return infos;
}

std::string reconstructionNames(const Lattice* lattice) {
  std::string names;
  for (const auto& info : reconstructionInfos()) {
    if (lattice && info.lattice != *lattice) continue;
    names += (names.empty() ? "" : ", ") + std::string(info.name);
  }
  return names;
}

const ReconstructionInfo& findReconstruction(std::string_view name) {
  for (const auto& info : reconstructionInfos())
    if (info.name == name) return info;
  throw ValueError("unknown reconstruction '" + std::string(name) + "' (valid: " + reconstructionNames() + ")");
}

namespace {

template <int N, class Samples, class SiteOf>
Samples gather(const SiteValue& at, SiteOf&& siteOf) {
  Samples s;
  for (int i = 0; i < N; ++i) s.v[i] = at(siteOf(i));
  return s;
}

class Trilinear final : public Reconstruction {
 public:
  using Reconstruction::Reconstruction;
  FccValueGradient evaluateInPiece(const glm::vec3& inside, const glm::vec3& xyz, const SiteValue& at) const override {
    const glm::ivec3 cell = spline::cc_trilinear_cell(inside);
    const auto c = gather<8, spline::FccCorners8>(at, [&](int i) { return spline::cc_trilinear_stencil_site(cell, i); });
    return spline::cc_trilinear_value_gradient(c, cell, xyz);
  }
  FccSplits cellSplits(const glm::ivec3&, const glm::vec3&, const glm::vec3&, float, float) const override {
    return spline::fcc_splits_none();
  }
};

class Tricubic final : public Reconstruction {
 public:
  using Reconstruction::Reconstruction;
  FccValueGradient evaluateInPiece(const glm::vec3& inside, const glm::vec3& xyz, const SiteValue& at) const override {
    const glm::ivec3 cell = spline::cc_tricubic_cell(inside);
    const auto c = gather<64, spline::FccCoeffs64>(at, [&](int i) { return spline::cc_tricubic_stencil_site(cell, i); });
    return spline::cc_tricubic_value_gradient(c, cell, xyz);
  }
  FccSplits cellSplits(const glm::ivec3&, const glm::vec3&, const glm::vec3&, float, float) const override {
    return spline::fcc_splits_none();
  }
};

// Sorokina and Zeilfelder's type-6 spline: the cube of the nearest site, its tetrahedron's 27 samples.
class Type6 final : public Reconstruction {
 public:
  using Reconstruction::Reconstruction;
  FccValueGradient evaluateInPiece(const glm::vec3& inside, const glm::vec3& xyz, const SiteValue& at) const override {
    const spline::CcType6Frame frame = spline::cc_type6_locate(inside);
    const auto s = gather<27, spline::FccSamples27>(at, [&](int i) { return spline::cc_type6_stencil_site(frame, i); });
    return spline::cc_type6_value_gradient(spline::cc_type6_cubic(s), frame, xyz);
  }
  FccSplits cellSplits(const glm::ivec3& cell, const glm::vec3& o, const glm::vec3& d, float ta, float tb) const override {
    return spline::cc_type6_cell_splits(cell, o, d, ta, tb);
  }
};

class Barycentric final : public Reconstruction {
 public:
  using Reconstruction::Reconstruction;
  FccValueGradient evaluateInPiece(const glm::vec3& inside, const glm::vec3& xyz, const SiteValue& at) const override {
    const spline::BccTetFrame frame = spline::bcc_barycentric_locate(inside);
    const auto s =
        gather<4, spline::FccCorners4>(at, [&](int i) { return spline::bcc_barycentric_stencil_site(frame, i); });
    return spline::bcc_barycentric_value_gradient(s, frame, xyz);
  }
  FccSplits cellSplits(const glm::ivec3& cell, const glm::vec3& o, const glm::vec3& d, float ta, float tb) const override {
    return spline::bcc_barycentric_cell_splits(cell, o, d, ta, tb);
  }
};

// The view-dependent BCC schemes: a stack axis and shear signs, from setView.
class StackScheme : public Reconstruction {
 public:
  using Reconstruction::Reconstruction;
  void setView(const glm::vec3& dIndex) override { params_ = spline::bcc_sheared_params_for_view(dIndex); }

 protected:
  glm::ivec3 params_{2, 1, 1};
};

class ShearedTrilinear final : public StackScheme {
 public:
  using StackScheme::StackScheme;
  FccValueGradient evaluateInPiece(const glm::vec3& inside, const glm::vec3& xyz, const SiteValue& at) const override {
    const spline::BccShearedFrame frame = spline::bcc_sheared_locate(inside, params_);
    const auto c = gather<8, spline::FccCorners8>(at, [&](int i) { return spline::bcc_sheared_stencil_site(frame, i); });
    return spline::bcc_sheared_value_gradient(c, frame, xyz);
  }
  FccSplits cellSplits(const glm::ivec3& cell, const glm::vec3& o, const glm::vec3& d, float ta, float tb) const override {
    return spline::bcc_sheared_cell_splits(cell, params_, o, d, ta, tb);
  }
};

class PlaneScheme final : public StackScheme {
 public:
  PlaneScheme(const ReconstructionInfo& info, int spatial) : StackScheme(info), spatial_(spatial) {}
  FccValueGradient evaluateInPiece(const glm::vec3& inside, const glm::vec3& xyz, const SiteValue& at) const override {
    const spline::BccPlaneFrame frame = spline::bcc_plane_locate(inside, params_.x, spatial_);
    const auto s = gather<8, spline::FccCorners8>(at, [&](int i) {
      // The nearest-plane scheme reads only the lower square.
      return spline::bcc_plane_stencil_site(frame, spatial_ != 0 ? i : (i & 3));
    });
    return spline::bcc_plane_value_gradient(s, frame, xyz, spatial_);
  }
  FccSplits cellSplits(const glm::ivec3& cell, const glm::vec3& o, const glm::vec3& d, float ta, float tb) const override {
    return spline::bcc_plane_cell_splits(cell, params_.x, spatial_, o, d, ta, tb);
  }

 private:
  int spatial_;
};

class BoxSpline final : public Reconstruction {
 public:
  using Reconstruction::Reconstruction;
  FccValueGradient evaluateInPiece(const glm::vec3& inside, const glm::vec3& xyz, const SiteValue& at) const override {
    spline::FccFrame frame = spline::fcc_locate(inside);
    const spline::FccSamples s = spline::gatherSamples(frame, at);
    frame.q = glm::vec3(frame.axis) * (xyz - glm::vec3(frame.origin));
    return spline::fcc_value_gradient(s, frame);
  }
  FccSplits cellSplits(const glm::ivec3& cell, const glm::vec3& o, const glm::vec3& d, float ta, float tb) const override {
    const glm::vec4 t = spline::fcc_cell_splits(cell, o, d, ta, tb);
    FccSplits s = spline::fcc_splits_none();
    for (int i = 0; i < 4; ++i) s = spline::fcc_splits_with(s, t[i], ta, tb);
    return s;
  }
};

}  // namespace

std::unique_ptr<Reconstruction> makeReconstruction(std::string_view name) {
  const ReconstructionInfo& info = findReconstruction(name);
  switch (info.deviceId) {
    case FCC_RECON_TRILINEAR: return std::make_unique<Trilinear>(info);
    case FCC_RECON_TRICUBIC: return std::make_unique<Tricubic>(info);  // both B-splines: the prefilter differs
    case FCC_RECON_TYPE6: return std::make_unique<Type6>(info);
    case FCC_RECON_BARYCENTRIC: return std::make_unique<Barycentric>(info);
    case FCC_RECON_SHEARED_TRILINEAR: return std::make_unique<ShearedTrilinear>(info);
    case FCC_RECON_BILINEAR_SPATIAL: return std::make_unique<PlaneScheme>(info, 1);
    case FCC_RECON_BILINEAR: return std::make_unique<PlaneScheme>(info, 0);
    default: return std::make_unique<BoxSpline>(info);
  }
}

}  // namespace fcc

