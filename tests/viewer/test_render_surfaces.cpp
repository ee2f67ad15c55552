// Several isosurfaces at once (RenderOptions::moreSurfaces, shaders/surfaces.glsl): two nested spheres
// against their analytic composite, the GPU against the CPU reference (sparse/ReferenceRaycast.h's
// surfaceCrossings) pixel by pixel, a pool of a few slots against an unbounded one bit for bit, and a
// one-surface list against the single-surface path.
#include <gtest/gtest.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "CartesianTestSupport.h"
#include "RenderTestSupport.h"
#include "sparse/CubicBSpline.h"
#include "sparse/LatticeSamples.h"
#include "io/VdbFile.h"
#include "sparse/Lattice.h"
#include "sparse/ReferenceRaycast.h"
#include "sparse/SynthFields.h"
#include "viewer/Camera.h"
#include "viewer/BccBrickSource.h"
#include "viewer/FccBrickSource.h"

namespace fcc {
namespace {

using test::GlSuite;
using test::TempDir;

// The nested spheres: colour per channel against the analytic composite. The raycaster's depth is
// within 1e-3 voxels and its normals within 0.05 degrees of the sphere's (test_render), which moves
// a Lambert term by < 1e-3; float compositing adds ~1e-6.
constexpr double kAnalyticColorTol = 2e-3;
// The opacity is a product of the surfaces' opacities: exact but for float rounding.
constexpr double kAlphaTol = 1e-6;
constexpr double kDepthTolVoxels = 1e-3;
// Rays within this fraction of a sphere's radius of grazing it are left out (a matter of the last bit).
constexpr double kGrazingFraction = 0.01;
// GPU against the CPU reference: colour per channel where both saw the same crossings; pixels where
// they differ more (a grazing ray: one of them sees a pair of crossings the other does not) may be at
// most this fraction of the image.
constexpr double kReferenceColorTol = 2e-3;
constexpr double kMaxDisagreeingFraction = 0.01;

render::RenderOptions withSurfaces(const std::vector<render::Isosurface>& surfaces, render::RenderOptions options = {}) {
  options.iso = surfaces.at(0).iso;
  options.surfaceColor = surfaces[0].color;
  options.surfaceOpacity = surfaces[0].opacity;
  options.moreSurfaces.assign(surfaces.begin() + 1, surfaces.end());
  return options;
}

// The raycaster's light (Raycaster::dispatchPass): lightInCamera in the camera's frame, world space.
glm::dvec3 lightWorld(const render::CameraFrame& frame, const glm::vec3& l) {
  const glm::dvec3 sum = double(l.x) * glm::normalize(frame.right) + double(l.y) * glm::normalize(frame.up) -
                         double(l.z) * frame.forward;
  return glm::normalize(sum);
}

// Two-sided Lambert with 0.15 ambient, as the raycaster shades.
glm::dvec3 shade(const glm::dvec3& color, const glm::dvec3& n, const glm::dvec3& dir, const glm::dvec3& light) {
  const glm::dvec3 facing = glm::dot(n, dir) > 0.0 ? -n : n;
  return color * (0.15 + 0.85 * std::max(glm::dot(facing, light), 0.0));
}

class RenderSurfaces : public GlSuite {};

// f = |x - c|^2 / R^2 (the `sphere` synth field) is quadratic, so its spline is exact and f = a, f = b
// are spheres of radius R sqrt(a) and R sqrt(b). An opaque inner and a half-opaque outer one: a ray
// through the outer alone composites its entry and exit (opacity 0.75), one through both the outer's
// entry and the inner's (opacity 1), each shaded with the analytic normal.
TEST_F(RenderSurfaces, NestedSpheresMatchTheAnalyticComposite) {
  TempDir dir;
  const std::string path = dir / "sphere.vdb";
  const glm::ivec3 dims(40);
  const SynthField synth = makeSynthField(SynthSpec{"sphere", dims, 1});
  const double scale = 0.25;
  const openvdb::Vec3d origin(1.0, -2.0, 0.5);
  test::writeFccFile(path, *synth.field, scale, origin);
  const double R = 0.5 * (dims.x - 1);
  const glm::dvec3 center = glm::dvec3(origin.x(), origin.y(), origin.z()) + scale * glm::dvec3(0.5 * (dims.x - 1));
  const render::Isosurface inner{0.15f, {0.9f, 0.3f, 0.2f}, 1.0f}, outer{0.4f, {0.2f, 0.5f, 0.9f}, 0.5f};
  const double rInner = scale * R * std::sqrt(double(inner.iso)), rOuter = scale * R * std::sqrt(double(outer.iso));

  render::Camera camera;
  camera.lookat = center + glm::dvec3(0.3, -0.2, 0.1);
  camera.eye = center + glm::dvec3(9.0, 5.0, 7.0);
  camera.fovYDegrees = 30.0;
  const int w = 96, h = 80;
  const io::BrickStore store(path);
  const render::FccBrickSource source(store, std::size_t(64) << 20);
  const render::RenderOptions options = withSurfaces({inner, outer});
  const render::FrameImages img = test::renderSource(source, camera, w, h, options);
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  const glm::dvec3 light = lightWorld(frame, options.lightInCamera);

  int compared = 0, throughBoth = 0, throughOuter = 0;
  double worstColor = 0.0, worstDepth = 0.0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const glm::dvec3 d = render::pixelRay(frame, px, py, w, h);
      const test::SphereRay in = test::sphereRay(camera.eye, d, center, rInner);
      const test::SphereRay out = test::sphereRay(camera.eye, d, center, rOuter);
      if (in.grazes(kGrazingFraction) || out.grazes(kGrazingFraction)) continue;
      ++compared;
      glm::dvec3 color(0.0);
      double transmittance = 1.0, depth = std::numeric_limits<double>::infinity();
      const auto composite = [&](const render::Isosurface& s, double t) {
        const glm::dvec3 n = glm::normalize(camera.eye + t * d - center);
        color += transmittance * double(s.opacity) * shade(glm::dvec3(s.color), n, d, light);
        transmittance *= 1.0 - double(s.opacity);
        depth = std::min(depth, t);
      };
      if (out.hits) {
        composite(outer, out.tEnter);
        if (in.hits) {
          composite(inner, in.tEnter);
          ++throughBoth;
        } else {
          composite(outer, out.tEnter + out.chord);
          ++throughOuter;
        }
      }
      const std::size_t i = std::size_t(py) * w + px;
      const std::string where = "pixel (" + std::to_string(px) + ", " + std::to_string(py) + ")";
      for (int c = 0; c < 3; ++c) {
        const double e = std::abs(double(img.rgba[4 * i + c]) - color[c]);
        worstColor = std::max(worstColor, e);
        ASSERT_LT(e, kAnalyticColorTol) << where << " channel " << c << ": " << img.rgba[4 * i + c] << " against " << color[c];
      }
      ASSERT_NEAR(img.rgba[4 * i + 3], 1.0 - transmittance, kAlphaTol) << where;
      if (std::isinf(depth)) {
        EXPECT_TRUE(std::isinf(img.normalDepth[4 * i + 3])) << where << ": a miss has depth +inf";
      } else {
        const double e = std::abs(double(img.normalDepth[4 * i + 3]) - depth) / scale;
        worstDepth = std::max(worstDepth, e);
        EXPECT_LT(e, kDepthTolVoxels) << where << ": the depth is the first crossing's";
      }
    }
  EXPECT_GT(throughBoth, w * h / 20) << "rays through both spheres";
  EXPECT_GT(throughOuter, w * h / 40) << "rays through the outer sphere alone";
  std::printf("nested spheres: %d pixels compared (%d through both, %d through the outer alone), worst colour error "
              "%.3g, worst depth error %.3g voxels\n",
              compared, throughBoth, throughOuter, worstColor, worstDepth);
}

// Three surfaces of `synth blobs`, two translucent: every pixel against the CPU reference's crossings
// composited in double.
TEST_F(RenderSurfaces, MatchesTheCpuReference) {
  TempDir dir;
  const std::string path = dir / "blobs.vdb";
  ASSERT_EQ(test::runFccvdb("synth blobs " + path + " --dims 48,48,48 --quiet").status, 0);
  const io::BrickStore store(path);
  const render::FccBrickSource source(store, std::size_t(64) << 20);
  const glm::dmat4 indexFromWorld = glm::inverse(store.worldFromIndex());
  render::Camera camera;
  camera.lookat = glm::dvec3(store.worldFromIndex() * glm::dvec4(24.0, 24.0, 24.0, 1.0));
  camera.eye = camera.lookat + glm::dvec3(60.0, 44.0, 72.0);
  camera.fovYDegrees = 35.0;
  const int w = 48, h = 40;
  const std::vector<render::Isosurface> surfaces{
      {0.3f, {0.85f, 0.72f, 0.52f}, 0.4f}, {0.6f, {0.25f, 0.5f, 0.85f}, 0.6f}, {0.9f, {0.8f, 0.3f, 0.25f}, 1.0f}};
  const render::RenderOptions options = withSurfaces(surfaces);
  const render::FrameImages gpu = test::renderSource(source, camera, w, h, options);

  const FccGrid::Ptr grid = io::readFccGrid(path);
  // The tree itself, not an accessor (not thread-safe): rows run in parallel.
  const SiteValue at = [&](const glm::ivec3& ijk) {
    const glm::ivec3 v = packedVoxelOfSite(ijk);
    return grid->tree().getValue(openvdb::Coord(v.x, v.y, v.z))[channelOfSite(ijk)];
  };
  const std::unique_ptr<Reconstruction> boxSpline = makeReconstruction("boxspline");
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  const glm::dvec3 light = lightWorld(frame, options.lightInCamera);
  std::vector<SurfaceLook> looks;
  std::vector<float> isos;
  for (const render::Isosurface& s : surfaces) {
    looks.push_back(SurfaceLook{glm::dvec3(s.color), double(s.opacity)});
    isos.push_back(s.iso);
  }
  const glm::dmat3 normalFromIndex = glm::transpose(glm::dmat3(indexFromWorld));
  std::vector<SurfacePixel> ref(std::size_t(w) * h);
  tbb::parallel_for(0, h, [&](int py) {
    for (int px = 0; px < w; ++px) {
      const glm::dvec3 dWorld = render::pixelRay(frame, px, py, w, h);
      const glm::dvec3 o(indexFromWorld * glm::dvec4(camera.eye, 1.0));
      const glm::dvec3 d = glm::dmat3(indexFromWorld) * dWorld;
      // The data's box (sites 0..47) with the spline's reach: nothing crosses outside it.
      double t0 = 0.0, t1 = 1e9;
      for (int a = 0; a < 3; ++a) {
        double ta = (-4.0 - o[a]) / d[a], tb = (52.0 - o[a]) / d[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
      }
      if (!(t0 < t1)) continue;
      const std::vector<SurfaceCrossing> crossings =
          surfaceCrossings(*boxSpline, at, nullptr, glm::vec3(o), glm::vec3(d), float(t0), float(t1), isos);
      ref[std::size_t(py) * w + px] =
          compositeCrossings(crossings, looks, normalFromIndex, dWorld, light, 1.0 - double(options.terminationOpacity));
    }
  });
  int disagree = 0, translucent = 0, covered = 0;
  double worst = 0.0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const std::size_t i = std::size_t(py) * w + px;
      double e = 0.0;
      for (int c = 0; c < 4; ++c) e = std::max(e, std::abs(double(gpu.rgba[4 * i + c]) - ref[i].rgba[c]));
      if (e > kReferenceColorTol) {
        ++disagree;
        std::printf("pixel (%d, %d): device rgba %.5g %.5g %.5g %.5g, reference %.5g %.5g %.5g %.5g\n", px, py,
                    gpu.rgba[4 * i], gpu.rgba[4 * i + 1], gpu.rgba[4 * i + 2], gpu.rgba[4 * i + 3], ref[i].rgba.r,
                    ref[i].rgba.g, ref[i].rgba.b, ref[i].rgba.a);
        continue;
      }
      worst = std::max(worst, e);
      covered += ref[i].rgba.a > 0.0;
      translucent += ref[i].rgba.a > 0.0 && ref[i].rgba.a < 0.99;
    }
  std::printf("blobs, 3 surfaces: %d pixels covered (%d translucent) agree within %.3g (worst %.3g), %d disagree\n",
              covered, translucent, kReferenceColorTol, worst, disagree);
  EXPECT_GT(covered, w * h / 10);
  EXPECT_GT(translucent, w * h / 20) << "the translucent surfaces must show what lies behind them somewhere";
  EXPECT_LE(disagree, int(kMaxDisagreeingFraction * w * h));
}

// The Cartesian reconstructions (the cubic of trilinear, tricubic's degree 9, type6's cubic per tetrahedron) composite their crossings
// too: two surfaces of the wavy field against the CPU reference with the same coefficients.
TEST_F(RenderSurfaces, CartesianAndBccReconstructionsMatchTheCpuReference) {
  TempDir dir;
  const std::string path = dir / "wavy.vdb", bccPath = dir / "wavy_bcc.vdb";
  const double scale = 0.5;
  test::writeCartesianFile(path, test::wavy, scale, openvdb::Vec3d(-3.0, 1.0, 2.0));
  // The same field at the BCC sites, in the same index and world space.
  test::writeBccFile(bccPath, test::wavy, scale, openvdb::Vec3d(-3.0, 1.0, 2.0));
  const io::CartesianBrickStore store(path);
  const glm::dmat4 indexFromWorld = glm::inverse(store.worldFromIndex());
  render::Camera camera;
  camera.lookat = glm::dvec3(store.worldFromIndex() * glm::dvec4(24.0, 24.0, 24.0, 1.0));
  camera.eye = camera.lookat + glm::dvec3(30.0, 22.0, 36.0);
  camera.fovYDegrees = 35.0;
  const int w = 48, h = 40;
  const std::vector<render::Isosurface> surfaces{{0.6f, {0.85f, 0.72f, 0.52f}, 0.5f}, {0.2f, {0.25f, 0.5f, 0.85f}, 0.8f}};
  const render::RenderOptions options = withSurfaces(surfaces);
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  const glm::dvec3 light = lightWorld(frame, options.lightInCamera);
  std::vector<SurfaceLook> looks;
  std::vector<float> isos;
  for (const render::Isosurface& s : surfaces) {
    looks.push_back(SurfaceLook{glm::dvec3(s.color), double(s.opacity)});
    isos.push_back(s.iso);
  }
  const glm::dmat3 normalFromIndex = glm::transpose(glm::dmat3(indexFromWorld));
  const glm::vec3 o(indexFromWorld * glm::dvec4(camera.eye, 1.0));
  for (const char* name : {"trilinear", "tricubic", "type6", "barycentric", "sheared-trilinear", "bilinear"}) {
    SCOPED_TRACE(name);
    const ReconstructionInfo& info = findReconstruction(name);
    const bool bcc = info.lattice == Lattice::Bcc;
    const std::unique_ptr<render::BrickSource> source =
        bcc ? std::unique_ptr<render::BrickSource>(std::make_unique<render::BccBrickSource>(bccPath, info))
            : std::make_unique<render::CartesianBrickSource>(store, info);
    const render::FrameImages gpu = test::renderSource(*source, camera, w, h, options);
    const int pad = kBSplinePrefilterReach + 4;
    LatticeSamples samples(info.lattice, glm::ivec3(-pad), glm::ivec3(test::kDim + 2 * pad), test::kBackground);
    samples.fill([](const glm::ivec3& ijk) {
      const bool in = glm::all(glm::greaterThanEqual(ijk, glm::ivec3(0))) && glm::all(glm::lessThan(ijk, glm::ivec3(test::kDim)));
      return in ? test::wavy(ijk) : test::kBackground;
    });
    samples.prefilter(info.prefilter);
    const CellBounds bounds(samples);
    const std::unique_ptr<Reconstruction> recon = makeReconstruction(name);
    recon->setView(glm::vec3(glm::dmat3(indexFromWorld) * frame.forward));  // the stack schemes' (the renderer's per frame)
    std::vector<SurfacePixel> ref(std::size_t(w) * h);
    std::vector<char> layered(ref.size(), 0);  // two crossings or more composited (both surfaces are translucent)
    tbb::parallel_for(0, h, [&](int py) {
      for (int px = 0; px < w; ++px) {
        const glm::dvec3 dWorld = render::pixelRay(frame, px, py, w, h);
        const glm::vec3 d(glm::dmat3(indexFromWorld) * dWorld);
        const std::vector<SurfaceCrossing> crossings = surfaceCrossings(*recon, samples.accessor(), &bounds, o, d, 0.0f, 400.0f, isos);
        ref[std::size_t(py) * w + px] =
            compositeCrossings(crossings, looks, normalFromIndex, dWorld, light, 1.0 - double(options.terminationOpacity));
        layered[std::size_t(py) * w + px] = crossings.size() >= 2;
      }
    });
    int disagree = 0, translucent = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < ref.size(); ++i) {
      double e = 0.0;
      for (int c = 0; c < 4; ++c) e = std::max(e, std::abs(double(gpu.rgba[4 * i + c]) - ref[i].rgba[c]));
      if (e > kReferenceColorTol) {
        ++disagree;
        continue;
      }
      worst = std::max(worst, e);
      translucent += layered[i];
    }
    std::printf("%s, 2 surfaces: %d pixels composite two crossings or more, worst difference %.3g where they agree, %d disagree\n", name,
                translucent, worst, disagree);
    EXPECT_GT(translucent, w * h / 10);
    EXPECT_LE(disagree, int(kMaxDisagreeingFraction * w * h));
  }
}

