// The raycaster on llvmpipe (or a GPU): exact isosurfaces of a quadratic field, thin features, and
// independence of the image from the cache budgets.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "RenderTestSupport.h"
#include "sparse/SynthFields.h"
#include "tests/tools/RunCommand.h"
#include "viewer/Camera.h"
#include "viewer/FccBrickSource.h"

namespace fcc {
namespace {

using test::GlSuite;
using test::renderFile;
using test::TempDir;
using test::writeFccFile;
using test::kSmallPoolBytes;
using test::smallBlobsCamera;
using test::writeSmallBlobs;
using test::describe;

// Tolerances of the exactness test (the numbers): depth in voxels, normals in degrees.
constexpr double kDepthTolVoxels = 1e-3;
constexpr double kNormalTolDegrees = 0.05;
// Rays whose distance from the sphere's centre is within this fraction of the radius of grazing it
// are left out of the coverage comparison (a pixel there is a matter of the last float bit).
constexpr double kGrazingFraction = 0.01;

// Asserts `image` equals `reference` bit for bit (colour, normal and depth); returns the hit pixels.
int expectSameImage(const render::FrameImages& reference, const render::FrameImages& image, const std::string& what) {
  EXPECT_EQ(reference.rgba.size(), image.rgba.size()) << what;
  int hits = 0;
  for (std::size_t i = 0; i < reference.rgba.size() && i < image.rgba.size(); ++i) {
    if (reference.rgba[i] != image.rgba[i] || !(reference.normalDepth[i] == image.normalDepth[i])) {
      ADD_FAILURE() << what << ": component " << i << " (pixel " << i / 4 << ") differs: rgba " << reference.rgba[i]
                    << " vs " << image.rgba[i] << ", normal/depth " << reference.normalDepth[i] << " vs "
                    << image.normalDepth[i];
      return hits;
    }
    hits += (i % 4 == 3) && reference.rgba[i] > 0.5f;
  }
  return hits;
}

// The rectangle of pixels in columns from `firstColumn` on that show the surface (A = 1).
render::PixelRect surfacePixels(const render::FrameImages& image, int firstColumn = 0) {
  render::PixelRect r;
  for (int y = 0; y < image.height; ++y)
    for (int x = firstColumn; x < image.width; ++x)
      if (image.rgba[(std::size_t(y) * image.width + x) * 4 + 3] > 0.5f) r = render::united(r, {x, y, x + 1, y + 1});
  return r;
}

// Raycaster::surfaceRect() is exactly the rectangle of the image's surface pixels.
void expectSurfaceRect(const render::Raycaster& raycaster, int firstColumn, const std::string& what) {
  const render::PixelRect expected = surfacePixels(raycaster.readImages(), firstColumn);
  EXPECT_TRUE(raycaster.surfaceRect() == expected)
      << what << ": surfaceRect " << describe(raycaster.surfaceRect()) << ", image's surface pixels " << describe(expected);
}

class Render : public GlSuite {};

// f = |x - c|^2 / R^2 is quadratic, so the prefiltered spline reproduces it exactly and the
// isosurface f = iso is the sphere of radius R sqrt(iso) about c: coverage, depth and normals must
// match the analytic sphere, here under a scaled and translated transform.
TEST_F(Render, QuadraticFieldGivesTheExactSphere) {
  TempDir dir;
  const std::string path = dir / "sphere.vdb";
  const glm::ivec3 dims(40);
  const SynthField synth = makeSynthField(SynthSpec{"sphere", dims, 1});
  const double scale = 0.25;
  const openvdb::Vec3d origin(1.0, -2.0, 0.5);
  writeFccFile(path, *synth.field, scale, origin);

  const double R = 0.5 * (dims.x - 1), iso = 0.3;
  const glm::dvec3 centerIndex(0.5 * (dims.x - 1));
  const glm::dvec3 center = glm::dvec3(origin.x(), origin.y(), origin.z()) + scale * centerIndex;
  const double radius = scale * R * std::sqrt(iso);

  render::Camera camera;
  camera.lookat = center + glm::dvec3(0.3, -0.2, 0.1);
  camera.eye = center + glm::dvec3(9.0, 5.0, 7.0);
  camera.fovYDegrees = 30.0;
  const int w = 96, h = 80;
  const render::FrameImages img = renderFile(path, camera, w, h, float(iso));
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);

