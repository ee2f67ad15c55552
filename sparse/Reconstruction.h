// The reconstruction layer's C++ face: which lattices and reconstructions exist, what each promises
// (its contract, in OpenVDB's sampler style: stencil, degree along a ray, what it reproduces, its
// continuity), and a CPU evaluation of each over any source of site values.
//
// The mathematics lives in one header per reconstruction, compiled as C++, OpenCL C and GLSL
// (sparse/FccSpline.h, CcTrilinear.h, CcTricubic.h, BccBarycentric.h, BccShearedTrilinear.h,
// BccBilinear.h); the classes here only locate the piece, gather its stencil and call those functions,
// so the CPU path is the device paths' reference (tests/sparse/test_reconstructions.cpp).
//
// Index spaces: each lattice's sites are integer points of its own index space (CC: all of them;
// BCC: the three coordinates of one parity; FCC: an even coordinate sum). `xyz` is a position there.
#pragma once

#include <glm/glm.hpp>

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "Spline.h"

namespace fcc {

enum class Lattice { Cc, Bcc, Fcc };

std::string_view latticeName(Lattice lattice);  // "cc", "bcc", "fcc"
// Sites per unit volume of the lattice's index space: 1, 1/4, 1/2.
double latticeDensity(Lattice lattice);
bool isLatticeSite(Lattice lattice, const glm::ivec3& ijk);

// What turns samples into the coefficients a reconstruction reads.
enum class Prefilter {
  None,          // the samples themselves
  Fcc,           // q_fcc (FccSpline.h's fcc_prefilter over the 12 nearest neighbours)
  CubicBSpline,  // the interpolating cubic B-spline prefilter along each axis (CubicBSpline.h)
};

struct ReconstructionInfo {
  std::string_view name;  // as `compare` and `render --reconstruction` name it
  Lattice lattice;
  std::string_view description;
  int stencil;       // coefficients read per evaluation
  int rayDegree;     // degree in the ray parameter of one piece along a ray (hits are exact roots)
  int reproduces;    // the highest degree of polynomials reproduced exactly (-1: not even constants)
  int continuity;    // -1 discontinuous, 0 C0, 1 C1, 2 C2
  bool viewDependent;  // its pieces depend on the view direction (BCC's plane stacks)
  Prefilter prefilter;
  int deviceId;  // the evaluation sparse/ReconDispatch.h knows it by (FCC_RECON_*); one per class below
};

// Every reconstruction, in the order `compare` reports them.
const std::vector<ReconstructionInfo>& reconstructionInfos();
// The one named; ValueError naming the valid ones otherwise.
const ReconstructionInfo& findReconstruction(std::string_view name);
// The names, comma-separated (of `lattice` only, when given).
std::string reconstructionNames(const Lattice* lattice = nullptr);

// The coefficient at a site (after the prefilter).
using SiteValue = std::function<float(const glm::ivec3&)>;

class Reconstruction {
 public:
  explicit Reconstruction(const ReconstructionInfo& info) : info_(info) {}
  virtual ~Reconstruction() = default;
  const ReconstructionInfo& info() const { return info_; }

  // Value and index-space gradient at xyz.
  spline::FccValueGradient evaluate(const glm::vec3& xyz, const SiteValue& at) const { return evaluateInPiece(xyz, xyz, at); }
  // The polynomial of the piece holding `inside`, at xyz (continued past the piece's faces).
  virtual spline::FccValueGradient evaluateInPiece(const glm::vec3& inside, const glm::vec3& xyz,
                                                   const SiteValue& at) const = 0;
  // Where the ray o + t d crosses piece boundaries inside the unit cell [cell, cell + 1]^3, in (ta, tb).
  virtual spline::FccSplits cellSplits(const glm::ivec3& cell, const glm::vec3& o, const glm::vec3& d, float ta,
                                       float tb) const = 0;
  // The view direction (index space) for view-dependent schemes; the default stack is normal to z
  // with positive shears. Others ignore it.
  virtual void setView(const glm::vec3& /*dIndex*/) {}

 private:
  const ReconstructionInfo& info_;
};

std::unique_ptr<Reconstruction> makeReconstruction(std::string_view name);

// The id sparse/ReconDispatch.h's device dispatch knows it by (FCC_RECON_*).
inline int reconstructionDeviceId(const ReconstructionInfo& info) { return info.deviceId; }

}  // namespace fcc
