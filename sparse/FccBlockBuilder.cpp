#include "FccBlockBuilder.h"

#include <cmath>

#include "Lattice.h"
#include "Spline.h"

namespace fcc {
namespace {

constexpr int kLeafDim = FccBlockBuilder::Leaf::DIM;  // packed voxels per leaf side
static_assert(kLeafDim == 8, "block arithmetic assumes 8^3 leaves");

}  // namespace

FccBlockBuilder::FccBlockBuilder(const SampleField& field, const BuildOptions& options)
    : field_(field), options_(options), bounds_(field.bounds()) {
  if (bounds_.empty()) return;
  // Coefficients differ from the background up to one neighbour step outside the data.
  const int halo = options_.prefilter ? 1 : 0;
  const glm::ivec3 blockMin = ((bounds_.min - halo) >> 1) >> 3, blockMax = ((bounds_.max + halo) >> 1) >> 3;
  blocks_ = openvdb::CoordBBox(openvdb::Coord(blockMin.x, blockMin.y, blockMin.z),
                               openvdb::Coord(blockMax.x, blockMax.y, blockMax.z));
}

std::unique_ptr<FccBlockBuilder::Leaf> FccBlockBuilder::build(const openvdb::Coord& block, Scratch& samples,
                                                              SampleRange* range) const {
  const float background = field_.background();
  const int halo = options_.prefilter ? 1 : 0;
  const glm::ivec3 leafOrigin = glm::ivec3(block.x(), block.y(), block.z()) * kLeafDim;  // packed voxel
  const SiteBox siteBox{2 * leafOrigin - halo, 2 * leafOrigin + 2 * kLeafDim - 1 + halo};
  if (!field_.mayHoldData(siteBox)) return nullptr;

  samples.side = 2 * kLeafDim + 2 * halo;
  samples.values.resize(size_t(samples.side) * samples.side * samples.side);
  samples.origin = siteBox.min;
  for (int z = 0; z < samples.side; ++z)
    for (int y = 0; y < samples.side; ++y)
      for (int x = 0; x < samples.side; ++x) {
        const glm::ivec3 ijk = samples.origin + glm::ivec3(x, y, z);
        samples.values[size_t((z * samples.side + y) * samples.side + x)] =
            spline::isFccSite(ijk) ? field_.sample(ijk) : background;
      }

  auto leaf = std::make_unique<Leaf>(openvdb::Coord(leafOrigin.x, leafOrigin.y, leafOrigin.z),
                                     openvdb::Vec4f(background), false);
  bool anyActive = false;
  for (openvdb::Index n = 0; n < Leaf::SIZE; ++n) {
    const openvdb::Coord xyz = leaf->offsetToGlobalCoord(n);
    const glm::ivec3 packed(xyz.x(), xyz.y(), xyz.z());
    openvdb::Vec4f value;
    bool active = false;
    for (int c = 0; c < 4; ++c) {
      const glm::ivec3 site = siteOfChannel(packed, c);
      const float v = samples.at(site);
      if (range && glm::all(glm::greaterThanEqual(site, bounds_.min)) && glm::all(glm::lessThanEqual(site, bounds_.max)))
        range->add(v);
      value[c] = options_.prefilter ? spline::prefilterAt(site, [&](const glm::ivec3& s) { return samples.at(s); }) : v;
      active = active || !(std::abs(value[c] - background) <= options_.tolerance);
    }
    if (active) {
      leaf->setValueOn(n, value);
      anyActive = true;
    }
  }
  if (!anyActive) return nullptr;
  return leaf;
}

}  // namespace fcc