  int compared = 0, hits = 0;
  double worstDepth = 0.0, worstAngle = 0.0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const glm::dvec3 d = render::pixelRay(frame, px, py, w, h);
      const test::SphereRay ray = test::sphereRay(camera.eye, d, center, radius);
      if (ray.grazes(kGrazingFraction)) continue;
      ++compared;
      const std::size_t i = std::size_t(py) * w + px;
      const bool expectHit = ray.hits;
      const bool hit = img.rgba[4 * i + 3] > 0.5f;
      ASSERT_EQ(hit, expectHit) << "pixel (" << px << ", " << py << ")";
      if (!hit) {
        EXPECT_TRUE(std::isinf(img.normalDepth[4 * i + 3])) << "a miss has depth +inf";
        continue;
      }
      ++hits;
      const double t = ray.tEnter;
      const double depthErrorVoxels = std::abs(img.normalDepth[4 * i + 3] - t) / scale;
      const glm::dvec3 nExpected = glm::normalize(camera.eye + t * d - center);
      const glm::dvec3 n(img.normalDepth[4 * i], img.normalDepth[4 * i + 1], img.normalDepth[4 * i + 2]);
      const double angle = glm::degrees(std::acos(std::clamp(glm::dot(glm::normalize(n), nExpected), -1.0, 1.0)));
      worstDepth = std::max(worstDepth, depthErrorVoxels);
      worstAngle = std::max(worstAngle, angle);
      EXPECT_LT(depthErrorVoxels, kDepthTolVoxels) << "pixel (" << px << ", " << py << ") t " << t;
      EXPECT_LT(angle, kNormalTolDegrees) << "pixel (" << px << ", " << py << ")";
      EXPECT_NEAR(glm::length(n), 1.0, 1e-5);
    }
  EXPECT_GT(hits, w * h / 10) << "the sphere should cover a good part of the image";
  std::printf("sphere: %d pixels compared, %d hits, worst depth error %.3g voxels, worst normal %.3g degrees\n",
              compared, hits, worstDepth, worstAngle);
}

// f = ((x - x0) / 4)^2 is quadratic; the isosurface f = (eps / 4)^2 is the pair of planes
// x = x0 +- eps bounding a slab 2 eps = 0.08 voxel thick. Every ray crossing the slab must hit it at
// the first plane: no step size to fall between.
class SlabField : public SampleField {
 public:
  static constexpr double kX0 = 23.37;
  float sample(const glm::ivec3& ijk) const override {
    const double u = (ijk.x - kX0) / 4.0;
    return float(u * u);
  }
  SiteBox bounds() const override { return SiteBox{glm::ivec3(0), glm::ivec3(47)}; }
  float background() const override { return 100.0f; }
};

TEST_F(Render, SlabThinnerThanATenthOfAVoxelHasNoHoles) {
  TempDir dir;
  const std::string path = dir / "slab.vdb";
  writeFccFile(path, SlabField());
  const double eps = 0.04;
  const float iso = float((eps / 4.0) * (eps / 4.0));

  render::Camera camera;
  camera.eye = glm::dvec3(60.0, 30.0, 20.0);
  camera.lookat = glm::dvec3(SlabField::kX0, 23.5, 23.5);
  camera.fovYDegrees = 35.0;
  const int w = 64, h = 64;
  const render::FrameImages img = renderFile(path, camera, w, h, iso);
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);

  int expected = 0, holes = 0;
  double worstDepth = 0.0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const glm::dvec3 d = render::pixelRay(frame, px, py, w, h);
      // The first plane the ray meets: x = x0 + eps (the eye is at larger x).
      const double t = (SlabField::kX0 + eps - camera.eye.x) / d.x;
      const glm::dvec3 p = camera.eye + t * d;
      // Away from the data's border, where the background breaks the quadratic.
      if (!(t > 0.0 && p.y > 6.0 && p.y < 41.0 && p.z > 6.0 && p.z < 41.0)) continue;
      ++expected;
      const std::size_t i = std::size_t(py) * w + px;
      if (img.rgba[4 * i + 3] < 0.5f) {
        ++holes;
        continue;
      }
      worstDepth = std::max(worstDepth, std::abs(double(img.normalDepth[4 * i + 3]) - t));
    }
  ASSERT_GT(expected, w * h / 4);
  EXPECT_EQ(holes, 0) << "of " << expected << " rays that cross the slab";
  EXPECT_LT(worstDepth, kDepthTolVoxels);
}

}  // namespace
}  // namespace fcc

