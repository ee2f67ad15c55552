// Level of detail in the raycaster (docs/RENDERER.md, "Level of detail"): a file with a pyramid
// (`synth ... --pyramid`) drawn at full resolution and without a pyramid give today's image bit for bit;
// progressive steps with a tiny pool show no hole once the coarsest level is resident; the converged
// image equals the full-resolution one bit for bit; the bias rises when the pool cannot hold the bricks
// a frame wants, and the frame completes.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <thread>
#include <string>
#include <vector>

#include "RenderTestSupport.h"
#include "tests/PrivateUserCache.h"
#include "tests/tools/RunCommand.h"
#include "sparse/TransferFunction.h"
#include "viewer/Camera.h"
#include "viewer/FccBrickSource.h"
#include "viewer/PyramidLevels.h"

namespace fcc {
namespace {

using test::GlSuite;
using test::TempDir;

class Lod : public GlSuite {};

// The sphere field's surface, with and without a pyramid, from one synth run each (level 0 is the
// same bits: docs/FORMAT.md). 96^3: 6^3 level-0 bricks, three levels above them.
struct SphereFiles {
  std::string plain, pyramid;
};
SphereFiles writeSpheres(const TempDir& dir) {
  SphereFiles f{dir / "sphere.vdb", dir / "sphere_lod.vdb"};
  EXPECT_EQ(test::runFccvdb("synth sphere " + f.plain + " --dims 96,96,96 --quiet").status, 0);
  EXPECT_EQ(test::runFccvdb("synth sphere " + f.pyramid + " --dims 96,96,96 --pyramid --quiet").status, 0);
  return f;
}

// Close enough that every brick wants level 0 at this size (a level-0 voxel covers more than half a
// pixel everywhere: the distance to any brick's centre, at most 190, times 2 tan(20 deg) / 80 stays
// below 2 voxels).
render::Camera nearCamera() {
  render::Camera camera;
  camera.eye = glm::dvec3(130.0, 100.0, 120.0);
  camera.lookat = glm::dvec3(48.0);
  return camera;
}
constexpr int kW = 88, kH = 80;
constexpr float kIso = 0.5f;

bool hit(const render::FrameImages& image, std::size_t pixel) { return image.rgba[pixel * 4 + 3] > 0.5f; }

// Bit for bit, colour, normal and depth; the count of hit pixels (or -1 on the first difference).
int sameImage(const render::FrameImages& a, const render::FrameImages& b, const std::string& what) {
  if (a.rgba.size() != b.rgba.size() || a.normalDepth.size() != b.normalDepth.size()) {
    ADD_FAILURE() << what << ": sizes differ";
    return -1;
  }
  int hits = 0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    if (a.rgba[i] != b.rgba[i] || !(a.normalDepth[i] == b.normalDepth[i])) {
      ADD_FAILURE() << what << ": pixel " << i / 4 << " component " << i % 4 << ": " << a.rgba[i] << " vs " << b.rgba[i]
                    << ", normal/depth " << a.normalDepth[i] << " vs " << b.normalDepth[i];
      return -1;
    }
    hits += (i % 4 == 3) && a.rgba[i] > 0.5f;
  }
  return hits;
}

struct Opened {
  explicit Opened(const std::string& path, std::size_t hostCache = std::size_t(64) << 20)
      : store(path), level0(store, hostCache), levels(store, hostCache) {}
  io::BrickStore store;
  render::FccBrickSource level0;
  render::PyramidLevels levels;
};

render::RenderOptions isoOptions(std::size_t gpuBytes = std::size_t(256) << 20) {
  render::RenderOptions o;
  o.iso = kIso;
  o.gpuCacheBytes = gpuBytes;
  o.countBricksDrawn = true;
  return o;
}

TEST_F(Lod, FullResolutionAndAFileWithoutPyramidGiveTodaysImage) {
  TempDir dir;
  const SphereFiles files = writeSpheres(dir);
  Opened withPyramid(files.pyramid);
  ASSERT_GE(withPyramid.levels.size(), 2u) << "96^3: levels 1, 2 and more";
  const std::size_t levelCount = withPyramid.levels.size() + 1;
  // Today's image: the file without a pyramid (its raycaster has no levels: the unchanged program).
  const render::FrameImages today = test::renderFile(files.plain, nearCamera(), kW, kH, kIso, isoOptions());
  // --full-resolution: the pyramid's file, its levels not given to the raycaster.
  render::Raycaster full(withPyramid.level0, isoOptions());
  const render::FrameStats stats = full.render(nearCamera(), kW, kH);
  EXPECT_GT(sameImage(today, full.readImages(), "full resolution vs no pyramid"), kW * kH / 10);
  ASSERT_EQ(stats.bricksPerLevel.size(), 1u);
  EXPECT_GT(stats.bricksPerLevel[0], 0u);
  EXPECT_EQ(stats.fullResolutionFraction, 1.0);
  // With the levels and bias 0, every brick here wants level 0: the level-of-detail program's complete
  // frame is the same image, and says so in its mix.
  render::RenderOptions lod = isoOptions();
  lod.coarserLevels = withPyramid.levels.sources();
  render::Raycaster levels(withPyramid.level0, lod);
  EXPECT_EQ(levels.levelCount(), int(levelCount));
  const render::FrameStats lodStats = levels.render(nearCamera(), kW, kH);
  EXPECT_GT(sameImage(today, levels.readImages(), "level of detail, all bricks at level 0"), kW * kH / 10);
  ASSERT_EQ(lodStats.bricksPerLevel.size(), levelCount);
  EXPECT_GT(lodStats.bricksPerLevel[0], 0u);
  for (std::size_t k = 1; k < levelCount; ++k) EXPECT_EQ(lodStats.bricksPerLevel[k], 0u) << "no brick of level " << k;
  EXPECT_EQ(lodStats.fullResolutionFraction, 1.0);
  EXPECT_EQ(lodStats.lodBias, 0.0);
}

// A positive bias draws coarser levels: the mix says so, and the image is a sphere still (close to the
// full-resolution one: most pixels agree on hit or miss).
TEST_F(Lod, BiasDrawsCoarserLevelsAndTheMixSaysSo) {
  TempDir dir;
  const SphereFiles files = writeSpheres(dir);
  Opened opened(files.pyramid);
  render::RenderOptions lod = isoOptions();
  lod.coarserLevels = opened.levels.sources();
  lod.lodBias = 10.0f;  // every brick: the coarsest level
  render::Raycaster coarse(opened.level0, lod);
  const render::FrameStats stats = coarse.render(nearCamera(), kW, kH);
  const std::size_t levelCount = opened.levels.size() + 1;
  ASSERT_EQ(stats.bricksPerLevel.size(), levelCount);
  for (std::size_t k = 0; k + 1 < levelCount; ++k) EXPECT_EQ(stats.bricksPerLevel[k], 0u) << "level " << k;
  EXPECT_GT(stats.bricksPerLevel.back(), 0u);
  EXPECT_EQ(stats.fullResolutionFraction, 0.0);
  const render::FrameImages coarseImage = coarse.readImages();
  const render::FrameImages full = test::renderFile(files.plain, nearCamera(), kW, kH, kIso, isoOptions());
  int agree = 0, hits = 0;
  for (std::size_t p = 0; p < std::size_t(kW * kH); ++p) {
    agree += hit(full, p) == hit(coarseImage, p);
    hits += hit(coarseImage, p);
  }
  EXPECT_GT(hits, kW * kH / 10);
  EXPECT_GT(agree, kW * kH * 95 / 100) << "the coarsest sphere covers nearly the same pixels";
}

// --host-cache is the total over every level: the coarser levels take level k's share, 1/8^k of it,
// and level 0's cache the rest; what the caches hold after a frame drawn from several levels stays
// within it.
TEST_F(Lod, HostCacheBudgetIsSharedByTheLevels) {
  TempDir dir;
  const SphereFiles files = writeSpheres(dir);
  constexpr std::size_t kHostBytes = std::size_t(2) << 20;  // smaller than the data: caches fill up
  const io::BrickStore store(files.pyramid);
  const render::PyramidLevels levels(store, kHostBytes);
  ASSERT_GE(levels.size(), 2u);
  std::size_t expected = 0;
  for (std::size_t k = 1; k <= levels.size(); ++k) expected += kHostBytes >> (3 * k);
  EXPECT_EQ(levels.hostCacheBytes(), expected);
  EXPECT_LT(levels.hostCacheBytes(), kHostBytes / 7 + 1);
  render::RenderOptions lod = isoOptions();
  lod.hostCacheBytes = kHostBytes;
  lod.coarserLevels = levels.sources();
  lod.lodBias = 1.0f;  // some bricks at level 0, some coarser
  render::Raycaster raycaster(store, lod);
  EXPECT_EQ(raycaster.hostCacheUse().budgetBytes, kHostBytes);
  const render::FrameStats stats = raycaster.render(nearCamera(), kW, kH);
  const render::HostCacheUse use = raycaster.hostCacheUse();
  EXPECT_GT(use.bytesUsed, 0u);
  EXPECT_LE(use.bytesUsed, kHostBytes) << "levels drawn: " << stats.bricksPerLevel.size();
}

// Level 0 as a slow disk would give it: each brick's decode waits kDelay first. Progressive steps
// then see the coarse level (pinned, a few fast bricks) long before the fine bricks; without it, the
// loader threads' speed against the steps' decides whether any intermediate image shows a coarse
// brick (CI's loaded 2-core machine once loaded every fine brick before the coarse level was in).
class SlowSource : public render::BrickSource {
 public:
  static constexpr std::chrono::milliseconds kDelay{15};
  explicit SlowSource(const render::BrickSource& inner) : inner_(inner) {}
  const std::string& path() const override { return inner_.path(); }
  const ReconstructionInfo& reconstruction() const override { return inner_.reconstruction(); }
  render::SlotBlock slotBlock() const override { return inner_.slotBlock(); }
  const glm::dmat4& worldFromIndex() const override { return inner_.worldFromIndex(); }
  void brickBox(glm::ivec3& lo, glm::ivec3& hi) const override { inner_.brickBox(lo, hi); }
  void worldBounds(glm::dvec3& lo, glm::dvec3& hi) const override { inner_.worldBounds(lo, hi); }
  float background() const override { return inner_.background(); }
  float valueMin() const override { return inner_.valueMin(); }
  float valueMax() const override { return inner_.valueMax(); }
  void forEachVaryingBrick(const std::function<void(const glm::ivec3&, float, float)>& visit) const override {
    inner_.forEachVaryingBrick(visit);
  }
  std::size_t varyingBrickCount() const override { return inner_.varyingBrickCount(); }
  void decode(std::vector<render::LoadedBrick>& chunk) const override {
    std::this_thread::sleep_for(kDelay * chunk.size());
    inner_.decode(chunk);
  }
  render::HostCacheUse hostCacheUse() const override { return inner_.hostCacheUse(); }
  io::Damage damage() const override { return inner_.damage(); }

