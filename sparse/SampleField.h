// A scalar field sampled at FCC sites, the input of the FCC grid builder: a Cartesian volume
// subsampled or resampled, or a synthetic function.
#pragma once

#include <glm/glm.hpp>

#include <functional>
#include <vector>

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
  bool contains(const glm::ivec3& ijk) const {
    return glm::all(glm::greaterThanEqual(ijk, min)) && glm::all(glm::lessThanEqual(ijk, max));
  }
  SiteBox intersection(const SiteBox& o) const { return {glm::max(min, o.min), glm::min(max, o.max)}; }
  SiteBox expandedBy(int n) const { return {min - n, max + n}; }
  glm::ivec3 dim() const { return max - min + 1; }
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

  // The samples at every integer point of `box` (x fastest, then y, then z) into `out`; points that are
  // not FCC sites may hold anything. Sparse sources override it to copy whole rows.
  virtual void fill(const SiteBox& box, float* out) const;

  // True (and the value) only if every site of `box` holds one value: lets the builder make a tile of
  // a block without visiting its sites. False is always correct.
  virtual bool uniformOver(const SiteBox& box, float& value) const { return false; }

  // Sparse sources: calls `visit` with boxes that together cover every site of `region` that may hold
  // a non-background sample (boxes may reach outside `region`), and returns true. False: the field
  // cannot tell, and every block of the region is built. Called from several threads at once (on
  // different regions): it must only read.
  virtual bool forEachDataBox(const SiteBox& region, const std::function<void(const SiteBox&)>& visit) const {
    return false;
  }

  // Out-of-core sources: makes the samples inside `boxes` readable by sample()/fill() from any thread
  // until the next call, which may release everything else. Called by one thread, between builds
  // (const: what it changes is a cache, not the field).
  virtual void prepare(const std::vector<SiteBox>& boxes) const {}
};

inline void SampleField::fill(const SiteBox& box, float* out) const {
  for (int z = box.min.z; z <= box.max.z; ++z)
    for (int y = box.min.y; y <= box.max.y; ++y)
      for (int x = box.min.x; x <= box.max.x; ++x)
        *out++ = ((x + y + z) & 1) == 0 ? sample(glm::ivec3(x, y, z)) : background();
}

}  // namespace fcc