namespace fcc {
namespace {

// Runs `fccvdb args...` in a child process; returns its exit status and peak resident memory.
struct ChildRun {
  int status = -1;
  long peakRssKiB = 0;
};
ChildRun runMeasured(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  std::string exe = FCC_FCCVDB_EXE;
  argv.push_back(exe.data());
  std::vector<std::string> copy = args;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execv(exe.c_str(), argv.data());
    ::_exit(127);
  }
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, usage.ru_maxrss};
}

// A dataset several times larger than both caches together renders to the same image as with
// caches that hold everything (more passes, same rays), and the process stays within the budgets.
TEST_F(Render, SmallCachesGiveTheSameImageWithinTheirBudgets) {
  TempDir dir;
  const std::string blobs = dir / "blobs.vdb", tiny = dir / "tiny.vdb";
  ASSERT_EQ(test::runFccvdb("synth blobs " + blobs + " --dims 160,160,160 --quiet").status, 0);
  ASSERT_EQ(test::runFccvdb("synth sphere " + tiny + " --dims 16,16,16 --quiet").status, 0);
  const double budgetMiB = 1.0;  // each of --gpu-cache and --host-cache

  const io::BrickStore store(blobs);
  const double decodedMiB = double(store.index().tree().leafCount()) * sizeof(io::BrickValues) / (1 << 20);
  ASSERT_GT(decodedMiB, 3.0 * 2.0 * budgetMiB) << "the dataset must be several times the budgets";

  render::Camera camera;
  camera.eye = glm::dvec3(260.0, 200.0, 230.0);
  camera.lookat = glm::dvec3(80.0);
  const int w = 64, h = 64;
  render::RenderOptions unlimited, small;
  small.gpuCacheBytes = small.hostCacheBytes = std::size_t(budgetMiB * (1 << 20));
  render::FrameStats bigStats, smallStats;
  const render::FrameImages reference = renderFile(blobs, camera, w, h, 0.3f, unlimited, &bigStats);
  const render::FrameImages limited = renderFile(blobs, camera, w, h, 0.3f, small, &smallStats);
  std::printf("unlimited: %d passes, %llu uploads; 1 MiB caches: %d passes, %llu uploads\n", bigStats.passes,
              (unsigned long long)bigStats.bricksUploaded, smallStats.passes,
              (unsigned long long)smallStats.bricksUploaded);
  ASSERT_GT(smallStats.bricksUploaded, bigStats.bricksUploaded) << "the small pool must have evicted bricks";
  EXPECT_GT(expectSameImage(reference, limited, "1 MiB caches"), w * h / 20);

  // Peak memory: the same budgets on a tiny dataset give the fixed overhead (libraries, GL driver,
  // images); the large one may add no more than the budgets and a little bookkeeping.
  const std::string caches = std::to_string(budgetMiB);
  const std::vector<std::string> flags = {"--res", "64x64", "--iso", "0.3", "--gpu-cache", caches, "--host-cache",
                                          caches, "--quiet"};
  auto run = [&](const std::string& file, const std::string& out) {
    std::vector<std::string> args = {"render", file, "-o", out};
    args.insert(args.end(), flags.begin(), flags.end());
    return runMeasured(args);
  };
  const ChildRun baseline = run(tiny, dir / "tiny.exr");
  const ChildRun large = run(blobs, dir / "blobs.exr");
  ASSERT_EQ(baseline.status, 0);
  ASSERT_EQ(large.status, 0);
  // Index topology, one upload batch of staging, allocator slack: well below the 7 MiB of data and
  // the 28 MiB pool an unbounded run uses, so a cache that ignored its budget would fail this.
  const double slackMiB = 4.0;
  const double growthMiB = double(large.peakRssKiB - baseline.peakRssKiB) / 1024.0;
  std::printf("peak RSS: tiny %ld KiB, blobs %ld KiB (+%.1f MiB; budgets 2 x %.0f MiB, data %.1f MiB)\n",
              baseline.peakRssKiB, large.peakRssKiB, growthMiB, budgetMiB, decodedMiB);
  EXPECT_LT(growthMiB, 2.0 * budgetMiB + slackMiB);
}