 private:
  const render::BrickSource& inner_;
};

// Progressive steps over a pool of a few dozen slots (the bias kept at 0), level 0 slow to load: coarse
// first, finer bricks replacing them. What is tested, precisely: once the coarsest level is resident
// and one pass has run with it, every pixel that the full-resolution image hits and whose 8 neighbours
// it hits too (the silhouette's pixels may differ between levels: a coarser spline's sphere is not the
// same sphere) is hit in every later intermediate image; some intermediate image shows coarser bricks
// (differs from the full-resolution one); and the converged image equals the full-resolution one bit
// for bit.
TEST_F(Lod, ProgressiveStepsShowNoHoleAndConvergeToFullResolution) {
  TempDir dir;
  const SphereFiles files = writeSpheres(dir);
  Opened opened(files.pyramid);
  const SlowSource slowLevel0(opened.level0);
  const render::FrameImages full = test::renderFile(files.plain, nearCamera(), kW, kH, kIso, isoOptions());
  render::RenderOptions lod = isoOptions(test::kSmallPoolBytes);
  lod.coarserLevels = opened.levels.sources();
  lod.lodAdaptBias = false;
  render::Raycaster raycaster(slowLevel0, lod);

  const auto interior = [&](int x, int y) {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int u = x + dx, v = y + dy;
        if (u < 0 || v < 0 || u >= kW || v >= kH || !hit(full, std::size_t(v) * kW + u)) return false;
      }
    return true;
  };
  // Checked as they come (a slow level 0 gives hundreds of steps; their images are not kept).
  int intermediate = 0, checked = 0, coarserShown = 0;
  const auto checkIntermediate = [&](const render::FrameImages& image, int step) {
    ++intermediate;
    int holes = 0;
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (!interior(x, y)) continue;
        ++checked;
        holes += !hit(image, std::size_t(y) * kW + x);
      }
    EXPECT_EQ(holes, 0) << "the image after step " << step << " shows " << holes << " holes";
    coarserShown += image.rgba != full.rgba;
  };
  bool coarseSeen = false, complete = false;
  int steps = 0;
  for (steps = 1; steps <= 20000 && !complete; ++steps) {
    const bool coarseBefore = raycaster.coarsestResident();
    const render::StepStats s = raycaster.step(nearCamera(), kW, kH, 0.0);
    complete = s.complete;
    if (coarseSeen && !complete) checkIntermediate(raycaster.readImages(false), steps);
    coarseSeen = coarseSeen || (coarseBefore && s.dispatched);
  }
  ASSERT_TRUE(complete) << "no complete frame after " << steps << " steps";
  std::printf("complete after %d steps, %d intermediate images checked (%d show coarser bricks), %llu bricks uploaded into %u slots\n",
              steps, intermediate, coarserShown, (unsigned long long)raycaster.bricksUploaded(), raycaster.slotCount());
  EXPECT_GT(raycaster.bricksUploaded(), raycaster.slotCount()) << "the pool must be too small for the frame";
  EXPECT_GE(intermediate, 1);
  EXPECT_GT(checked, 0);
  EXPECT_GT(coarserShown, 0) << "some intermediate image must show coarser levels";
  const render::FrameImages converged = raycaster.readImages();
  EXPECT_GT(sameImage(full, converged, "converged progressive vs full resolution"), kW * kH / 10);
  const render::LevelMix mix = raycaster.levelMix();
  EXPECT_EQ(mix.fullResolutionFraction, 1.0);
}

