// A scalar field sampled at FCC sites, the input of the FCC grid builder: a Cartesian volume
// subsampled or resampled, or a synthetic function.
#pragma once

#include <glm/glm.hpp>

namespace fcc {

inline int minComponent(const glm::ivec3& v) { return glm::min(v.x, glm::min(v.y, v.z)); }

// Inclusive box of integer points in the lattice's index space.
struct SiteBox {
  glm::ivec3 min{0};
  glm::ivec3 max{-1};
  bool empty() const { return glm::any(glm::lessThan(max, min)); }
  bool intersects(const SiteBox& o) const {
    return !empty() && !o.empty() && glm::all(glm::lessThanEqual(min, o.max)) && glm::all(glm::lessThanEqual(o.min, max));
  }
};

class SampleField {
 public:
  virtual ~SampleField() = default;
  // The sample V at FCC site ijk; the background outside bounds().
  virtual float sample(const glm::ivec3& ijk) const = 0;
  // Sites outside this box hold the background.
  virtual SiteBox bounds() const = 0;
  // False only if every site in `box` holds the background (lets sparse sources skip empty blocks).
  virtual bool mayHoldData(const SiteBox& box) const { return box.intersects(bounds()); }
  virtual float background() const = 0;
};

}  // namespace fcc