// A pass's requested bricks come back with its header, up to RenderOptions::requestsReadBack; the
// rest are read from the buffer itself. Either way the first pass of a view (from an empty pool)
// asks for the same bricks (in any order: rays append them concurrently), and frames complete alike.
TEST_F(Render, RequestsBeyondTheReadBackAreReadToo) {
  TempDir dir;
  const std::string blobs = writeSmallBlobs(dir);
  const io::BrickStore store(blobs);
  const render::Camera camera = smallBlobsCamera();
  const int w = 48, h = 40;
  render::RenderOptions options;  // a pool that holds every request (a smaller one keeps some of them)
  options.iso = 0.3f;
  render::RenderOptions fewReadBack = options;
  fewReadBack.requestsReadBack = 3;
  const auto sorted = [](std::vector<glm::ivec3> v) {
    std::sort(v.begin(), v.end(), [](const glm::ivec3& a, const glm::ivec3& b) {
      return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
    });
    return v;
  };
  render::Raycaster all(store, options), few(store, fewReadBack);
  const render::StepStats allStep = all.step(camera, w, h, 0.0), fewStep = few.step(camera, w, h, 0.0);
  ASSERT_GT(allStep.requested, 3u) << "the first pass must ask for more bricks than are read back with its header";
  EXPECT_EQ(fewStep.requested, allStep.requested);
  EXPECT_TRUE(sorted(few.lastRequests()) == sorted(all.lastRequests()))
      << "the first pass's requests differ (" << few.lastRequests().size() << " against " << all.lastRequests().size()
      << " bricks)";
  expectSameImage(renderFile(blobs, camera, w, h, options.iso, options),
                  renderFile(blobs, camera, w, h, options.iso, fewReadBack), "3 requests read back with the header");
}

// The viewer's progressive frames: step() with no upload time budget (one batch a step) reaches the
// same image as render() with a pool that must evict, restarts when the camera moves, and does no
// work once the frame is complete.
TEST_F(Render, ProgressiveStepsReachTheBlockingImage) {
  TempDir dir;
  const std::string blobs = writeSmallBlobs(dir);
  const render::Camera camera = smallBlobsCamera();
  const int w = 48, h = 40;
  render::RenderOptions options;
  options.iso = 0.3f;
  options.gpuCacheBytes = kSmallPoolBytes;
  const render::FrameImages reference = renderFile(blobs, camera, w, h, options.iso, options);

  const io::BrickStore store(blobs);
  render::Raycaster raycaster(store, options);
  const auto runToCompletion = [&](const render::Camera& cam, int& steps) {
    render::StepStats s;
    for (steps = 1; steps <= 100000; ++steps) {
      s = raycaster.step(cam, w, h, 0.0);
      // Over the passes of a view the rectangle grows with the image's surface pixels.
      expectSurfaceRect(raycaster, 0, "step " + std::to_string(steps));
      if (steps == 1) EXPECT_TRUE(s.restarted) << "a new view starts the rays over";
      else EXPECT_FALSE(s.restarted) << "step " << steps;
      if (s.complete) break;
    }
    return s;
  };
  int steps = 0;
  render::StepStats last = runToCompletion(camera, steps);
  ASSERT_TRUE(last.complete) << "no complete frame after " << steps << " steps";
  std::printf("complete after %d steps, %llu bricks uploaded\n", steps, (unsigned long long)raycaster.bricksUploaded());
  EXPECT_GT(steps, 2) << "a pool this small needs several steps";
  const render::FrameImages progressive = raycaster.readImages();
  EXPECT_GT(expectSameImage(reference, progressive, "progressive"), w * h / 20);

  const render::StepStats idle = raycaster.step(camera, w, h, 0.0);
  EXPECT_TRUE(idle.complete);
  EXPECT_FALSE(idle.dispatched) << "a complete frame needs no pass";

  // Bricks still arriving once the frame is complete (look-ahead requests) are taken in while idle,
  // so streaming settles. (Here the loader is usually done first; on the H200, whose frames are
  // faster than decoding, `bench view` never settled before step() uploaded on complete frames.)
  render::StepStats settling = idle;
  for (int i = 0; i < 10000 && settling.streaming > 0; ++i) settling = raycaster.step(camera, w, h, 0.0);
  EXPECT_EQ(settling.streaming, 0u) << "the loader still holds bricks after the frame completed";
  EXPECT_TRUE(settling.complete);

  render::Camera moved = camera;
  moved.eye.x += 30.0;
  last = runToCompletion(moved, steps);
  ASSERT_TRUE(last.complete);
  const render::FrameImages other = renderFile(blobs, moved, w, h, options.iso, options);
  const render::FrameImages afterMove = raycaster.readImages();
  expectSameImage(other, afterMove, "progressive, after the camera moved");
}

