// Shared by the renderer tests on Cartesian grids (and BCC datasets): a smooth test field, writing it as
// a float grid (or as BCC cosets), and rendering a Cartesian .vdb through the library as `render
// --reconstruction` does.
#pragma once

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include <glm/glm.hpp>

#include "io/CartesianBrickStore.h"
#include "io/VdbFile.h"
#include "sparse/BccGrids.h"
#include "sparse/ReferenceRaycast.h"
#include "viewer/CartesianBrickSource.h"
#include "tests/viewer/RenderTestSupport.h"
#include "viewer/Raycaster.h"

namespace fcc::test {

inline constexpr int kDim = 48;  // grid points per axis, [0, 48)^3
inline constexpr float kBackground = 2.0f;

// A smooth field with detail at several scales and orientations (values about -1 .. 1).
inline float wavy(const glm::ivec3& ijk) {
  const glm::dvec3 p = glm::dvec3(ijk) / double(kDim);
  return float(std::sin(7.0 * p.x + 1.0) * std::cos(5.0 * p.y - 0.5) + 0.6 * std::sin(9.0 * p.z + 4.0 * p.x) +
               0.3 * std::cos(13.0 * p.y + 11.0 * p.z));
}

// Writes the grid values(ijk) on [0, kDim)^3 with worldFromIndex = translate(origin) * scale(scale).
inline void writeCartesianFile(const std::string& path, const std::function<float(const glm::ivec3&)>& values, double scale,
                        const openvdb::Vec3d& origin, float background = kBackground) {
  initializeVdb();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(background);
  auto accessor = grid->getAccessor();
  for (int z = 0; z < kDim; ++z)
    for (int y = 0; y < kDim; ++y)
      for (int x = 0; x < kDim; ++x) accessor.setValue(openvdb::Coord(x, y, z), values(glm::ivec3(x, y, z)));
  auto xform = openvdb::math::Transform::createLinearTransform(scale);
  xform->postTranslate(origin);
  grid->setTransform(xform);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->setName("density");
  io::writeVdbAtomically(path, openvdb::GridCPtrVec{grid}, /*overwrite=*/true);
}

// Writes values(x) at the BCC sites of [0, kDim)^3 (sparse/BccGrids.h) with worldFromIndex =
// translate(origin) * scale(scale) for BCC index space. `indexShift` (even, to keep the lattice) moves
// the data to sites [indexShift, indexShift + kDim) with the same world positions and values: the same
// volume far from the index origin, where float index coordinates round coarser.
inline void writeBccFile(const std::string& path, const std::function<float(const glm::ivec3&)>& values, double scale,
                         const openvdb::Vec3d& origin, float background = kBackground,
                         const glm::ivec3& indexShift = glm::ivec3(0)) {
  initializeVdb();
  auto xform = openvdb::math::Transform::createLinearTransform(scale);
  xform->postTranslate(origin - scale * openvdb::Vec3d(indexShift.x, indexShift.y, indexShift.z));
  const BccGrids grids = buildBccGrids(SiteBox{indexShift, indexShift + glm::ivec3(kDim - 1)}, background,
                                       [&](const glm::ivec3& ijk) { return values(ijk - indexShift); }, *xform);
  io::writeVdbAtomically(path, openvdb::GridCPtrVec{grids.primary, grids.secondary}, /*overwrite=*/true);
}

// The device's isosurface image against the CPU reference raycaster (sparse/ReferenceRaycast.h), pixel
// by pixel, as both renderers' tests on the Cartesian and BCC lattices compare them: both find the roots
// of the same polynomials in float and differ by rounding only. A pixel disagrees where one hits and
// the other misses or their depths differ by more than kDepthTolVoxels index units (depths are world
// distances: `worldPerIndex` converts); where both hit, the normals must agree within kNormalTolDegrees;
// at most kMaxDisagreeingFraction of the image may disagree, and the surface must cover a quarter of it.
inline void expectReferenceIsosurface(const std::string& what, const render::FrameImages& gpu, const render::Camera& camera,
                                      const glm::dmat4& indexFromWorld, double worldPerIndex, const Reconstruction& recon,
                                      const SiteValue& sites, const CellBounds& bounds, float iso) {
  constexpr double kDepthTolVoxels = 2e-3;
  constexpr double kNormalTolDegrees = 0.1;
  constexpr double kMaxDisagreeingFraction = 0.005;
  const int w = gpu.width, h = gpu.height;
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  const glm::vec3 o(indexFromWorld * glm::dvec4(camera.eye, 1.0));
  int hits = 0, disagree = 0;
  double worstDepth = 0.0, worstAngle = 0.0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const glm::vec3 d(glm::dmat3(indexFromWorld) * render::pixelRay(frame, px, py, w, h));
      const RayHit ref = firstHit(recon, sites, bounds, o, d, 0.0f, 400.0f, iso);
      const std::size_t i = std::size_t(py) * w + px;
      const bool hit = gpu.rgba[4 * i + 3] > 0.5f;
      const double depthVoxels = ref.hit && hit ? std::abs(double(gpu.normalDepth[4 * i + 3]) - ref.t) / worldPerIndex : 0.0;
      if (hit != ref.hit || depthVoxels > kDepthTolVoxels) {
        ++disagree;
        std::printf("%s: pixel (%d, %d) device %s t %.6g, reference %s t %.6g\n", what.c_str(), px, py, hit ? "hit" : "miss",
                    double(gpu.normalDepth[4 * i + 3]), ref.hit ? "hit" : "miss", double(ref.t));
        continue;
      }
      if (!hit) continue;
      ++hits;
      const glm::dvec3 nRef = glm::normalize(glm::transpose(glm::dmat3(indexFromWorld)) * glm::dvec3(ref.gradient));
      const glm::dvec3 n(gpu.normalDepth[4 * i], gpu.normalDepth[4 * i + 1], gpu.normalDepth[4 * i + 2]);
      const double angle = glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(n), nRef), -1.0, 1.0)));
      worstDepth = std::max(worstDepth, depthVoxels);
      worstAngle = std::max(worstAngle, angle);
      EXPECT_LT(angle, kNormalTolDegrees) << what << ": pixel (" << px << ", " << py << ")";
    }
  std::printf("%s: %d hits agree (worst depth %.3g voxels, normal %.3g degrees), %d pixels disagree\n", what.c_str(), hits,
              worstDepth, worstAngle, disagree);
  EXPECT_GT(hits, w * h / 4) << what << ": the surface should cover a good part of the image";
  EXPECT_LE(disagree, int(kMaxDisagreeingFraction * w * h)) << what;
}

inline render::FrameImages renderCartesian(const std::string& path, const std::string& reconstruction, const render::Camera& camera,
                                    int width, int height, float iso, render::RenderOptions options = {},
                                    render::FrameStats* stats = nullptr) {
  const io::CartesianBrickStore store(path);
  const render::CartesianBrickSource source(store, findReconstruction(reconstruction));
  options.iso = iso;
  return renderSource(source, camera, width, height, options, stats);
}

}  // namespace fcc::test
