// The brick-paged raycaster on Cartesian grids rendered as they are (viewer/CartesianBrickSource.h):
// every CC reconstruction against the exact CPU reference raycaster (sparse/ReferenceRaycast.h) pixel
// by pixel, the exact sphere of a quadratic field from the interpolating tricubic (it reproduces
// cubics) and from the type-6 spline (|p|^2 + 3/4: the sphere of radius sqrt(r^2 - 3/4)), and the
// image independent of the cache budgets.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "CartesianTestSupport.h"
#include "RenderTestSupport.h"
#include "io/CartesianBrickStore.h"
#include "io/VdbFile.h"
#include "tests/io/LeafDamage.h"
#include "sparse/CubicBSpline.h"
#include "sparse/LatticeSamples.h"
#include "sparse/ReferenceRaycast.h"
#include "viewer/CartesianBrickSource.h"

namespace fcc {
namespace {

using test::GlSuite;
using test::TempDir;
using test::kBackground;
using test::kDim;
using test::renderCartesian;
using test::wavy;
using test::writeCartesianFile;

class RenderCartesian : public GlSuite {};

TEST_F(RenderCartesian, EveryReconstructionMatchesTheCpuReference) {
  TempDir dir;
  const std::string path = dir / "wavy.vdb";
  const double scale = 0.5;
  const openvdb::Vec3d origin(-3.0, 1.0, 2.0);
  writeCartesianFile(path, wavy, scale, origin);
  // The renderer's map (the sphere test below checks it against world space).
  const glm::dmat4 worldFromIndex = io::CartesianBrickStore(path).worldFromIndex();
  const glm::dmat4 indexFromWorld = glm::inverse(worldFromIndex);

  render::Camera camera;
  camera.lookat = glm::dvec3(worldFromIndex * glm::dvec4(24.0, 24.0, 24.0, 1.0));
  camera.eye = camera.lookat + glm::dvec3(30.0, 22.0, 36.0);
  camera.fovYDegrees = 35.0;
  const int w = 64, h = 56;
  const float iso = 0.35f;

  for (const char* name : {"trilinear", "tricubic-bspline", "tricubic", "type6"}) {
    SCOPED_TRACE(name);
    const ReconstructionInfo& info = findReconstruction(name);
    const render::FrameImages gpu = renderCartesian(path, name, camera, w, h, iso);
    // The CPU's coefficients: the grid in a box padded with the background by more than the
    // prefilter's reach, as the bricks see it, prefiltered where the reconstruction asks for it.
    const int pad = kBSplinePrefilterReach + 4;
    LatticeSamples samples(Lattice::Cc, glm::ivec3(-pad), glm::ivec3(kDim + 2 * pad), kBackground);
    samples.fill([](const glm::ivec3& ijk) {
      return glm::all(glm::greaterThanEqual(ijk, glm::ivec3(0))) && glm::all(glm::lessThan(ijk, glm::ivec3(kDim))) ? wavy(ijk)
                                                                                                               : kBackground;
    });
    samples.prefilter(info.prefilter);
    const CellBounds bounds(samples);
    const std::unique_ptr<Reconstruction> recon = makeReconstruction(name);
    test::expectReferenceIsosurface(name, gpu, camera, indexFromWorld, scale, *recon, samples.accessor(), bounds, iso);
  }
}

// f = |x - c|^2 sampled, rendered with `name` at iso r^2, against the analytic sphere of radius
// `surfaceRadiusIndex` about c (index units): coverage, depth and normals.
// The background (beyond the grid) is near the values at its faces (576 .. 1700), so the prefilter's
// ringing at the jump stays far above the isovalue and dies out (0.27 per voxel) before the sphere.
void expectExactSphere(const char* name, double radiusIndex, double surfaceRadiusIndex) {
  TempDir dir;
  const std::string path = dir / "quadratic.vdb";
  const glm::dvec3 centerIndex(23.3, 24.1, 24.6);
  const double scale = 0.25;
  const openvdb::Vec3d origin(1.0, -2.0, 0.5);
  writeCartesianFile(path, [&](const glm::ivec3& ijk) {
    const glm::dvec3 r = glm::dvec3(ijk) - centerIndex;
    return float(glm::dot(r, r));
  }, scale, origin, /*background=*/800.0f);
  const glm::dvec3 center = glm::dvec3(origin.x(), origin.y(), origin.z()) + scale * centerIndex;
  const double radius = scale * surfaceRadiusIndex;

  render::Camera camera;
  camera.lookat = center + glm::dvec3(0.3, -0.2, 0.1);
  camera.eye = center + glm::dvec3(9.0, 5.0, 7.0);
  camera.fovYDegrees = 30.0;
  const int w = 64, h = 56;
  const render::FrameImages img = renderCartesian(path, name, camera, w, h, float(radiusIndex * radiusIndex));
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  int hits = 0;
  double worstDepth = 0.0, worstAngle = 0.0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const glm::dvec3 d = render::pixelRay(frame, px, py, w, h);
      const test::SphereRay ray = test::sphereRay(camera.eye, d, center, radius);
      if (ray.grazes(0.01)) continue;
      const std::size_t i = std::size_t(py) * w + px;
      const bool hit = img.rgba[4 * i + 3] > 0.5f;
      ASSERT_EQ(hit, ray.hits) << "pixel (" << px << ", " << py << ")";
      if (!hit) continue;
      ++hits;
      const double t = ray.tEnter;
      const double depthVoxels = std::abs(img.normalDepth[4 * i + 3] - t) / scale;
      const glm::dvec3 nExpected = glm::normalize(camera.eye + t * d - center);
      const glm::dvec3 n(img.normalDepth[4 * i], img.normalDepth[4 * i + 1], img.normalDepth[4 * i + 2]);
      const double angle = glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(n), nExpected), -1.0, 1.0)));
      worstDepth = std::max(worstDepth, depthVoxels);
      worstAngle = std::max(worstAngle, angle);
      EXPECT_LT(depthVoxels, 1e-3) << "pixel (" << px << ", " << py << ") t " << t;
      EXPECT_LT(angle, 0.05) << "pixel (" << px << ", " << py << ")";
    }
  EXPECT_GT(hits, w * h / 10);
  std::printf("%s sphere: %d hits, worst depth error %.3g voxels, worst normal %.3g degrees\n", name, hits, worstDepth,
              worstAngle);
}

