#include "BccGrids.h"

#include "CartesianGridBuilder.h"

namespace fcc {
namespace {

// The coset voxels whose sites 2m + c lie in `box`: m in [ceil((min - c) / 2), floor((max - c) / 2)].
SiteBox cosetBox(const SiteBox& box, int coset) {
  const auto floorDiv2 = [](int v) { return v >= 0 ? v / 2 : -((1 - v) / 2); };
  SiteBox m;
  for (int a = 0; a < 3; ++a) {
    m.min[a] = -floorDiv2(-(box.min[a] - coset));
    m.max[a] = floorDiv2(box.max[a] - coset);
  }
  return m;
}

}  // namespace

openvdb::math::Transform::Ptr bccCosetTransform(const openvdb::math::Transform& worldFromIndex, int coset) {
  openvdb::math::Transform::Ptr xform = worldFromIndex.copy();
  // Applied to a voxel m before the BCC map: first + c/2, then x 2, so m -> 2m + c.
  xform->preScale(2.0);
  if (coset != 0) xform->preTranslate(openvdb::Vec3d(0.5));
  return xform;
}

BccGrids buildBccGrids(const SiteBox& box, float background, const std::function<float(const glm::ivec3&)>& value,
                       const openvdb::math::Transform& worldFromIndex, openvdb::GridClass gridClass,
                       const std::function<bool(const SiteBox&)>& mayHoldData) {
  BccGrids grids;
  for (int coset = 0; coset < 2; ++coset) {
    const glm::ivec3 shift(coset);
    std::function<bool(const SiteBox&)> cosetMayHoldData;
    if (mayHoldData)
      cosetMayHoldData = [&](const SiteBox& m) { return mayHoldData(SiteBox{2 * m.min + shift, 2 * m.max + shift}); };
    openvdb::FloatGrid::Ptr grid = buildCartesianGrid(
        cosetBox(box, coset), background, [&](const glm::ivec3& m) { return value(2 * m + shift); }, cosetMayHoldData);
    grid->setTransform(bccCosetTransform(worldFromIndex, coset));
    grid->setName(coset == 0 ? kBccPrimaryGridName : kBccSecondaryGridName);
    grid->setGridClass(gridClass);
    grid->insertMeta("lattice", openvdb::StringMetadata("bcc"));
    grid->insertMeta("bcc_coset", openvdb::StringMetadata(coset == 0 ? "primary" : "secondary"));
    (coset == 0 ? grids.primary : grids.secondary) = grid;
  }
  return grids;
}

}  // namespace fcc