// A ray that waits for a brick keeps what it composited (colour and transmittance, exactly): a pool of
// a few slots, which evicts and reloads bricks over many passes, gives the unbounded pool's image bit
// for bit; and skipping (nodes, bricks, cells holding none of the values) changes nothing either.
TEST_F(RenderSurfaces, SmallPoolAndSkippingChangeNoBit) {
  TempDir dir;
  const std::string path = test::writeSmallBlobs(dir);
  const render::Camera camera = test::smallBlobsCamera();
  const int w = 48, h = 40;
  const io::BrickStore store(path);
  const render::RenderOptions options =
      withSurfaces({{0.25f, {0.85f, 0.72f, 0.52f}, 0.5f}, {0.55f, {0.25f, 0.5f, 0.85f}, 0.7f}, {0.8f, {0.8f, 0.3f, 0.25f}, 1.0f}});
  render::RenderOptions small = options, noSkip = options;
  small.gpuCacheBytes = small.hostCacheBytes = test::kSmallPoolBytes;
  noSkip.skipEmpty = false;
  render::FrameStats bigStats, smallStats;
  const render::FrameImages reference = test::renderSource(render::FccBrickSource(store, std::size_t(64) << 20), camera, w, h, options, &bigStats);
  const render::FrameImages limited = test::renderSource(render::FccBrickSource(store, test::kSmallPoolBytes), camera, w, h, small, &smallStats);
  const render::FrameImages unskipped = test::renderSource(render::FccBrickSource(store, std::size_t(64) << 20), camera, w, h, noSkip);
  std::printf("unbounded: %d passes, %llu uploads; 1 MiB: %d passes, %llu uploads\n", bigStats.passes,
              (unsigned long long)bigStats.bricksUploaded, smallStats.passes, (unsigned long long)smallStats.bricksUploaded);
  EXPECT_GT(smallStats.bricksUploaded, bigStats.bricksUploaded) << "the small pool must have evicted bricks";
  int translucent = 0;
  for (std::size_t i = 0; i < reference.rgba.size(); ++i) {
    ASSERT_EQ(reference.rgba[i], limited.rgba[i]) << "the small pool changed component " << i;
    ASSERT_EQ(reference.normalDepth[i], limited.normalDepth[i]) << "the small pool changed normal/depth component " << i;
    ASSERT_EQ(reference.rgba[i], unskipped.rgba[i]) << "skipping changed component " << i;
    translucent += i % 4 == 3 && reference.rgba[i] > 0.0f && reference.rgba[i] < 0.99f;
  }
  EXPECT_GT(translucent, w * h / 20) << "rays must composite translucent surfaces for this test to mean anything";
}

