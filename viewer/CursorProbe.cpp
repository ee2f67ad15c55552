#include "CursorProbe.h"

#include <cmath>

#include "sparse/Lattice.h"
#include "sparse/Spline.h"

namespace fcc::render {
namespace {
constexpr std::size_t kMaxBricksKept = 64;  // a 2-site stencil at a brick corner needs 8
}  // namespace

glm::ivec3 nearestFccSite(const glm::dvec3& xyz) {
  glm::ivec3 ijk(int(std::lround(xyz.x)), int(std::lround(xyz.y)), int(std::lround(xyz.z)));
  if (((ijk.x + ijk.y + ijk.z) & 1) != 0) {
    // The nearest integer point is not a site: move the coordinate that rounded furthest the other way.
    const glm::dvec3 off = xyz - glm::dvec3(ijk);
    int k = 0;
    for (int c = 1; c < 3; ++c)
      if (std::abs(off[c]) > std::abs(off[k])) k = c;
    ijk[k] += off[k] >= 0.0 ? 1 : -1;
  }
  return ijk;
}

float SplineProbe::coefficientAt(const glm::ivec3& ijk) {
  const glm::ivec3 packed = packedVoxelOfSite(ijk);
  const glm::ivec3 brick(int(std::floor(packed.x / double(kBrickPackedDim))), int(std::floor(packed.y / double(kBrickPackedDim))),
                         int(std::floor(packed.z / double(kBrickPackedDim))));
  const auto key = std::make_tuple(brick.x, brick.y, brick.z);
  auto it = bricks_.find(key);
  if (it == bricks_.end()) {
    if (bricks_.size() >= kMaxBricksKept) bricks_.clear();
    auto values = std::make_unique<io::BrickValues>();
    store_.readBrick(brick, *values);
    it = bricks_.emplace(key, std::move(values)).first;
  }
  const glm::ivec3 local = packed - brick * kBrickPackedDim;  // OpenVDB's leaf order: x major
  const int offset = (local.x * kBrickPackedDim + local.y) * kBrickPackedDim + local.z;
  return (*it->second)[std::size_t(offset)][channelOfSite(ijk)];
}

float SplineProbe::valueAt(const glm::dvec3& xyz) {
  return spline::evaluate(glm::vec3(xyz), [&](const glm::ivec3& ijk) { return coefficientAt(ijk); });
}

CursorProbe probePoint(const glm::dmat4& indexFromWorld, const Camera& camera, int px, int py, int width, int height,
                       float depth) {
  CursorProbe p;
  if (!std::isfinite(depth)) return p;
  const CameraFrame frame = cameraFrame(camera, double(width) / double(height));
  p.hit = true;
  p.pWorld = frame.eye + double(depth) * pixelRay(frame, px, py, width, height);
  p.xyz = glm::dvec3(indexFromWorld * glm::dvec4(p.pWorld, 1.0));
  return p;
}

CursorProbe probeSurface(SplineProbe& spline, const glm::dmat4& indexFromWorld, const Camera& camera, int px, int py,
                         int width, int height, float depth) {
  CursorProbe p = probePoint(indexFromWorld, camera, px, py, width, height, depth);
  if (!p.hit) return p;
  p.values = true;
  p.ijk = nearestFccSite(p.xyz);
  p.valueAtSite = spline.valueAt(glm::dvec3(p.ijk));
  p.valueAtPoint = spline.valueAt(p.xyz);
  return p;
}

}  // namespace fcc::render
