// Shared by the renderer tests on Cartesian grids (and BCC datasets): a smooth test field, writing it as
// a float grid (or as BCC cosets), and rendering a Cartesian .vdb through the library as `render
// --reconstruction` does.
#pragma once

#include <openvdb/openvdb.h>

#include <cmath>
#include <functional>
#include <string>

#include <glm/glm.hpp>

#include "io/CartesianBrickStore.h"
#include "io/VdbFile.h"
#include "sparse/BccGrids.h"
#include "viewer/CartesianBrickSource.h"
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
// translate(origin) * scale(scale) for BCC index space.
inline void writeBccFile(const std::string& path, const std::function<float(const glm::ivec3&)>& values, double scale,
                         const openvdb::Vec3d& origin, float background = kBackground) {
  initializeVdb();
  auto xform = openvdb::math::Transform::createLinearTransform(scale);
  xform->postTranslate(origin);
  const BccGrids grids = buildBccGrids(SiteBox{glm::ivec3(0), glm::ivec3(kDim - 1)}, background, values, *xform);
  io::writeVdbAtomically(path, openvdb::GridCPtrVec{grids.primary, grids.secondary}, /*overwrite=*/true);
}

inline render::FrameImages renderCartesian(const std::string& path, const std::string& reconstruction, const render::Camera& camera,
                                    int width, int height, float iso, render::RenderOptions options = {},
                                    render::FrameStats* stats = nullptr) {
  const io::CartesianBrickStore store(path);
  const render::CartesianBrickSource source(store, findReconstruction(reconstruction));
  options.iso = iso;
  render::Raycaster raycaster(source, options);
  const render::FrameStats s = raycaster.render(camera, width, height);
  if (stats) *stats = s;
  return raycaster.readImages();
}

}  // namespace fcc::test