// A one-element list with the default colour and opacity 1 is the single surface: the same program,
// the same image bit for bit. The compositing variant agrees with it too: the same opaque surface
// with a second, invisible one (opacity 0) composites exactly the first crossing.
TEST_F(RenderSurfaces, OneOpaqueSurfaceIsTheSingleSurfacePath) {
  TempDir dir;
  const std::string path = test::writeSmallBlobs(dir);
  const render::Camera camera = test::smallBlobsCamera();
  const int w = 48, h = 40;
  const io::BrickStore store(path);
  const render::FccBrickSource source(store, std::size_t(64) << 20);
  render::RenderOptions plain;
  plain.iso = 0.3f;
  const render::FrameImages single = test::renderSource(source, camera, w, h, plain);
  render::Raycaster listed(source, render::RenderOptions{});
  listed.setSurfaces({render::Isosurface{0.3f, plain.surfaceColor, 1.0f}});
  EXPECT_FALSE(render::compositesSurfaces(listed.options()));
  listed.render(camera, w, h);
  const render::FrameImages fromList = listed.readImages();
  EXPECT_EQ(single.rgba, fromList.rgba);
  EXPECT_EQ(single.normalDepth, fromList.normalDepth);

  const render::RenderOptions twoOptions =
      withSurfaces({render::Isosurface{0.3f, plain.surfaceColor, 1.0f}, render::Isosurface{0.6f, glm::vec3(1.0f), 0.0f}});
  ASSERT_TRUE(render::compositesSurfaces(twoOptions));
  const render::FrameImages composited = test::renderSource(source, camera, w, h, twoOptions);
  int hits = 0, differ = 0;
  for (std::size_t p = 0; p < single.rgba.size() / 4; ++p) {
    hits += single.rgba[4 * p + 3] > 0.5f;
    bool same = (single.rgba[4 * p + 3] > 0.5f) == (composited.rgba[4 * p + 3] > 0.5f);
    for (int c = 0; c < 4 && same; ++c) same = std::abs(single.rgba[4 * p + c] - composited.rgba[4 * p + c]) < 1e-4f;
    if (same && single.rgba[4 * p + 3] > 0.5f)
      same = std::abs(single.normalDepth[4 * p + 3] - composited.normalDepth[4 * p + 3]) < 1e-3f;
    differ += !same;
  }
  EXPECT_GT(hits, w * h / 20);
  EXPECT_LE(differ, w * h / 200) << "of " << hits << " hit pixels";
}

}  // namespace
}  // namespace fcc