// The interpolating tricubic B-spline reproduces the quadratic: the sphere of radius r.
TEST_F(RenderCartesian, TricubicGivesTheExactSphereOfAQuadraticField) { expectExactSphere("tricubic", 9.5, 9.5); }

// The type-6 spline makes |p - c|^2 into |p - c|^2 + 3/4 (test_type6): the isosurface at r^2 is exactly
// the sphere of radius sqrt(r^2 - 3/4), rendered on the device with its hits and normals.
TEST_F(RenderCartesian, Type6GivesTheExactSphereAtTheShiftedRadius) {
  expectExactSphere("type6", 9.5, std::sqrt(9.5 * 9.5 - 0.75));
}

// Out of core: a pool of a few slots gives the image of an unbounded one, bit for bit.
TEST_F(RenderCartesian, SmallPoolGivesTheSameImage) {
  TempDir dir;
  const std::string path = dir / "wavy.vdb";
  writeCartesianFile(path, wavy, 1.0, openvdb::Vec3d(0.0));
  render::Camera camera;
  camera.lookat = glm::dvec3(24.0);
  camera.eye = glm::dvec3(90.0, 70.0, 80.0);
  const io::CartesianBrickStore store(path);
  for (const char* name : {"trilinear", "tricubic"}) {
    SCOPED_TRACE(name);
    test::expectSixSlotsGiveTheSameImage(render::CartesianBrickSource(store, findReconstruction(name)), camera, 48, 48, 0.35f);
  }
}

