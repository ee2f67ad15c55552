#include "DenseSlabField.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <tuple>

#include "sparse/CubicBSpline.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

constexpr int kBlockSites = 16;  // sites along an axis of an output block (8 packed voxels)
constexpr int kNodeBlocks = 16;  // blocks along an axis of a level-1 internal node

bool isSite(int x, int y, int z) { return ((x + y + z) & 1) == 0; }

// CubicBSplineVolume's boundary: the coefficients mirrored at the first and last voxel.
int mirror(int a, int n) {
  if (a >= 0 && a < n) return a;
  if (n == 1) return 0;
  const int period = 2 * n - 2;
  a = ((a % period) + period) % period;
  return a < n ? a : period - a;
}

}  // namespace

DenseSlabField::GroupKey DenseSlabField::groupOf(const SiteBox& sites) {
  // The block of the box's centre: a block's sample box is its sites and a halo, both ways.
  const glm::ivec3 block = ((sites.min + sites.max) >> 1) >> 4;
  static_assert(kBlockSites == 16 && kNodeBlocks == 16, "shifts below assume 16");
  return {block.x, block.y >> 4, block.z >> 4};
}

void DenseSlabField::prepare(const std::vector<SiteBox>& boxes) const {
  std::vector<std::pair<GroupKey, SiteBox>> wanted;
  wanted.reserve(boxes.size());
  for (const SiteBox& sites : boxes) {
    const SiteBox voxels = voxelsFor(sites);
    if (!voxels.empty()) wanted.emplace_back(groupOf(sites), voxels);
  }
  std::sort(wanted.begin(), wanted.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  regions_.clear();
  byGroup_.clear();
  for (size_t i = 0; i < wanted.size(); ++i) {
    if (i == 0 || wanted[i].first != wanted[i - 1].first) {
      byGroup_.emplace_back(wanted[i].first, regions_.size());
      regions_.push_back(Region{wanted[i].second, {}});
    } else {
      SiteBox& box = regions_.back().voxels;
      box = {glm::min(box.min, wanted[i].second.min), glm::max(box.max, wanted[i].second.max)};
    }
  }
  tbb::parallel_for(size_t(0), regions_.size(), [&](size_t r) {
    Region& region = regions_[r];
    const glm::ivec3 d = region.voxels.dim();
    region.values.resize(size_t(d.x) * size_t(d.y) * size_t(d.z));
    scratch_->read(region.voxels, region.values.data());
  });
}

const DenseSlabField::Region& DenseSlabField::regionFor(const SiteBox& sites) const {
  const SiteBox voxels = voxelsFor(sites);
  auto holds = [&](const Region& r) { return r.voxels.contains(voxels.min) && r.voxels.contains(voxels.max); };
  const GroupKey key = groupOf(sites);
  const auto it = std::lower_bound(byGroup_.begin(), byGroup_.end(), key,
                                   [](const auto& entry, const GroupKey& k) { return entry.first < k; });
  if (it != byGroup_.end() && it->first == key && holds(regions_[it->second])) return regions_[it->second];
  for (const Region& r : regions_)  // a box prepare() was not given as a block's: any region holding it
    if (holds(r)) return r;
  throw Error("internal: dense samples read outside what the field was prepared for");
}

float DenseSlabSubsampleField::sample(const glm::ivec3& ijk) const {
  if (!bounds().contains(ijk)) return background_;
  return regionFor(SiteBox{ijk, ijk}).at(ijk);
}

void DenseSlabSubsampleField::fill(const SiteBox& box, float* out) const {
  const glm::ivec3 d = box.dim();
  const SiteBox inside = voxelsFor(box);
  if (inside.empty()) {
    std::fill(out, out + size_t(d.x) * d.y * d.z, background_);
    return;
  }
  const Region& region = regionFor(box);
  for (int z = box.min.z; z <= box.max.z; ++z)
    for (int y = box.min.y; y <= box.max.y; ++y) {
      float* row = out + (size_t(z - box.min.z) * d.y + size_t(y - box.min.y)) * d.x;
      if (y < inside.min.y || y > inside.max.y || z < inside.min.z || z > inside.max.z) {
        std::fill(row, row + d.x, background_);
        continue;
      }
      for (int x = box.min.x; x <= box.max.x; ++x)
        row[x - box.min.x] = x < inside.min.x || x > inside.max.x ? background_ : region.at(glm::ivec3(x, y, z));
    }
}

DenseSlabResampleField::DenseSlabResampleField(std::shared_ptr<const SlabScratch> coefficients, float background,
                                               double spacingInVoxels)
    : DenseSlabField(std::move(coefficients), background), spacing_(spacingInVoxels) {
  latticeMax_ = glm::ivec3(glm::floor(glm::dvec3(scratch_->dims() - 1) / spacing_ + 1e-9));  // as DenseResampleField
}

SiteBox DenseSlabResampleField::voxelsFor(const SiteBox& sites) const {
  const SiteBox inside = sites.intersection(bounds());
  if (inside.empty()) return {};
  const glm::dvec3 last(scratch_->dims() - 1);
  const glm::ivec3 lo = glm::ivec3(glm::floor(glm::clamp(glm::dvec3(inside.min) * spacing_, glm::dvec3(0.0), last))) - 1;
  const glm::ivec3 hi = glm::ivec3(glm::floor(glm::clamp(glm::dvec3(inside.max) * spacing_, glm::dvec3(0.0), last))) + 2;
  // Points beyond a face read mirrored ones: -1 reads 1, n reads n - 2, n + 1 reads n - 3 (>= lo - 2).
  return {glm::max(lo - 2, glm::ivec3(0)), glm::min(hi, scratch_->dims() - 1)};
}

float DenseSlabResampleField::evaluate(const Region& region, const glm::ivec3& ijk) const {
  const glm::ivec3 dims = scratch_->dims();
  const glm::dvec3 xyz = glm::clamp(glm::dvec3(ijk) * spacing_, glm::dvec3(0.0), glm::dvec3(dims - 1));
  return float(cubicBSplineAt(xyz, [&](const glm::ivec3& c) {
    return region.at(glm::ivec3(mirror(c.x, dims.x), mirror(c.y, dims.y), mirror(c.z, dims.z)));
  }));
}

float DenseSlabResampleField::sample(const glm::ivec3& ijk) const {
  if (!bounds().contains(ijk)) return background_;
  return evaluate(regionFor(SiteBox{ijk, ijk}), ijk);
}

void DenseSlabResampleField::fill(const SiteBox& box, float* out) const {
  const glm::ivec3 d = box.dim();
  if (voxelsFor(box).empty()) {
    std::fill(out, out + size_t(d.x) * d.y * d.z, background_);
    return;
  }
  const Region& region = regionFor(box);
  const SiteBox lattice = bounds();
  for (int z = box.min.z; z <= box.max.z; ++z)
    for (int y = box.min.y; y <= box.max.y; ++y)
      for (int x = box.min.x; x <= box.max.x; ++x) {
        const glm::ivec3 ijk(x, y, z);
        *out++ = isSite(x, y, z) && lattice.contains(ijk) ? evaluate(region, ijk) : background_;
      }
}

std::shared_ptr<const SlabScratch> slabsOfSamples(DenseSource& source, openvdb::util::NullInterrupter* progress) {
  return std::make_shared<SlabScratch>(source, SlabScratch::SliceTransform{}, progress);
}

std::shared_ptr<const SlabScratch> slabsOfCoefficients(DenseSource& source, openvdb::util::NullInterrupter* progress) {
  const glm::ivec3 dims = source.geometry().dims;
  auto alongXAndY = [dims](float* slices, int count) {
    tbb::parallel_for(0, count, [&](int k) {
      float* slice = slices + size_t(k) * size_t(dims.x) * size_t(dims.y);
      // The x-lines one by one (each is contiguous), the y-lines side by side (they vectorise).
      for (int y = 0; y < dims.y; ++y) bsplinePrefilterLine(slice + size_t(y) * size_t(dims.x), dims.x, 1);
      bsplinePrefilterLines(slice, dims.y, dims.x, dims.x, 1);
    });
  };
  auto scratch = std::make_shared<SlabScratch>(source, alongXAndY, progress);
  scratch->transformAlongZ(bsplinePrefilterLines);
  return scratch;
}

}  // namespace fcc::io
