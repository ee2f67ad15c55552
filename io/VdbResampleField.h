// `convert --mode resample` of a Cartesian float grid, out of core: the sample at FCC site ijk is the
// interpolating cubic B-spline of the source (the grid extended by its background, tiles included) at
// source index position ijk * h. The B-spline's coefficients are computed per block from the source
// samples around it (a separable recursive prefilter over the block's reach, padded by
// kBSplinePrefilterReach voxels, beyond which the filter's response is below float precision), so
// nothing is densified: only the leaves near a block are decoded (VdbSourceField), and a block whose
// reach is one constant value is that value, a tile (a level set's inside and outside).
#pragma once

#include <memory>

#include "VdbSourceField.h"

namespace fcc::io {

class VdbResampleField final : public SampleField {
 public:
  // `reader` holds a float grid; `spacing` is h in source voxels; `background` the field's value where
  // it holds none (sites outside bounds()).
  VdbResampleField(std::shared_ptr<const VdbLeafReader> reader, double spacing, float background);

  float sample(const glm::ivec3& ijk) const override;
  SiteBox bounds() const override { return bounds_; }
  bool mayHoldData(const SiteBox& box) const override;
  float background() const override { return background_; }
  void fill(const SiteBox& box, float* out) const override;
  bool uniformOver(const SiteBox& box, float& value) const override;
  bool forEachDataBox(const SiteBox& region, const std::function<void(const SiteBox&)>& visit) const override;
  void prepare(const std::vector<SiteBox>& boxes) const override;

  // The source voxels whose samples the sites of `box` depend on.
  SiteBox sourceReach(const SiteBox& box) const;
  // The sites that depend on the source voxels of `source` (the inverse of sourceReach).
  SiteBox sitesReaching(const SiteBox& source) const;

 private:
  VdbSourceField source_;  // the source's samples, unmapped (its own background)
  double spacing_;
  float background_;
  SiteBox bounds_;
};

}  // namespace fcc::io
