#include "VdbResampleField.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sparse/CubicBSpline.h"
#include "sparse/Error.h"

namespace fcc::io {
namespace {

// A cubic B-spline at position p reads the coefficients floor(p) - 1 .. floor(p) + 2.
constexpr int kSplineBelow = 1, kSplineAbove = 2;

}  // namespace

VdbResampleField::VdbResampleField(std::shared_ptr<const VdbLeafReader> reader, double spacing, float background)
    : source_(reader, static_cast<const openvdb::FloatGrid&>(*reader->grid()).background()),
      spacing_(spacing),
      background_(background) {
  const SiteBox data = source_.bounds();
  if (!data.empty()) bounds_ = sitesReaching(data);
}

SiteBox VdbResampleField::sitesReaching(const SiteBox& source) const {
  // The sites whose positions lie within the prefilter's and the spline's reach of the source box.
  const int pad = kBSplinePrefilterReach + kSplineAbove;
  return {glm::ivec3(glm::ceil(glm::dvec3(source.min - pad) / spacing_)),
          glm::ivec3(glm::floor(glm::dvec3(source.max + pad) / spacing_))};
}

SiteBox VdbResampleField::sourceReach(const SiteBox& box) const {
  const glm::ivec3 lo = glm::ivec3(glm::floor(glm::dvec3(box.min) * spacing_)) - kSplineBelow;
  const glm::ivec3 hi = glm::ivec3(glm::floor(glm::dvec3(box.max) * spacing_)) + kSplineAbove;
  return SiteBox{lo, hi}.expandedBy(kBSplinePrefilterReach);
}

bool VdbResampleField::mayHoldData(const SiteBox& box) const {
  return box.intersects(bounds_) && source_.mayHoldData(sourceReach(box));
}

bool VdbResampleField::uniformOver(const SiteBox& box, float& value) const {
  return source_.uniformOver(sourceReach(box), value);
}

bool VdbResampleField::forEachDataBox(const SiteBox& region, const std::function<void(const SiteBox&)>& visit) const {
  return source_.forEachDataBox(sourceReach(region), [&](const SiteBox& data) { visit(sitesReaching(data)); });
}

void VdbResampleField::prepare(const std::vector<SiteBox>& boxes) const {
  std::vector<SiteBox> reach;
  reach.reserve(boxes.size());
  for (const SiteBox& b : boxes) reach.push_back(sourceReach(b));
  source_.prepare(reach);
}

void VdbResampleField::fill(const SiteBox& box, float* out) const {
  const glm::ivec3 dim = box.dim();
  const size_t count = size_t(dim.x) * dim.y * dim.z;
  const SiteBox reach = sourceReach(box);
  float uniform = 0.0f;
  if (source_.uniformOver(reach, uniform)) {  // exactly the value: what uniformOver promised the builder
    std::fill_n(out, count, uniform);
    return;
  }
  // The source samples over the reach become B-spline coefficients, line by line along each axis.
  // Only the coefficients the spline reads (the reach without the prefilter's padding) are kept, so
  // each pass filters only the lines the next one needs: x over all, y over the kept x, z over the
  // kept x and y.
  thread_local std::vector<float> c;
  const glm::ivec3 n = reach.dim();
  // A coarse lattice makes a block reach far: refuse what would not fit rather than fail for memory.
  constexpr uint64_t kMaxReachVoxels = uint64_t(1) << 26;  // 256 MiB of floats per thread
  if (uint64_t(n.x) * uint64_t(n.y) * uint64_t(n.z) > kMaxReachVoxels)
    throw ValueError("resampling at a spacing of " + std::to_string(spacing_) + " source voxels: a block of 16 sites reads " +
                     std::to_string(n.x) + "^3 source voxels, more than " + std::to_string(kMaxReachVoxels) +
                     "; use a smaller --scale or more --samples");
  c.resize(size_t(n.x) * n.y * n.z);
  source_.fill(reach, c.data());
  const ptrdiff_t sy = n.x, sz = ptrdiff_t(n.x) * n.y;
  constexpr int pad = kBSplinePrefilterReach;
  const int keptX = n.x - 2 * pad;
  for (int z = 0; z < n.z; ++z) bsplinePrefilterLines(c.data() + z * sz, n.x, 1, n.y, sy);
  for (int z = 0; z < n.z; ++z) bsplinePrefilterLines(c.data() + z * sz + pad, n.y, sy, keptX, 1);
  for (int y = pad; y < n.y - pad; ++y) bsplinePrefilterLines(c.data() + y * sy + pad, n.z, sz, keptX, 1);

  for (int z = box.min.z; z <= box.max.z; ++z)
    for (int y = box.min.y; y <= box.max.y; ++y)
      for (int x = box.min.x; x <= box.max.x; ++x, ++out) {
        if ((x + y + z) & 1) {  // not an FCC site: never read
          *out = background_;
          continue;
        }
        const double sum = cubicBSplineAt(glm::dvec3(x, y, z) * spacing_, [&](const glm::ivec3& ijk) {
          const glm::ivec3 l = ijk - reach.min;
          return c[size_t(l.z * sz + l.y * sy + l.x)];
        });
        *out = float(sum);
      }
}

float VdbResampleField::sample(const glm::ivec3& ijk) const {
  float v = 0.0f;
  fill(SiteBox{ijk, ijk}, &v);
  return v;
}

}  // namespace fcc::io
