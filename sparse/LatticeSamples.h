// A dense box of one lattice's site values in memory: what `compare` samples an analytic field into,
// and what the reconstruction tests read. Values of every integer point are stored (x fastest); only
// the lattice's sites are meaningful, the rest read as the background (a BCC box wastes 3/4 of its
// memory, an FCC box 1/2: `compare`'s budgets are small enough for that to be simpler than packing).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <vector>

#include "Reconstruction.h"

namespace fcc {

class LatticeSamples {
 public:
  LatticeSamples(Lattice lattice, const glm::ivec3& origin, const glm::ivec3& dims, float background = 0.0f);

  Lattice lattice() const { return lattice_; }
  const glm::ivec3& origin() const { return origin_; }
  const glm::ivec3& dims() const { return dims_; }

  // Sets every site of the box to valueAt(ijk) (in parallel: valueAt must be thread-safe).
  void fill(const std::function<float(const glm::ivec3&)>& valueAt);
  // The value at a site of the box; the background outside it or off the lattice.
  float at(const glm::ivec3& ijk) const {
    const glm::ivec3 r = ijk - origin_;
    if (r.x < 0 || r.y < 0 || r.z < 0 || r.x >= dims_.x || r.y >= dims_.y || r.z >= dims_.z) return background_;
    if (!isLatticeSite(lattice_, ijk)) return background_;
    return values_[index(r)];
  }
  SiteValue accessor() const {
    return [this](const glm::ivec3& ijk) { return at(ijk); };
  }
  // Samples -> coefficients, in place. Prefilter::Fcc: q_fcc at every site (neighbours outside the box
  // read the background); CubicBSpline (CC only): the interpolating filter along x, y, z, each line
  // mirrored at the box's faces (pad the box by kBSplinePrefilterReach to be exact inside).
  void prefilter(Prefilter prefilter);

 private:
  size_t index(const glm::ivec3& r) const { return (size_t(r.z) * dims_.y + r.y) * dims_.x + r.x; }
  Lattice lattice_;
  glm::ivec3 origin_, dims_;
  float background_;
  std::vector<float> values_;
};

}  // namespace fcc