// A pool far too small for the bricks bias 0 wants: render() raises the bias and completes with
// coarser levels; without adapting, the same pool streams the level-0 bricks through.
TEST_F(Lod, BiasRisesWhenThePoolIsTooSmallAndTheFrameCompletes) {
  TempDir dir;
  const SphereFiles files = writeSpheres(dir);
  Opened opened(files.pyramid);
  render::RenderOptions lod = isoOptions(test::kSmallPoolBytes / 2);
  lod.coarserLevels = opened.levels.sources();
  render::Raycaster small(opened.level0, lod);
  const render::FrameStats s = small.render(nearCamera(), kW, kH);
  std::printf("%u slots: bias %.1f after %d restarts, %d passes, level mix", small.slotCount(), s.lodBias, s.lodRestarts, s.passes);
  for (uint64_t n : s.bricksPerLevel) std::printf(" %llu", (unsigned long long)n);
  std::printf(", full resolution %.3f\n", s.fullResolutionFraction);
  EXPECT_GT(s.lodBias, 0.0);
  EXPECT_GE(s.lodRestarts, 1);
  EXPECT_LT(s.fullResolutionFraction, 1.0);
  const render::FrameImages image = small.readImages();
  int hits = 0;
  for (std::size_t p = 0; p < std::size_t(kW * kH); ++p) hits += hit(image, p);
  EXPECT_GT(hits, kW * kH / 10) << "the frame completes with the surface";

  // Without adapting, the same pool streams the level-0 bricks through and ends at full resolution.
  lod.lodAdaptBias = false;
  render::Raycaster fixed(opened.level0, lod);
  const render::FrameStats f = fixed.render(nearCamera(), kW, kH);
  EXPECT_EQ(f.lodBias, 0.0);
  EXPECT_EQ(f.fullResolutionFraction, 1.0);
  const render::FrameImages full = test::renderFile(files.plain, nearCamera(), kW, kH, kIso, isoOptions());
  EXPECT_GT(sameImage(full, fixed.readImages(), "small pool, bias fixed at 0"), kW * kH / 10);

}