// Columns covered by the viewer's opaque panel get no rays: the uncovered ones match render() bit for
// bit (also with an evicting pool), and the covered ones keep what the image held before.
TEST_F(Render, CoveredColumnsAreNotRaycast) {
  TempDir dir;
  const std::string blobs = writeSmallBlobs(dir);
  const render::Camera camera = smallBlobsCamera();
  const int w = 48, h = 40, covered = 13;  // not a multiple of the work group's width
  render::RenderOptions options;
  options.iso = 0.3f;
  options.gpuCacheBytes = kSmallPoolBytes;
  const io::BrickStore store(blobs);
  render::Raycaster raycaster(store, options);
  render::Camera before = camera;
  before.eye.x += 30.0;
  raycaster.render(before, w, h);
  const render::FrameImages old = raycaster.readImages();
  render::StepStats s;
  int steps = 0;
  while (!s.complete && ++steps < 100000) s = raycaster.step(camera, w, h, 0.0, covered);
  ASSERT_TRUE(s.complete);
  const render::FrameImages stepped = raycaster.readImages();
  expectSurfaceRect(raycaster, covered, "steps beside the cover");
  const render::FrameImages full = renderFile(blobs, camera, w, h, options.iso, options);
  raycaster.render(camera, w, h);
  expectSurfaceRect(raycaster, 0, "render()");
  EXPECT_FALSE(raycaster.surfaceRect().empty());
  int uncoveredHits = 0, coveredChanged = 0, coveredWouldChange = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 4; ++c) {
        const std::size_t i = (std::size_t(y) * w + x) * 4 + c;
        if (x >= covered) {
          ASSERT_EQ(stepped.rgba[i], full.rgba[i]) << "pixel " << x << "," << y << " channel " << c;
          ASSERT_EQ(stepped.normalDepth[i], full.normalDepth[i]) << "pixel " << x << "," << y << " channel " << c;
          uncoveredHits += c == 3 && full.rgba[i] > 0.5f;
        } else {
          coveredChanged += stepped.rgba[i] != old.rgba[i];
          coveredWouldChange += full.rgba[i] != old.rgba[i];
        }
      }
  EXPECT_GT(uncoveredHits, (w - covered) * h / 20) << "the surface must show beside the cover";
  EXPECT_GT(coveredWouldChange, 0) << "the two views must differ under the cover for this test to mean anything";
  EXPECT_EQ(coveredChanged, 0) << "rays were cast under the cover";
}

// Every brick layout of the pool (viewer/BrickPool.h) reads the same coefficients, so the images
// are bit-identical, also when a small pool makes bricks move between slots.
TEST_F(Render, EveryBrickLayoutGivesTheSameImage) {
  TempDir dir;
  const std::string blobs = writeSmallBlobs(dir);
  const render::Camera camera = smallBlobsCamera();
  const int w = 40, h = 32;
  render::RenderOptions options;
  options.gpuCacheBytes = kSmallPoolBytes;
  render::FrameStats stats;
  const render::FrameImages reference = renderFile(blobs, camera, w, h, 0.3f, options, &stats);
  ASSERT_GT(expectSameImage(reference, reference, "reference"), w * h / 20);
  for (const render::BrickLayout layout : render::allBrickLayouts()) {
    options.layout = layout;
    render::FrameStats s;
    const render::FrameImages image = renderFile(blobs, camera, w, h, 0.3f, options, &s);
    std::printf("%s: %d passes, %llu uploads\n", render::brickLayoutName(layout).c_str(), s.passes,
                (unsigned long long)s.bricksUploaded);
    expectSameImage(reference, image, render::brickLayoutName(layout));
  }
  EXPECT_THROW(render::parseBrickLayout("one-channel"), ValueError);

  // Without a layout asked for: one channel while every varying brick fits the budget, else four.
  const io::BrickStore store(blobs);
  const render::FccBrickSource source(store, std::size_t(1) << 20);
  const std::size_t varying = std::size_t(store.bounds().activeVoxelCount());
  const std::size_t scalarSlot = render::BrickPool::slotBytes(render::BrickLayout::TextureScalar) + 4096;
  EXPECT_EQ(render::chooseBrickLayout(source, varying * scalarSlot), render::BrickLayout::TextureScalar);
  EXPECT_EQ(render::chooseBrickLayout(source, varying * scalarSlot - 1), render::BrickLayout::TextureVec4);
}

}  // namespace
}  // namespace fcc

