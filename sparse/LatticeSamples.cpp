#include "LatticeSamples.h"

#include <tbb/parallel_for.h>

#include "CubicBSpline.h"
#include "Error.h"

namespace fcc {

LatticeSamples::LatticeSamples(Lattice lattice, const glm::ivec3& origin, const glm::ivec3& dims, float background)
    : lattice_(lattice), origin_(origin), dims_(dims), background_(background),
      values_(size_t(dims.x) * dims.y * dims.z, background) {}

void LatticeSamples::fill(const std::function<float(const glm::ivec3&)>& valueAt) {
  tbb::parallel_for(0, dims_.z, [&](int z) {
    for (int y = 0; y < dims_.y; ++y)
      for (int x = 0; x < dims_.x; ++x) {
        const glm::ivec3 ijk = origin_ + glm::ivec3(x, y, z);
        if (isLatticeSite(lattice_, ijk)) values_[index({x, y, z})] = valueAt(ijk);
      }
  });
}

void LatticeSamples::prefilter(Prefilter prefilter) {
  if (prefilter == Prefilter::None) return;
  if (prefilter == Prefilter::Fcc) {
    if (lattice_ != Lattice::Fcc) throw ValueError("the FCC prefilter needs FCC samples");
    std::vector<float> coefficients(values_.size(), background_);
    tbb::parallel_for(0, dims_.z, [&](int z) {
      for (int y = 0; y < dims_.y; ++y)
        for (int x = 0; x < dims_.x; ++x) {
          const glm::ivec3 ijk = origin_ + glm::ivec3(x, y, z);
          if (isLatticeSite(lattice_, ijk))
            coefficients[index({x, y, z})] = spline::prefilterAt(ijk, [&](const glm::ivec3& s) { return at(s); });
        }
    });
    values_.swap(coefficients);
    return;
  }
  if (lattice_ != Lattice::Cc) throw ValueError("the cubic B-spline prefilter needs Cartesian samples");
  const ptrdiff_t sx = 1, sy = dims_.x, sz = ptrdiff_t(dims_.x) * dims_.y;
  // Lines along x: one per (y, z); along y: one per (x, z); along z: one per (x, y).
  tbb::parallel_for(0, dims_.z, [&](int z) {
    for (int y = 0; y < dims_.y; ++y) bsplinePrefilterLine(&values_[index({0, y, z})], dims_.x, sx);
  });
  tbb::parallel_for(0, dims_.z, [&](int z) {
    bsplinePrefilterLines(&values_[index({0, 0, z})], dims_.y, sy, dims_.x, 1);
  });
  tbb::parallel_for(0, dims_.y, [&](int y) {
    bsplinePrefilterLines(&values_[index({0, y, 0})], dims_.z, sz, dims_.x, 1);
  });
}

}  // namespace fcc