// DVR through the pyramid: each brick integrated from the level it wants, waiting for it (no stand-in:
// what a ray integrated is not taken back). Bias 0 near the data (every brick wants level 0) gives the
// full-resolution DVR image bit for bit; a positive bias (1: the farther bricks) draws coarser levels, says so in the mix, and
// gives nearly the same image from fewer bricks; a pool too small for the frame gives the big pool's
// image bit for bit.
TEST_F(Lod, DvrDrawsEachBrickFromItsLevel) {
  TempDir dir;
  const SphereFiles files = writeSpheres(dir);
  Opened opened(files.pyramid);
  // The sphere field is 0 at the centre, 1 at the box's faces' middles: a translucent ball, the
  // background (above 0.6) transparent.
  const TransferFunction tf({{0.0, {1.0, 0.8, 0.3}}, {0.6, {0.2, 0.4, 1.0}}}, {{0.0, 0.05}, {0.6, 0.3}, {0.6, 0.0}});
  const auto table = std::make_shared<const TransferTable>(tf, 0.0, 0.65, 256, OpticalScale{8.0, 1.0});
  const auto dvrOptions = [&](std::size_t gpuBytes = std::size_t(256) << 20) {
    render::RenderOptions o = isoOptions(gpuBytes);
    o.mode = render::RenderMode::Dvr;
    o.transfer = table;
    return o;
  };
  // The pyramid's walk takes two gathers a cell (the chain of pieces is the flat walk's:
  // march_fcc.glsl), so the full-resolution image it must give bit for bit is the flat walk's with two.
  render::FrameImages full;
  {
    const test::ScopedEnv twoGathers("FCCVDB_SHADER_DEFINES", "FCC_DVR_CHAIN=0");
    render::Raycaster plain(opened.level0, dvrOptions());
    plain.render(nearCamera(), kW, kH);
    full = plain.readImages();
  }
  double opacity = 0.0;
  for (std::size_t i = 3; i < full.rgba.size(); i += 4) opacity = std::max(opacity, double(full.rgba[i]));
  EXPECT_GT(opacity, 0.3) << "the ball must be seen";
  const auto meanDifference = [&](const render::FrameImages& a) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) sum += std::abs(double(a.rgba[i]) - full.rgba[i]);
    return sum / double(a.rgba.size());
  };

  render::RenderOptions lod = dvrOptions();
  lod.coarserLevels = opened.levels.sources();
  render::Raycaster levels(opened.level0, lod);
  const render::FrameStats atZero = levels.render(nearCamera(), kW, kH);
  ASSERT_EQ(atZero.bricksPerLevel.size(), opened.levels.size() + 1);
  for (std::size_t k = 1; k < atZero.bricksPerLevel.size(); ++k) EXPECT_EQ(atZero.bricksPerLevel[k], 0u) << "level " << k;
  EXPECT_EQ(atZero.fullResolutionFraction, 1.0);
  EXPECT_EQ(levels.readImages().rgba, full.rgba) << "bias 0, every brick at level 0: the full-resolution image";

  lod.lodBias = 1.0f;
  render::Raycaster coarser(opened.level0, lod);
  const render::FrameStats biased = coarser.render(nearCamera(), kW, kH);
  const render::FrameImages coarserImage = coarser.readImages();
  std::printf("bias 1: level mix");
  for (uint64_t n : biased.bricksPerLevel) std::printf(" %llu", (unsigned long long)n);
  std::printf(" (%llu bricks uploaded, %llu at level 0 alone); mean difference %.4g\n", (unsigned long long)biased.bricksUploaded,
              (unsigned long long)atZero.bricksUploaded, meanDifference(coarserImage));
  uint64_t coarse = 0;
  for (std::size_t k = 1; k < biased.bricksPerLevel.size(); ++k) coarse += biased.bricksPerLevel[k];
  EXPECT_GT(coarse, 0u) << "the bias draws coarser levels";
  EXPECT_LT(biased.fullResolutionFraction, 1.0) << "and the mix says so";
  EXPECT_LT(biased.bricksUploaded, atZero.bricksUploaded);
  EXPECT_LT(meanDifference(coarserImage), 0.01) << "a coarser spline of the same field";
  EXPECT_NE(coarserImage.rgba, full.rgba);
  // The walk's schedule changes no pixel through the pyramid either (a round that takes one cell
  // against one that finds the next non-zero cell; RenderDvr.WalkSchedulesGiveTheSameImage covers the
  // flat walk).
  {
    const test::ScopedEnv oneCell("FCCVDB_SHADER_DEFINES", "FCC_DVR_FIND_THEN_INTEGRATE=0");
    render::Raycaster scheduled(opened.level0, lod);
    scheduled.render(nearCamera(), kW, kH);
    const render::FrameImages other = scheduled.readImages();
    EXPECT_EQ(other.rgba, coarserImage.rgba) << "FCC_DVR_FIND_THEN_INTEGRATE=0 through the pyramid";
    EXPECT_EQ(other.normalDepth, coarserImage.normalDepth) << "FCC_DVR_FIND_THEN_INTEGRATE=0 through the pyramid";
  }

  // Shaded: a coarser level's gradient is in its own index space (2^k times level 0's): shading by it
  // must come out as level 0's would, close to the full-resolution shaded image; under the headlight
  // and under a directional light with a highlight (--light), whose angles take the level's gradient
  // scaled back too.
  const auto meanDifferenceOf = [](const render::FrameImages& a, const render::FrameImages& b) {
    double sum = 0.0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) sum += std::abs(double(a.rgba[i]) - b.rgba[i]);
    return sum / double(a.rgba.size());
  };
  // Level 0's image and the levels' at bias 1 with `options`.
  const auto fullAndLevels = [&](render::RenderOptions options) {
    render::Raycaster full(opened.level0, options);
    full.render(nearCamera(), kW, kH);
    options.coarserLevels = opened.levels.sources();
    options.lodBias = 1.0f;
    render::Raycaster levels(opened.level0, options);
    levels.render(nearCamera(), kW, kH);
    return std::make_pair(full.readImages(), levels.readImages());
  };
  render::RenderOptions shaded = dvrOptions();
  shaded.dvrShading.on = true;
  const auto [shadedFull, shadedLevels] = fullAndLevels(shaded);
  const double shadedDifference = meanDifferenceOf(shadedLevels, shadedFull);
  std::printf("shaded, bias 1: mean difference %.4g\n", shadedDifference);
  EXPECT_LT(shadedDifference, 0.01) << "the coarser levels' shading differs from level 0's";
  render::RenderOptions lit = shaded;
  lit.dvrShading.light = render::DvrLight::Directional;
  lit.lightInCamera = render::lightInCameraFromAngles(50.0f, 30.0f);
  lit.dvrShading.specular = 0.5f;
  const auto [litFull, litLevels] = fullAndLevels(lit);
  const double litDifference = meanDifferenceOf(litLevels, litFull), fromHeadlight = meanDifferenceOf(litFull, shadedFull);
  std::printf("directional light, bias 1: mean difference %.4g (the light against the headlight: %.4g)\n", litDifference,
              fromHeadlight);
  EXPECT_LT(litDifference, 0.01) << "the coarser levels' light differs from level 0's";
  EXPECT_GT(fromHeadlight, 10.0 * litDifference) << "the light must show more than the levels do";
  // The light kit (its headlight's term takes the level's scale as the headlight does; its directional
  // lights' as the directional light does).
  render::RenderOptions kit = lit;
  kit.dvrShading.light = render::DvrLight::Kit;
  const auto [kitFull, kitLevels] = fullAndLevels(kit);
  const double kitDifference = meanDifferenceOf(kitLevels, kitFull);
  std::printf("light kit, bias 1: mean difference %.4g\n", kitDifference);
  EXPECT_LT(kitDifference, 0.01) << "the coarser levels' light kit differs from level 0's";

  // Out of core through the levels: a pool of a few dozen slots, the bias held, the same image.
  render::RenderOptions small = dvrOptions(test::kSmallPoolBytes);
  small.coarserLevels = opened.levels.sources();
  small.lodBias = 1.0f;
  small.lodAdaptBias = false;
  render::Raycaster streamed(opened.level0, small);
  const render::FrameStats s = streamed.render(nearCamera(), kW, kH);
  EXPECT_GT(s.bricksUploaded, streamed.slotCount()) << "the pool must be too small for the frame";
  EXPECT_EQ(streamed.readImages().rgba, coarserImage.rgba) << "the image does not depend on the pool";
}

}  // namespace
}  // namespace fcc
