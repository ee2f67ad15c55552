#include "FccBlockBuilder.h"

#include <algorithm>
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

SiteBox FccBlockBuilder::sampleBox(const openvdb::Coord& block) const {
  const int halo = options_.prefilter ? 1 : 0;
  const glm::ivec3 leafOrigin = glm::ivec3(block.x(), block.y(), block.z()) * kLeafDim;  // packed voxel
  return SiteBox{2 * leafOrigin - halo, 2 * leafOrigin + 2 * kLeafDim - 1 + halo};
}

FccBlockBuilder::Uniform FccBlockBuilder::uniform(const openvdb::Coord& block, SampleStats* stats) const {
  Uniform u;
  const SiteBox box = sampleBox(block);
  float v = 0.0f;
  if (!field_.uniformOver(box, v)) return u;
  u.known = true;
  if (!field_.mayHoldData(box)) {  // build() returns null before sampling
    u.none = true;
    return u;
  }
  // build() adds the samples of the block's own sites (no halo) inside the field's bounds.
  const int halo = options_.prefilter ? 1 : 0;
  const uint64_t ownSites = fccSiteCount(box.expandedBy(-halo).intersection(bounds_));
  if (stats && ownSites > 0) stats->add(v, ownSites);
  const float background = field_.background();
  // Every site's coefficient is the same sum of the same values: the one computed here.
  const float c = options_.prefilter ? spline::prefilterAt(glm::ivec3(0), [&](const glm::ivec3&) { return v; }) : v;
  u.none = std::abs(c - background) <= options_.tolerance;
  u.value = openvdb::Vec4f(c);
  return u;
}

std::vector<openvdb::Coord> FccBlockBuilder::blocksInSlab(int x) const {
  std::vector<openvdb::Coord> out;
  if (blocks_.empty() || x < blocks_.min().x() || x > blocks_.max().x()) return out;
  const int halo = options_.prefilter ? 1 : 0;
  // The slab's sites, and the halo a block reads beyond them.
  SiteBox region{glm::ivec3(2 * kLeafDim * x, 2 * kLeafDim * blocks_.min().y(), 2 * kLeafDim * blocks_.min().z()),
                 glm::ivec3(2 * kLeafDim * (x + 1) - 1, 2 * kLeafDim * (blocks_.max().y() + 1) - 1,
                            2 * kLeafDim * (blocks_.max().z() + 1) - 1)};
  // Marked blocks as (z, y) keys: memory and time follow the data, not the slab's area.
  std::vector<std::pair<int, int>> marked;
  const bool sparse = field_.forEachDataBox(region.expandedBy(halo), [&](const SiteBox& data) {
    // Blocks whose sample box (block sites plus halo) meets the data.
    const SiteBox reach = data.expandedBy(halo).intersection(region);
    if (reach.empty()) return;
    const glm::ivec3 lo = (reach.min >> 1) >> 3, hi = (reach.max >> 1) >> 3;
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y) marked.emplace_back(z, y);
  });
  if (sparse) {
    std::sort(marked.begin(), marked.end());
    marked.erase(std::unique(marked.begin(), marked.end()), marked.end());
    out.reserve(marked.size());
    for (const auto& [z, y] : marked) out.emplace_back(x, y, z);
    return out;
  }
  for (int z = blocks_.min().z(); z <= blocks_.max().z(); ++z)
    for (int y = blocks_.min().y(); y <= blocks_.max().y(); ++y) out.emplace_back(x, y, z);
  return out;
}

void FccBlockBuilder::prepare(const std::vector<openvdb::Coord>& blocks) const {
  std::vector<SiteBox> boxes;
  boxes.reserve(blocks.size());
  for (const openvdb::Coord& b : blocks) boxes.push_back(sampleBox(b));
  field_.prepare(boxes);
}

std::unique_ptr<FccBlockBuilder::Leaf> FccBlockBuilder::build(const openvdb::Coord& block, Scratch& samples,
                                                              SampleStats* stats) const {
  const float background = field_.background();
  const glm::ivec3 leafOrigin = glm::ivec3(block.x(), block.y(), block.z()) * kLeafDim;  // packed voxel
  const SiteBox siteBox = sampleBox(block);
  if (!field_.mayHoldData(siteBox)) return nullptr;

  samples.side = siteBox.dim().x;
  samples.values.resize(size_t(samples.side) * samples.side * samples.side);
  samples.origin = siteBox.min;
  field_.fill(siteBox, samples.values.data());

  // The prefilter's taps as offsets into the scratch (side^3, x fastest), in fcc_neighbour_offset's
  // order: the same sums in the same order as spline::prefilterAt, so the same bits, without the
  // per-tap index arithmetic (this loop is most of a conversion's leaf building).
  const int side = samples.side;
  int taps[12];
  for (int k = 0; k < 12; ++k) {
    const glm::ivec3 d = spline::fcc_neighbour_offset(k);
    taps[k] = (d.z * side + d.y) * side + d.x;
  }
  // Whether every site of the block (halo apart) lies in the field's bounds: then no site needs the test.
  const SiteBox own = options_.prefilter ? siteBox.expandedBy(-1) : siteBox;
  const bool ownInside = glm::all(glm::greaterThanEqual(own.min, bounds_.min)) && glm::all(glm::lessThanEqual(own.max, bounds_.max));
  const float* values = samples.values.data();
  auto leaf = std::make_unique<Leaf>(openvdb::Coord(leafOrigin.x, leafOrigin.y, leafOrigin.z),
                                     openvdb::Vec4f(background), false);
  bool anyActive = false;
  for (openvdb::Index n = 0; n < Leaf::SIZE; ++n) {
    const glm::ivec3 packed = leafOrigin + glm::ivec3(int(n >> 6), int((n >> 3) & 7), int(n & 7));  // VDB leaf order
    openvdb::Vec4f value;
    bool active = false;
    for (int c = 0; c < 4; ++c) {
      const glm::ivec3 site = siteOfChannel(packed, c);
      const glm::ivec3 local = site - samples.origin;
      const int at = (local.z * side + local.y) * side + local.x;
      const float v = values[at];
      if (stats && (ownInside || (glm::all(glm::greaterThanEqual(site, bounds_.min)) &&
                                  glm::all(glm::lessThanEqual(site, bounds_.max)))))
        stats->add(v);
      if (options_.prefilter) {
        float neighbourSum = 0.0f;
        for (int k = 0; k < 12; ++k) neighbourSum += values[at + taps[k]];
        value[c] = spline::fcc_prefilter(v, neighbourSum);
      } else {
        value[c] = v;
      }
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