// Whether the ray eye + t d, 0 <= t <= tMax, meets the box [lo, hi] (slabs).
bool rayMeetsBox(const glm::dvec3& eye, const glm::dvec3& d, double tMax, const glm::dvec3& lo, const glm::dvec3& hi) {
  double t0 = 0.0, t1 = tMax;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (eye[a] < lo[a] || eye[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - eye[a]) / d[a], tb = (hi[a] - eye[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

// A leaf whose bytes are damaged renders as a hole, with every CC reconstruction: the frame renders
// (no throw), the damage is recorded once, no surface lies inside the leaf (but within the
// reconstruction's reach of its faces: the cells there blend the data with the background the leaf
// now holds), and a ray that passes nowhere near the leaf — not within `reach` of it before its
// surface — gives the undamaged image's pixel: bit for bit where the blocks it reads are unchanged;
// for the interpolating tricubic within float noise (its prefilter spreads the jump at the leaf's
// faces, decaying by 0.27 a voxel, over every block around).
TEST_F(RenderCartesian, DamagedLeafRendersAsAHole) {
  TempDir dir;
  const std::string good = dir / "plane.vdb", bad = dir / "damaged.vdb";
  // The plane z = 20.5 of f = z; the background (also what the damaged leaf reads as) lies above it.
  const float background = 100.0f, iso = 20.5f;
  writeCartesianFile(good, [](const glm::ivec3& ijk) { return float(ijk.z); }, 1.0, openvdb::Vec3d(0.0), background);
  std::filesystem::copy_file(good, bad);
  const glm::dvec3 leafLo(16.0), leafHi(24.0);  // the leaf's voxels [16, 24)^3 hold the plane
  test::damageLeafValues(bad, {"Tree_float_5_4_3"}, openvdb::Coord(16, 16, 16));

  render::Camera camera;  // world = index space
  camera.eye = glm::dvec3(30.0, 18.0, 70.0);
  camera.lookat = glm::dvec3(22.0, 22.0, 20.0);
  camera.fovYDegrees = 55.0;
  const int w = 64, h = 64;
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  struct Case {
    const char* name;
    double reach;       // index units around the leaf where the image may change
    double wall;        // index units inside the leaf's faces where the blend may still cross the isovalue
    float tolerance;    // on every channel of the pixels beyond the reach
  };
  for (const Case& c : {Case{"trilinear", 2.0, 1.0, 0.0f}, Case{"type6", 3.0, 1.5, 0.0f},
                        Case{"tricubic-bspline", 3.0, 2.0, 0.0f}, Case{"tricubic", 10.0, 2.0, 1e-3f}}) {
    SCOPED_TRACE(c.name);
    const render::FrameImages reference = renderCartesian(good, c.name, camera, w, h, iso);
    const io::CartesianBrickStore store(bad);
    const render::CartesianBrickSource source(store, findReconstruction(c.name));
    render::RenderOptions options;
    options.iso = iso;
    render::Raycaster raycaster(source, options);
    raycaster.render(camera, w, h);
    const render::FrameImages damaged = raycaster.readImages();
    EXPECT_EQ(source.damage().count, 1u);
    EXPECT_NE(source.damage().first.find("leaf at (16, 16, 16) is damaged"), std::string::npos) << source.damage().first;

    int unchanged = 0, holeBefore = 0;
    for (int py = 0; py < h; ++py)
      for (int px = 0; px < w; ++px) {
        const std::size_t i = std::size_t(py) * w + px;
        const glm::dvec3 d = render::pixelRay(frame, px, py, w, h);
        const bool hitBefore = reference.rgba[4 * i + 3] > 0.5f, hitAfter = damaged.rgba[4 * i + 3] > 0.5f;
        const double tBefore = hitBefore ? reference.normalDepth[4 * i + 3] : 1e9;
        const glm::dvec3 inset(c.wall);
        const auto insideLeaf = [&](double t) {
          const glm::dvec3 p = camera.eye + t * d;
          return glm::all(glm::greaterThan(p, leafLo + inset)) && glm::all(glm::lessThan(p, leafHi - inset));
        };
        if (hitBefore && insideLeaf(tBefore)) ++holeBefore;
        EXPECT_FALSE(hitAfter && insideLeaf(damaged.normalDepth[4 * i + 3]))
            << "a surface inside the damaged leaf at pixel (" << px << ", " << py << ")";
        if (rayMeetsBox(camera.eye, d, tBefore, leafLo - c.reach, leafHi + c.reach)) continue;
        ++unchanged;
        for (int k = 0; k < 4; ++k) {
          ASSERT_NEAR(damaged.rgba[4 * i + k], reference.rgba[4 * i + k], c.tolerance) << "pixel (" << px << ", " << py << ")";
          if (!hitBefore) continue;  // a miss's depth is +inf
          ASSERT_NEAR(damaged.normalDepth[4 * i + k], reference.normalDepth[4 * i + k], c.tolerance)
              << "pixel (" << px << ", " << py << ")";
        }
        EXPECT_EQ(hitAfter, hitBefore);
      }
    std::printf("%s: %d pixels beyond the damaged leaf's reach unchanged, %d pixels saw the plane inside the leaf\n",
                c.name, unchanged, holeBefore);
    EXPECT_GT(unchanged, w * h / 10);
    EXPECT_GT(holeBefore, 20) << "the camera must see the plane inside the damaged leaf";
  }
}

// A vec4 layout packs FCC's channels: a Cartesian grid asks for a one-channel layout, in one line.
TEST_F(RenderCartesian, FourChannelLayoutIsRefusedByName) {
  TempDir dir;
  const std::string path = dir / "wavy.vdb";
  writeCartesianFile(path, wavy, 1.0, openvdb::Vec3d(0.0));
  const io::CartesianBrickStore store(path);
  const render::CartesianBrickSource source(store, findReconstruction("trilinear"));
  render::RenderOptions options;
  options.layout = render::BrickLayout::TextureVec4;
  try {
    render::Raycaster raycaster(source, options);
    FAIL() << "texture-vec4 accepted for a Cartesian grid";
  } catch (const ValueError& e) {
    EXPECT_NE(std::string(e.what()).find("texture-scalar"), std::string::npos) << e.what();
  }
  EXPECT_THROW(render::CartesianBrickSource(store, findReconstruction("boxspline")), ValueError);
}

}  // namespace
}  // namespace fcc
