// Shared by the renderer tests: writing an FCC file from a sample field, and rendering a file through the library (as `fccvdb render` does).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "io/BrickStore.h"
#include "io/VdbFile.h"
#include "sparse/FccBuilder.h"
#include "sparse/SampleField.h"
#include "tests/tools/RunCommand.h"
#include "tests/viewer/GlTestSuite.h"
#include "viewer/Raycaster.h"

namespace fcc::test {

// Builds the FCC grid of `field` (prefiltered), gives it worldFromIndex = translate(origin) *
// scale(scale), and writes it to `path`.
inline void writeFccFile(const std::string& path, const SampleField& field, double scale = 1.0,
                         const openvdb::Vec3d& origin = openvdb::Vec3d(0.0)) {
  initializeVdb();
  BuildResult built = buildFccGrid(field, BuildOptions{});
  auto xform = openvdb::math::Transform::createLinearTransform(scale);
  xform->postTranslate(origin);
  built.grid->setTransform(xform);
  built.grid->setName("test");
  FccProvenance p;
  p.mode = "test";
  p.sampleMin = built.samples.min;
  p.sampleMax = built.samples.max;
  setFccMetadata(*built.grid, p);
  io::writeVdbAtomically(path, openvdb::GridCPtrVec{built.grid}, /*overwrite=*/true);
}

inline render::FrameImages renderFile(const std::string& path, const render::Camera& camera, int width, int height,
                                      float iso, const render::RenderOptions& options = {},
                                      render::FrameStats* stats = nullptr) {
  const io::BrickStore store(path);
  render::RenderOptions withIso = options;
  withIso.iso = iso;
  render::Raycaster raycaster(store, withIso);
  const render::FrameStats s = raycaster.render(camera, width, height);
  if (stats) *stats = s;
  return raycaster.readImages();
}

// A unit-direction ray o + t d against the sphere of `radius` about `center` (world space): whether and
// where it enters, the chord, and how close it passes (grazing rays are left out by the exactness tests).
struct SphereRay {
  double radius = 0.0;
  bool hits = false;
  double tEnter = 0.0;   // where it enters (if it hits)
  double chord = 0.0;    // length inside (0 if it misses)
  double closest = 0.0;  // distance of the line from the centre
  // Passes within `fraction` of the radius of the sphere's outline.
  bool grazes(double fraction) const { return std::abs(closest - radius) < fraction * radius; }
};
inline SphereRay sphereRay(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& center, double radius) {
  const glm::dvec3 oc = o - center;
  const double b = glm::dot(oc, d), c = glm::dot(oc, oc) - radius * radius;
  SphereRay r;
  r.radius = radius;
  r.closest = std::sqrt(std::max(glm::dot(oc, oc) - b * b, 0.0));
  r.hits = b * b - c >= 0.0;
  if (r.hits) {
    r.tEnter = -b - std::sqrt(b * b - c);
    r.chord = 2.0 * std::sqrt(b * b - c);
  }
  return r;
}

// "[x0,x1)x[y0,y1)", for failure messages.
inline std::string describe(const render::PixelRect& r) {
  return "[" + std::to_string(r.x0) + "," + std::to_string(r.x1) + ")x[" + std::to_string(r.y0) + "," +
         std::to_string(r.y1) + ")";
}

// Sparse blobs of 96^3 (307 bricks), a camera that sees most of them, and a pool of a few dozen
// slots (by layout), so a frame needs several passes and bricks are evicted and reloaded.
inline constexpr std::size_t kSmallPoolBytes = std::size_t(1) << 20;

// One complete frame of `source` with `options`: the image, and the frame's stats into `stats` if given.
inline render::FrameImages renderSource(const render::BrickSource& source, const render::Camera& camera, int width, int height,
                                        const render::RenderOptions& options, render::FrameStats* stats = nullptr) {
  render::Raycaster raycaster(source, options);
  const render::FrameStats s = raycaster.render(camera, width, height);
  if (stats) *stats = s;
  return raycaster.readImages();
}

// Two images bit for bit, colour and normal/depth (a failure names the first component that differs);
// the count of hit pixels (alpha > 0.5) of the first.
inline int expectSameImages(const render::FrameImages& a, const render::FrameImages& b) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  EXPECT_EQ(a.normalDepth.size(), b.normalDepth.size());
  if (a.rgba.size() != b.rgba.size() || a.normalDepth.size() != b.normalDepth.size()) return 0;
  int hits = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    if (a.rgba[i] != b.rgba[i] || !(a.normalDepth[i] == b.normalDepth[i])) {
      ADD_FAILURE() << "component " << i << ": " << a.rgba[i] << " vs " << b.rgba[i] << ", normal/depth "
                    << a.normalDepth[i] << " vs " << b.normalDepth[i];
      return hits;
    }
    hits += i % 4 == 3 && a.rgba[i] > 0.5f;
  }
  return hits;
}

// Out of core: the isosurface at `iso` through a pool of six slots of 20^3 floats (and their cell
// bounds), which must evict and reload bricks, is the unbounded pool's image bit for bit.
inline void expectSixSlotsGiveTheSameImage(const render::BrickSource& source, const render::Camera& camera, int width,
                                           int height, float iso) {
  render::RenderOptions unbounded, small;
  unbounded.iso = small.iso = iso;
  small.gpuCacheBytes = 6 * (8000 * 4 + 4096);
  render::FrameStats bigStats, smallStats;
  const render::FrameImages reference = renderSource(source, camera, width, height, unbounded, &bigStats);
  const render::FrameImages limited = renderSource(source, camera, width, height, small, &smallStats);
  std::printf("%s: unbounded %d passes, %llu uploads; six slots %d passes, %llu uploads\n",
              std::string(source.reconstruction().name).c_str(), bigStats.passes, (unsigned long long)bigStats.bricksUploaded,
              smallStats.passes, (unsigned long long)smallStats.bricksUploaded);
  EXPECT_GT(smallStats.bricksUploaded, bigStats.bricksUploaded) << "the small pool must have evicted bricks";
  EXPECT_GT(expectSameImages(reference, limited), width * height / 10);
}

inline std::string writeSmallBlobs(const TempDir& dir) {
  const std::string path = dir / "blobs.vdb";
  EXPECT_EQ(test::runFccvdb("synth blobs " + path + " --dims 96,96,96 --quiet").status, 0);
  return path;
}

inline render::Camera smallBlobsCamera() {
  render::Camera camera;
  camera.eye = glm::dvec3(160.0, 120.0, 140.0);
  camera.lookat = glm::dvec3(48.0);
  return camera;
}

}  // namespace fcc::test