namespace fcc {
namespace {

// The clipping box cuts rays (a hit inside the box is the unclipped hit; every hit lies inside it) and
// bricks (outside it none is loaded); a box around everything changes no pixel.
TEST_F(Render, ClippingBoxCutsRaysAndBricks) {
  TempDir dir;
  const std::string path = writeSmallBlobs(dir);
  const render::Camera camera = smallBlobsCamera();
  const int w = 64, h = 64;
  const io::BrickStore store(path);
  glm::dvec3 lo, hi;
  store.worldBounds(lo, hi);
  render::RenderOptions options;
  render::FrameStats fullStats, cutStats;
  const render::FrameImages full = renderFile(path, camera, w, h, 0.3f, options, &fullStats);
  options.clipLo = lo - 10.0;
  options.clipHi = hi + 10.0;
  const render::FrameImages around = renderFile(path, camera, w, h, 0.3f, options);
  EXPECT_EQ(full.rgba, around.rgba) << "a box around everything changes no pixel";
  EXPECT_EQ(full.normalDepth, around.normalDepth);

  const glm::dvec3 mid = 0.5 * (lo + hi);
  options.clipLo = lo - 10.0;
  options.clipHi = glm::dvec3(mid.x, hi.y + 10.0, hi.z + 10.0);  // the half x < mid.x
  const render::FrameImages cut = renderFile(path, camera, w, h, 0.3f, options, &cutStats);
  EXPECT_LT(cutStats.bricksUploaded, fullStats.bricksUploaded) << "bricks outside the box are not loaded";
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  int kept = 0, inside = 0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const std::size_t i = std::size_t(py) * w + px;
      const glm::dvec3 d = render::pixelRay(frame, px, py, w, h);
      if (cut.rgba[4 * i + 3] > 0.5f) {
        const glm::dvec3 p = camera.eye + double(cut.normalDepth[4 * i + 3]) * d;
        EXPECT_LE(p.x, mid.x + 1e-3) << "pixel (" << px << ", " << py << ") hits outside the box";
        ++inside;
      }
      if (full.rgba[4 * i + 3] > 0.5f) {
        const glm::dvec3 p = camera.eye + double(full.normalDepth[4 * i + 3]) * d;
        if (p.x < mid.x - 1e-2) {  // the unclipped hit is inside: the clipped ray finds it too
          ASSERT_GT(cut.rgba[4 * i + 3], 0.5f) << "pixel (" << px << ", " << py << ")";
          EXPECT_NEAR(cut.normalDepth[4 * i + 3], full.normalDepth[4 * i + 3], 1e-3) << "pixel (" << px << ", " << py << ")";
          ++kept;
        }
      }
    }
  EXPECT_GT(kept, w * h / 20);
  EXPECT_GT(inside, kept) << "the cut opens the blobs: surfaces behind the cut show";
  std::printf("clip: %d hits kept, %d inside the half box; bricks %llu of %llu\n", kept, inside,
              (unsigned long long)cutStats.bricksUploaded, (unsigned long long)fullStats.bricksUploaded);

  options.clipLo = glm::dvec3(1.0);
  options.clipHi = glm::dvec3(0.0);  // empty
  const render::FrameImages none = renderFile(path, camera, w, h, 0.3f, options);
  for (std::size_t i = 3; i < none.rgba.size(); i += 4) ASSERT_EQ(none.rgba[i], 0.0f) << "an empty box shows nothing";
}

}  // namespace
}  // namespace fcc
