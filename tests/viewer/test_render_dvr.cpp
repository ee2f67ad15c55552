// Direct volume rendering on the GPU (shaders/dvr.glsl): the exact chord opacity of a sphere, agreement
// with the CPU reference integrator (sparse/ReferenceDvr.h) on every lattice, and images independent of
// skipping and of the cache budgets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "CartesianTestSupport.h"
#include "tests/PrivateUserCache.h"
#include "RenderTestSupport.h"
#include "io/VdbFile.h"
#include "sparse/CubicBSpline.h"
#include "sparse/Lattice.h"
#include "sparse/LatticeSamples.h"
#include "sparse/ReferenceDvr.h"
#include "sparse/SynthFields.h"
#include "viewer/BccBrickSource.h"
#include "viewer/DvrTableGpu.h"
#include "viewer/FccBrickSource.h"
#include "viewer/GlProgram.h"
#include "viewer/ProjectedTetrahedra.h"

namespace fcc {
namespace {

using test::GlSuite;
using test::TempDir;
using test::renderSource;

// The bound: the device against the CPU reference, PSNR of premultiplied RGBA.
constexpr double kMinPsnrDb = 45.0;
// The sphere: |alpha - (1 - exp(-sigma chord))| per pixel. The transfer table turns the step of the
// opacity at r^2 into a ramp one entry wide (4e-4 of f here, 0.007 voxels of radius), and float
// arithmetic adds ~1e-6: well inside.
constexpr double kChordAlphaTol = 2e-3;
// Two images of one medium whose sub-steps differ (the sub-step rule with or without its curvature
// term): opacity per pixel.
constexpr double kSubStepOpacityTol = 2e-3;

render::RenderOptions dvrOptions(const TransferTable& table) {
  render::RenderOptions options;
  options.mode = render::RenderMode::Dvr;
  options.transfer = std::make_shared<const TransferTable>(table);
  return options;
}

// A GPU image as the pixels psnr compares with (another renderer's image as the reference).
std::vector<DvrPixel> pixelsOf(const render::FrameImages& image) {
  std::vector<DvrPixel> pixels(image.rgba.size() / 4);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    pixels[i].rgba = glm::dvec4(image.rgba[4 * i], image.rgba[4 * i + 1], image.rgba[4 * i + 2], image.rgba[4 * i + 3]);
  return pixels;
}

double psnr(const render::FrameImages& image, const std::vector<DvrPixel>& reference) {
  double sum = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      const double e = double(image.rgba[4 * i + c]) - reference[i].rgba[c];
      sum += e * e;
    }
  const double mse = sum / double(4 * reference.size());
  {  // where it is worst, for a failure's message
    std::size_t worst = 0;
    double worstE = 0.0;
    for (std::size_t i = 0; i < reference.size(); ++i) {
      const double e = std::abs(double(image.rgba[4 * i + 3]) - reference[i].rgba[3]);
      if (e > worstE) worstE = e, worst = i;
    }
    std::printf("worst alpha error %.4g at pixel %zu: device %.6g reference %.6g\n", worstE, worst,
                double(image.rgba[4 * worst + 3]), reference[worst].rgba[3]);
  }
  return mse > 0.0 ? 10.0 * std::log10(1.0 / mse) : 1e9;
}

// How two device images differ, component by component: how many components differ, the largest
// difference and the PSNR between them (1e9 where equal).
struct ImageDifference {
  int differing = 0;
  double worst = 0.0, psnrDb = 1e9;
};
ImageDifference differenceOf(const render::FrameImages& a, const render::FrameImages& b) {
  ImageDifference d;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    const double e = std::abs(double(a.rgba[i]) - b.rgba[i]);
    d.differing += e != 0.0;
    d.worst = std::max(d.worst, e);
    sum += e * e;
  }
  const double mse = sum / double(a.rgba.size());
  if (mse > 0.0) d.psnrDb = 10.0 * std::log10(1.0 / mse);
  return d;
}

// An FCC grid's coefficients for the CPU reference, read from the tree itself, not an accessor (not
// thread-safe): the reference's rows run in parallel. `grid` outlives the function.
SiteValue siteValuesOf(const FccGrid& grid) {
  return [&grid](const glm::ivec3& ijk) {
    const glm::ivec3 v = packedVoxelOfSite(ijk);
    return grid.tree().getValue(openvdb::Coord(v.x, v.y, v.z))[channelOfSite(ijk)];
  };
}

// A colour map with an opacity ramp over [lo, hi] (zero below lo), constant above up to `cut` and zero
// from there: the renderer draws only bricks with data, so the background must be transparent (the
// Cartesian test grid's is 2, above its data).
TransferTable rampTable(double lo, double hi, double unitDistance, double cut = 1e30) {
  std::vector<OpacityPoint> opacity{{lo, 0.0}, {hi, 0.6}};
  if (cut < 1e30) opacity.insert(opacity.end(), {{cut, 0.6}, {cut, 0.0}});
  const TransferFunction tf({{lo, {0.1, 0.2, 0.9}}, {0.5 * (lo + hi), {0.9, 0.5, 0.1}}, {hi, {1.0, 1.0, 0.8}}}, opacity);
  return TransferTable(tf, lo, cut < 1e30 ? cut + 0.05 : hi, 256, OpticalScale{unitDistance, 1.0});
}

// The camera the Cartesian and BCC test grids (test::kDim^3 points, worldFromIndex theirs) are seen
// from: at their centre, from above one corner.
render::Camera cartesianTestCamera(const glm::dmat4& worldFromIndex) {
  render::Camera camera;
  camera.lookat = glm::dvec3(worldFromIndex * glm::dvec4(24.0, 24.0, 24.0, 1.0));
  camera.eye = camera.lookat + glm::dvec3(30.0, 22.0, 36.0);
  camera.fovYDegrees = 35.0;
  return camera;
}

// The small blobs file (test::writeSmallBlobs) in a temporary folder, its store, a source that holds
// every brick, and the camera that sees it: what most tests below start from.
struct SmallBlobs {
  TempDir dir;
  io::BrickStore store{test::writeSmallBlobs(dir)};
  render::FccBrickSource source{store, std::size_t(64) << 20};
  render::Camera camera = test::smallBlobsCamera();
};

// The test grid's samples for the CPU reference: field(ijk) on [0, test::kDim)^3, the background
// outside, `pad` sites of it around.
LatticeSamples testBoxSamples(Lattice lattice, const std::function<float(const glm::ivec3&)>& field, int pad) {
  LatticeSamples samples(lattice, glm::ivec3(-pad), glm::ivec3(test::kDim + 2 * pad), test::kBackground);
  samples.fill([&](const glm::ivec3& ijk) {
    const bool in = glm::all(glm::greaterThanEqual(ijk, glm::ivec3(0))) && glm::all(glm::lessThan(ijk, glm::ivec3(test::kDim)));
    return in ? field(ijk) : test::kBackground;
  });
  return samples;
}

// viewer/DvrTableGpu's sparse table, read as dvr.glsl's tfExtinctionOn reads it (two overlapping
// power-of-two runs), is TransferTable::maxExtinctionOn and minExtinctionOn: the largest and the
// smallest extinction of the entries that the lookups in [lo, hi] read. No GL needed.
TEST(DvrTableGpu, SparseTableMaximaAreTheTablesRangeMaxima) {
  std::mt19937_64 rng(23);
  for (int size : {2, 3, 7, 64, 256, 300}) {
    // Zero runs and a step (the ramp's cut) at 256 entries, CT's plateaus at the other sizes.
    const TransferTable table = size == 256 ? rampTable(0.2, 0.7, 1.0, 0.85)
                                            : TransferTable(transferFunctionPreset("ct-bone").stretchedTo(0.0, 1.0), 0.0, 1.0,
                                                    size, OpticalScale{0.5, 1.0});
    const std::vector<glm::vec2> levels = render::DvrTableGpu::extinctionLevels(table);
    std::uniform_real_distribution<double> x(-0.1, 1.1);
    for (int r = 0; r < 2000; ++r) {
      double lo = x(rng), hi = x(rng);
      if (r % 3 == 0) hi = lo + 0.01 * (hi - lo);
      if (hi < lo) std::swap(lo, hi);
      int first, last;
      table.entriesOn(lo, hi, first, last);
      first = std::clamp(first, 0, size - 1);
      last = std::clamp(last, 0, size - 1);
      int k = 0;
      while ((2 << k) <= last - first + 1) ++k;  // findMSB
      ASSERT_LT(std::size_t((k + 1) * size), levels.size() + 1) << "size " << size;
      const glm::vec2 a = levels[std::size_t(k * size + first)], b = levels[std::size_t(k * size + last - (1 << k) + 1)];
      ASSERT_EQ(double(std::max(a.x, b.x)), double(float(table.maxExtinctionOn(lo, hi))))
          << "size " << size << " on [" << lo << ", " << hi << "], entries " << first << ".." << last;
      ASSERT_EQ(double(std::min(a.y, b.y)), double(float(table.minExtinctionOn(lo, hi))))
          << "size " << size << " on [" << lo << ", " << hi << "], entries " << first << ".." << last;
    }
  }
}

// viewer/DvrTableGpu's prefix sums, read as dvr.glsl's dvrSteps reads them (two entries' difference
// times the quantum), bound TransferTable::kinkSumOn and colourVariationOn from above by at most one
// quantum an entry, and keep the non-zero count exact. No GL needed.
TEST(DvrTableGpu, QuantizedPrefixSumsBoundTheTablesSums) {
  std::mt19937_64 rng(31);
  for (int size : {2, 3, 64, 256, 300}) {
    const TransferTable table = size == 256 ? rampTable(0.2, 0.7, 1.0, 0.85)
                                            : TransferTable(transferFunctionPreset(size == 64 ? "viridis" : "ct-bone").stretchedTo(0.0, 1.0),
                                                            0.0, 1.0, size, OpticalScale{0.5, 1.0});
    const render::DvrTableGpu::Prefixes p = render::DvrTableGpu::prefixes(table);
    ASSERT_EQ(p.sums.size(), std::size_t(size + 1));
    std::uniform_real_distribution<double> x(-0.1, 1.1);
    for (int r = 0; r < 2000; ++r) {
      double lo = x(rng), hi = x(rng);
      if (hi < lo) std::swap(lo, hi);
      int first, last;
      table.entriesOn(lo, hi, first, last);
      const glm::uvec4 sum = p.sums[std::size_t(last) + 1] - p.sums[std::size_t(first)];
      ASSERT_EQ(table.nonZeroPrefix()[std::size_t(last) + 1] - table.nonZeroPrefix()[std::size_t(first)], int(sum.x));
      // dvrSteps' reads: the kinks strictly inside, the colour over the pairs first..last.
      int kinkFirst, kinkLast;
      table.kinkEntriesOn(lo, hi, kinkFirst, kinkLast);
      const double kinkCount = std::max(kinkLast - kinkFirst + 1, 0), pairCount = double(last - first);
      const double gpuKinks = kinkLast < kinkFirst ? 0.0
          : double(p.sums[std::size_t(kinkLast) + 1].y - p.sums[std::size_t(kinkFirst)].y) * p.kinkQuantum;
      // dvrSteps reads them from entries first and last alone: w holds the next entry's kink sum.
      const bool below = lo < table.vmin(), beyond = hi > table.vmax();
      const int shaderKinks = int(beyond ? p.sums[std::size_t(last)].w : p.sums[std::size_t(last)].y) -
                              int(below ? p.sums[std::size_t(first)].y : p.sums[std::size_t(first)].w);
      ASSERT_EQ(double(std::max(shaderKinks, 0)) * p.kinkQuantum, gpuKinks) << "size " << size << " on [" << lo << ", " << hi << "]";
      const double gpuColour = double(p.sums[std::size_t(last)].z - p.sums[std::size_t(first)].z) * p.colourQuantum;
      const double kinks = table.kinkSumOn(lo, hi), colour = table.colourVariationOn(lo, hi);
      ASSERT_GE(gpuKinks, kinks) << "size " << size << " on [" << lo << ", " << hi << "]";
      ASSERT_LE(gpuKinks, kinks + kinkCount * p.kinkQuantum * (1.0 + 1e-6) + 1e-6 * kinks) << "size " << size;
      ASSERT_GE(gpuColour, colour) << "size " << size << " on [" << lo << ", " << hi << "]";
      ASSERT_LE(gpuColour, colour + pairCount * p.colourQuantum * (1.0 + 1e-6) + 1e-6 * colour) << "size " << size;
    }
  }
}

// A function with zero runs below, inside and above its non-zero entries (each a step, so that the
// table's entries hold exact zeros there).
TransferTable zeroRunsTable(double lo, double hi) {
  const double w = hi - lo;
  const TransferFunction tf({{lo, {0.2, 0.4, 0.9}}, {hi, {1.0, 0.8, 0.2}}},
                            {{lo, 0.0}, {lo + 0.2 * w, 0.0}, {lo + 0.2 * w, 0.5}, {lo + 0.45 * w, 0.5}, {lo + 0.45 * w, 0.0},
                             {lo + 0.55 * w, 0.0}, {lo + 0.55 * w, 0.7}, {lo + 0.8 * w, 0.7}, {lo + 0.8 * w, 0.0}});
  return TransferTable(tf, lo, hi, 256, OpticalScale{1.0, 1.0});
}

// viewer/DvrTableGpu's span of non-zero entries, read as dvr.glsl's tfZeroOn reads it (the span alone,
// the prefix counts only where zeros lie inside it), is TransferTable::zeroOn on random ranges, with
// and without interior zeros. No GL needed.
TEST(DvrTableGpu, NonZeroSpanAnswersAsThePrefixCounts) {
  std::mt19937_64 rng(5);
  const TransferTable tables[] = {rampTable(0.2, 0.7, 1.0), rampTable(0.2, 0.7, 1.0, 0.85), zeroRunsTable(0.0, 1.0),
                                  TransferTable(TransferFunction({{0.0, glm::dvec3(1.0)}}, {{0.0, 0.0}}), 0.0, 1.0, 16,
                                                OpticalScale{1.0, 1.0})};
  for (int k = 0; k < 4; ++k) {
    const TransferTable& table = tables[k];
    const render::DvrTableGpu::NonZeroSpan span = render::DvrTableGpu::nonZeroSpan(table);
    EXPECT_EQ(span.interiorZeros, k == 2) << "table " << k;
    if (k == 3) {
      EXPECT_EQ(span.end, 0) << "an all-zero table has an empty span";
    }
    std::uniform_real_distribution<double> x(-0.2, 1.2);
    int spanAnswers = 0;
    for (int r = 0; r < 4000; ++r) {
      double lo = x(rng), hi = r % 3 == 0 ? lo + 0.01 * x(rng) : x(rng);
      if (hi < lo) std::swap(lo, hi);
      int first, last;
      table.entriesOn(lo, hi, first, last);
      bool zero;
      if (last < span.first || first >= span.end) {
        zero = true;
        ++spanAnswers;
      } else if (!span.interiorZeros) {
        zero = false;
        ++spanAnswers;
      } else {
        zero = table.nonZeroPrefix()[std::size_t(last) + 1] == table.nonZeroPrefix()[std::size_t(first)];
      }
      ASSERT_EQ(zero, table.zeroOn(lo, hi)) << "table " << k << " on [" << lo << ", " << hi << "]";
    }
    if (k != 2) {
      EXPECT_EQ(spanAnswers, 4000) << "without interior zeros the span answers alone";
    }
  }
}

class RenderDvr : public GlSuite {};

// The sphere field f = |x - c|^2 / R^2 (quadratic: the prefiltered box spline reproduces it) with a
// constant extinction sigma where f < iso and none elsewhere: each ray's opacity is 1 - exp(-sigma
// chord) of the exact sphere chord, and its colour (white) the same.
TEST_F(RenderDvr, SphereOpacityIsTheExactChordsExtinction) {
  TempDir dir;
  const std::string path = dir / "sphere.vdb";
  const glm::ivec3 dims(40);
  const SynthField synth = makeSynthField(SynthSpec{"sphere", dims, 1});
  const double scale = 0.25;
  const openvdb::Vec3d origin(1.0, -2.0, 0.5);
  test::writeFccFile(path, *synth.field, scale, origin);
  const double R = 0.5 * (dims.x - 1), iso = 0.3;
  const glm::dvec3 center = glm::dvec3(origin.x(), origin.y(), origin.z()) + scale * glm::dvec3(0.5 * (dims.x - 1));
  const double radius = scale * R * std::sqrt(iso);

  const double alphaInside = 0.1;  // per world unit (the unit distance)
  const TransferFunction tf({{0.0, {1.0, 1.0, 1.0}}}, {{0.0, alphaInside}, {iso, alphaInside}, {iso, 0.0}});
  const TransferTable table(tf, iso - 0.05, iso + 0.05, 256, OpticalScale{1.0, 1.0});
  const double sigma = extinctionFromOpacity(alphaInside, OpticalScale{1.0, 1.0});

  render::Camera camera;
  camera.lookat = center + glm::dvec3(0.3, -0.2, 0.1);
  camera.eye = center + glm::dvec3(9.0, 5.0, 7.0);
  camera.fovYDegrees = 30.0;
  const int w = 80, h = 64;
  const io::BrickStore store(path);
  const render::FccBrickSource source(store, std::size_t(64) << 20);
  const render::FrameImages img = renderSource(source, camera, w, h, dvrOptions(table));
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  int inside = 0;
  double worst = 0.0;
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const glm::dvec3 d = render::pixelRay(frame, px, py, w, h);
      const test::SphereRay ray = test::sphereRay(camera.eye, d, center, radius);
      if (ray.grazes(0.02)) continue;  // grazing: the chord is a matter of rounding
      const double chord = ray.chord;
      const double expected = 1.0 - std::exp(-sigma * chord);
      const std::size_t i = std::size_t(py) * w + px;
      const double alpha = img.rgba[4 * i + 3];
      worst = std::max(worst, std::abs(alpha - expected));
      EXPECT_NEAR(alpha, expected, kChordAlphaTol) << "pixel (" << px << ", " << py << ") chord " << chord;
      EXPECT_NEAR(img.rgba[4 * i], alpha, 1e-5) << "white emission: colour equals opacity";
      inside += chord > 0.0;
    }
  EXPECT_GT(inside, w * h / 10);
  std::printf("sphere chords: %d rays through it, worst opacity error %.3g\n", inside, worst);
}

// Every reconstruction of a Cartesian grid, and the FCC box spline, against the CPU reference with a
// tiny step (0.02 voxels), PSNR of the premultiplied RGBA.
TEST_F(RenderDvr, MatchesTheCpuReferenceOnEveryLattice) {
  TempDir dir;
  const int w = 48, h = 40;
  const float unitDistance = 4.0f;
  const TransferTable table = rampTable(0.0, 1.5, unitDistance, /*cut=*/1.95);
  DvrOptions reference;
  reference.step = 0.01;  // world units: 0.02 voxels at the scale below

  // Cartesian: the wavy field of the isosurface tests.
  const std::string ccPath = dir / "wavy.vdb";
  const double scale = 0.5;
  test::writeCartesianFile(ccPath, test::wavy, scale, openvdb::Vec3d(-3.0, 1.0, 2.0));
  const io::CartesianBrickStore ccStore(ccPath);
  const glm::dmat4 ccIndexFromWorld = glm::inverse(ccStore.worldFromIndex());
  const render::Camera camera = cartesianTestCamera(ccStore.worldFromIndex());
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  for (const char* name : {"trilinear", "tricubic", "type6"}) {
    SCOPED_TRACE(name);
    const ReconstructionInfo& info = findReconstruction(name);
    const render::CartesianBrickSource source(ccStore, info);
    const render::FrameImages gpu = renderSource(source, camera, w, h, dvrOptions(table));
    LatticeSamples samples = testBoxSamples(Lattice::Cc, test::wavy, kBSplinePrefilterReach + 4);
    samples.prefilter(info.prefilter);
    const CellBounds bounds(samples);
    const std::unique_ptr<Reconstruction> recon = makeReconstruction(name);
    const std::vector<DvrPixel> ref = renderDvrImage(
        w, h, [&](int x, int y) { return dvrRayFromWorld(ccIndexFromWorld, camera.eye, render::pixelRay(frame, x, y, w, h), 0.0, 200.0); },
        *recon, samples.accessor(), &bounds, dvrMedium(table), reference);
    const double db = psnr(gpu, ref);
    std::printf("%s: PSNR %.1f dB against the CPU reference\n", name, db);
    EXPECT_GE(db, kMinPsnrDb);
  }

  // BCC: the same field at the BCC sites; the stack schemes take their stack from the view, as the
  // CPU's Reconstruction::setView does from the same direction.
  const std::string bccPath = dir / "wavy_bcc.vdb";
  test::writeBccFile(bccPath, test::wavy, scale, openvdb::Vec3d(-3.0, 1.0, 2.0));
  const LatticeSamples bccSamples = testBoxSamples(Lattice::Bcc, test::wavy, 8);
  const CellBounds bccBounds(bccSamples);
  for (const char* name : {"barycentric", "sheared-trilinear", "bilinear-spatial"}) {
    SCOPED_TRACE(name);
    const render::BccBrickSource source(bccPath, findReconstruction(name));
    const render::FrameImages gpu = renderSource(source, camera, w, h, dvrOptions(table));
    const glm::dmat4 indexFromWorld = glm::inverse(source.worldFromIndex());
    const std::unique_ptr<Reconstruction> recon = makeReconstruction(name);
    recon->setView(glm::vec3(glm::dmat3(indexFromWorld) * frame.forward));
    const std::vector<DvrPixel> ref = renderDvrImage(
        w, h, [&](int x, int y) { return dvrRayFromWorld(indexFromWorld, camera.eye, render::pixelRay(frame, x, y, w, h), 0.0, 200.0); },
        *recon, bccSamples.accessor(), &bccBounds, dvrMedium(table), reference);
    const double db = psnr(gpu, ref);
    std::printf("%s: PSNR %.1f dB against the CPU reference\n", name, db);
    EXPECT_GE(db, kMinPsnrDb);
  }

  // FCC: blobs from `synth`, its coefficients read whole for the CPU.
  const std::string fccPath = dir / "blobs.vdb";
  ASSERT_EQ(test::runFccvdb("synth blobs " + fccPath + " --dims 48,48,48 --quiet").status, 0);
  const io::BrickStore store(fccPath);
  const render::FccBrickSource source(store, std::size_t(64) << 20);
  const glm::dmat4 indexFromWorld = glm::inverse(store.worldFromIndex());
  render::Camera fccCamera;
  fccCamera.lookat = glm::dvec3(store.worldFromIndex() * glm::dvec4(24.0, 24.0, 24.0, 1.0));
  fccCamera.eye = fccCamera.lookat + glm::dvec3(60.0, 44.0, 72.0);
  fccCamera.fovYDegrees = 35.0;
  const render::CameraFrame fccFrame = render::cameraFrame(fccCamera, double(w) / h);
  const TransferTable blobTable = rampTable(0.1, 1.2, 4.0);
  const render::FrameImages gpu = renderSource(source, fccCamera, w, h, dvrOptions(blobTable));
  const FccGrid::Ptr grid = io::readFccGrid(fccPath);
  const SiteValue at = siteValuesOf(*grid);
  const std::unique_ptr<Reconstruction> boxSpline = makeReconstruction("boxspline");
  DvrOptions fccReference;
  fccReference.step = 0.02;  // world units (one index unit each here)
  const std::vector<DvrPixel> ref = renderDvrImage(
      w, h, [&](int x, int y) { return dvrRayFromWorld(indexFromWorld, fccCamera.eye, render::pixelRay(fccFrame, x, y, w, h), 0.0, 300.0); },
      *boxSpline, at, nullptr, dvrMedium(blobTable), fccReference);
  const double db = psnr(gpu, ref);
  std::printf("boxspline: PSNR %.1f dB against the CPU reference\n", db);
  EXPECT_GE(db, kMinPsnrDb);
}

// A Cartesian grid with a ball of NaN samples (a damaged simulation's output): where the field is NaN
// the medium is the transfer function's first entry, as the CPU reference's TransferTable::position
// takes it (on the GPU dvr.glsl's tfPosition takes the max with 0 before the min: GLSL promises nothing
// for NaN, llvmpipe's clamp gave entry 0 and NVIDIA's the last one, and both drivers' max returns the
// number), and
// the image is the reference's (within kNanPsnrDb, tighter than the bound: both integrate the
// same medium, 69 and 75 dB; NaN taken as the table's last entry gives 43 dB); no NaN reaches a
// pixel. Two tables: the first entry transparent (the ball a hole), and opaque enough to show it.
TEST_F(RenderDvr, NanSamplesAreTheTablesFirstEntryAsOnTheCpu) {
  constexpr double kNanPsnrDb = 60.0;
  TempDir dir;
  const int w = 48, h = 40;
  const auto field = [](const glm::ivec3& ijk) {
    const glm::dvec3 fromCentre = glm::dvec3(ijk) - glm::dvec3(24.0, 20.0, 26.0);
    return glm::dot(fromCentre, fromCentre) < 100.0 ? std::numeric_limits<float>::quiet_NaN() : test::wavy(ijk);
  };
  const std::string path = dir / "nan.vdb";
  test::writeCartesianFile(path, field, 0.5, openvdb::Vec3d(-3.0, 1.0, 2.0));
  const io::CartesianBrickStore ccStore(path);
  const glm::dmat4 indexFromWorld = glm::inverse(ccStore.worldFromIndex());
  const render::Camera camera = cartesianTestCamera(ccStore.worldFromIndex());
  const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
  const render::CartesianBrickSource source(ccStore, findReconstruction("trilinear"));
  const LatticeSamples samples = testBoxSamples(Lattice::Cc, field, 4);
  const CellBounds bounds(samples);
  const std::unique_ptr<Reconstruction> recon = makeReconstruction("trilinear");
  DvrOptions reference;
  reference.step = 0.01;
  // The background (2) transparent in both: bricks of it are not integrated (docs/DVR.md).
  const TransferTable hole = rampTable(0.0, 1.5, 4.0, /*cut=*/1.95);
  const TransferTable firstOpaque(TransferFunction({{-2.0, {0.1, 0.2, 0.9}}, {1.5, {1.0, 1.0, 0.8}}},
                                                   {{-2.0, 0.3}, {1.5, 0.6}, {1.95, 0.6}, {1.95, 0.0}}),
                                  -2.0, 2.0, 256, OpticalScale{4.0, 1.0});
  for (const TransferTable* table : {&hole, &firstOpaque}) {
    const render::FrameImages gpu = renderSource(source, camera, w, h, dvrOptions(*table));
    for (std::size_t i = 0; i < gpu.rgba.size(); ++i) ASSERT_TRUE(std::isfinite(gpu.rgba[i])) << "component " << i;
    const std::vector<DvrPixel> ref = renderDvrImage(
        w, h, [&](int x, int y) { return dvrRayFromWorld(indexFromWorld, camera.eye, render::pixelRay(frame, x, y, w, h), 0.0, 200.0); },
        *recon, samples.accessor(), &bounds, dvrMedium(*table), reference);
    const double db = psnr(gpu, ref);
    std::printf("trilinear with a ball of NaN, first entry %s: PSNR %.1f dB against the CPU reference\n",
                table == &hole ? "transparent" : "opaque", db);
    EXPECT_GE(db, kNanPsnrDb);
  }
}

// FCC: a unit cell's chord from its two end pieces, sub-stepped as one segment (the default; docs/DVR.md
// "A cell's chord from its end pieces"), against every piece gathered and sub-stepped by itself
// (RenderOptions::dvrGatherCentral). With a tight sub-step tolerance (FCC_DVR_TOLERANCE 1e-4, so that
// where the sub-steps lie matters little) the images differ (the chord is taken), by far less than
// either's error (PSNR between them at least 30 dB above the bound, every component within
// 1e-3); with the default rule both agree with the CPU reference within the bound.
// Marschner-Lobb 64^3 and blobs. (The central piece's exactness: Ray.CentralPieceFromItsNeighbours...)
TEST_F(RenderDvr, CellChordFromItsEndPiecesAgreesWithEveryPieceAndTheReference) {
  TempDir dir;
  const int w = 48, h = 40;
  for (const char* field : {"marschner-lobb", "blobs"}) {
    SCOPED_TRACE(field);
    const std::string path = dir / (std::string(field) + ".vdb");
    ASSERT_EQ(test::runFccvdb(std::string("synth ") + field + " " + path + " --dims 64,64,64 --quiet").status, 0);
    const io::BrickStore store(path);
    const render::FccBrickSource source(store, std::size_t(64) << 20);
    const glm::dmat4 indexFromWorld = glm::inverse(store.worldFromIndex());
    render::Camera camera;
    camera.lookat = glm::dvec3(store.worldFromIndex() * glm::dvec4(32.0, 32.0, 32.0, 1.0));
    camera.eye = glm::dvec3(store.worldFromIndex() * glm::dvec4(32.0 + 80.0, 32.0 + 58.0, 32.0 + 96.0, 1.0));
    camera.fovYDegrees = 35.0;
    const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
    const double worldPerIndex = std::cbrt(std::abs(glm::determinant(glm::dmat3(store.worldFromIndex()))));
    const TransferTable table = rampTable(0.05, 1.0, 4.0 * worldPerIndex);
    render::RenderOptions shortcut = dvrOptions(table), gathered = dvrOptions(table);
    gathered.dvrGatherCentral = true;
    const render::FrameImages withShortcut = renderSource(source, camera, w, h, shortcut);
    const render::FrameImages withGathered = renderSource(source, camera, w, h, gathered);
    render::FrameImages tightShortcut, tightGathered;
    {
      const test::ScopedEnv tight("FCCVDB_SHADER_DEFINES", "FCC_DVR_TOLERANCE=0.0001");
      tightShortcut = renderSource(source, camera, w, h, shortcut);
      tightGathered = renderSource(source, camera, w, h, gathered);
    }
    constexpr double kComponentTol = 1e-3;
    const ImageDifference between = differenceOf(tightShortcut, tightGathered);
    std::printf("%s: %d of %zu components differ, by at most %.2e (PSNR %.1f dB), between the chord and every "
                "piece (tolerance 1e-4)\n", field, between.differing, tightShortcut.rgba.size(), between.worst, between.psnrDb);
    EXPECT_GT(between.differing, 0) << "the chord was never taken";
    EXPECT_LE(between.worst, kComponentTol);
    EXPECT_GE(between.psnrDb, kMinPsnrDb + 30.0);

    const FccGrid::Ptr grid = io::readFccGrid(path);
    const SiteValue at = siteValuesOf(*grid);
    const std::unique_ptr<Reconstruction> boxSpline = makeReconstruction("boxspline");
    DvrOptions reference;
    reference.step = 0.02 * worldPerIndex;
    const double far = 3.0 * glm::distance(camera.eye, camera.lookat);  // past the data
    const std::vector<DvrPixel> ref = renderDvrImage(
        w, h, [&](int x, int y) { return dvrRayFromWorld(indexFromWorld, camera.eye, render::pixelRay(frame, x, y, w, h), 0.0, far); },
        *boxSpline, at, nullptr, dvrMedium(table), reference);
    const double dbShortcut = psnr(withShortcut, ref), dbGathered = psnr(withGathered, ref);
    std::printf("%s: PSNR against the CPU reference %.1f dB (the chord), %.1f dB (every piece)\n", field,
                dbShortcut, dbGathered);
    EXPECT_GE(dbShortcut, kMinPsnrDb);
    EXPECT_GE(dbGathered, kMinPsnrDb);
  }
}

// Fragment shader invocations while `draw` runs, where the GL counts them
// (GL_ARB_pipeline_statistics_query); 0 where it does not.
template <class Draw>
uint64_t fragmentInvocations(Draw draw) {
  if (!epoxy_has_gl_extension("GL_ARB_pipeline_statistics_query")) {
    draw();
    return 0;
  }
  GLuint query = 0;
  glGenQueries(1, &query);
  glBeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, query);
  draw();
  glEndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
  GLuint64 count = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &count);
  glDeleteQueries(1, &query);
  return count;
}

// Paper 002's projected tetrahedra (viewer/ProjectedTetrahedra.h) on a BCC dataset: the same image as
// the raycaster's integration of the same barycentric field and as the CPU reference, from two views
// (the back-to-front order is sorted anew for each); the faces' culling changes no pixel; with shading
// too; refused on other data.
TEST_F(RenderDvr, ProjectedTetrahedraMatchTheRaycasterAndTheCpuReference) {
  TempDir dir;
  const int w = 48, h = 40;
  const double scale = 0.5;
  const TransferTable table = rampTable(0.0, 1.5, 4.0, /*cut=*/1.95);
  const std::string path = dir / "wavy_bcc.vdb";
  test::writeBccFile(path, test::wavy, scale, openvdb::Vec3d(-3.0, 1.0, 2.0));
  const render::BccBrickSource source(path, findReconstruction("barycentric"));
  const glm::dmat4 indexFromWorld = glm::inverse(source.worldFromIndex());
  LatticeSamples samples(Lattice::Bcc, glm::ivec3(-8), glm::ivec3(test::kDim + 16), test::kBackground);
  samples.fill([](const glm::ivec3& x) {
    const bool in = glm::all(glm::greaterThanEqual(x, glm::ivec3(0))) && glm::all(glm::lessThan(x, glm::ivec3(test::kDim)));
    return in ? test::wavy(x) : test::kBackground;
  });
  const CellBounds bounds(samples);
  const std::unique_ptr<Reconstruction> recon = makeReconstruction("barycentric");
  DvrOptions reference;
  reference.step = 0.01;  // world units
  render::ProjectedTetrahedra::Options ptOptions;
  ptOptions.transfer = std::make_shared<const TransferTable>(table);
  render::ProjectedTetrahedra pt(source, ptOptions);
  std::printf("%zu tetrahedra with data\n", pt.tetrahedronCount());
  EXPECT_GT(pt.tetrahedronCount(), 1000u);
  // The reference for tetra.vert's culling: every face rasterized, tetra.frag's test alone deciding.
  render::ProjectedTetrahedra::Options allFacesOptions = ptOptions;
  allFacesOptions.cullFaces = false;
  render::ProjectedTetrahedra allFaces(source, allFacesOptions);
  const glm::dvec3 lookat(source.worldFromIndex() * glm::dvec4(24.0, 24.0, 24.0, 1.0));
  // Two views from outside, and one from inside the data (the eye inside a tetrahedron: its segment
  // from the eye to where the ray leaves it).
  for (const glm::dvec3 offset : {glm::dvec3(30.0, 22.0, 36.0), glm::dvec3(-14.0, -44.0, 20.0), glm::dvec3(0.31, 0.17, 0.23)}) {
    render::Camera camera;
    camera.lookat = lookat + (glm::length(offset) < 1.0 ? glm::dvec3(6.0, -2.0, 3.0) : glm::dvec3(0.0));
    camera.eye = lookat + offset;
    camera.fovYDegrees = 35.0;
    const render::CameraFrame frame = render::cameraFrame(camera, double(w) / h);
    const uint64_t culledInvocations = fragmentInvocations([&] { pt.render(camera, w, h); });
    const render::FrameImages tetra = pt.readImages();
    const uint64_t allInvocations = fragmentInvocations([&] { allFaces.render(camera, w, h); });
    const render::FrameImages unculled = allFaces.readImages();
    // Culling drops only faces whose every fragment tetra.frag discards: the same image bit for bit,
    // with fewer fragments shaded (about half the faces face away) where the GL counts them.
    ASSERT_EQ(tetra.rgba.size(), unculled.rgba.size());
    std::size_t changed = 0;
    for (std::size_t i = 0; i < tetra.rgba.size(); ++i) changed += tetra.rgba[i] != unculled.rgba[i] ? 1 : 0;
    EXPECT_EQ(changed, 0u) << "components culling changed, of " << tetra.rgba.size() << " (eye offset " << offset.x << ", "
                           << offset.y << ", " << offset.z << ")";
    std::printf("fragment shader invocations: %llu culled, %llu every face\n", (unsigned long long)culledInvocations,
                (unsigned long long)allInvocations);
    if (allInvocations > 0) {  // 0.50 of them from every view on llvmpipe
      EXPECT_LT(culledInvocations, allInvocations * 3 / 4) << "culling dropped too little";
    }
    const render::FrameImages ray = renderSource(source, camera, w, h, dvrOptions(table));
    const std::vector<DvrPixel> ref = renderDvrImage(
        w, h, [&](int x, int y) { return dvrRayFromWorld(indexFromWorld, camera.eye, render::pixelRay(frame, x, y, w, h), 0.0, 200.0); },
        *recon, samples.accessor(), &bounds, dvrMedium(table), reference);
    const double dbRef = psnr(tetra, ref), dbRay = psnr(ray, ref);
    // The tetrahedra against the raycaster directly: their sub-steps differ (the raycaster's segments
    // are also cut at unit cells), the field and the compositing do not.
    const double dbBoth = psnr(tetra, pixelsOf(ray));
    double opaque = 0.0;
    for (std::size_t i = 3; i < tetra.rgba.size(); i += 4) opaque = std::max(opaque, double(tetra.rgba[i]));
    std::printf("projected tetrahedra: %.1f dB against the CPU reference (the raycaster %.1f dB), %.1f dB against "
                "the raycaster; largest opacity %.3f\n", dbRef, dbRay, dbBoth, opaque);
    EXPECT_GE(dbRef, kMinPsnrDb);
    EXPECT_GE(dbBoth, kMinPsnrDb);
    EXPECT_GT(opaque, 0.5) << "the volume must be seen";
  }
  // Shading: the tetrahedron's gradient, against the raycaster's shaded integration.
  render::ProjectedTetrahedra::Options shadedOptions = ptOptions;
  shadedOptions.shading.on = true;
  render::ProjectedTetrahedra shaded(source, shadedOptions);
  render::Camera camera;
  camera.lookat = lookat;
  camera.eye = lookat + glm::dvec3(30.0, 22.0, 36.0);
  camera.fovYDegrees = 35.0;
  shaded.render(camera, w, h);
  render::RenderOptions shadedRay = dvrOptions(table);
  shadedRay.dvrShading.on = true;
  const render::FrameImages ray = renderSource(source, camera, w, h, shadedRay), tetra = shaded.readImages();
  EXPECT_GE(psnr(tetra, pixelsOf(ray)), kMinPsnrDb) << "shaded";
  // Under a directional light with a highlight (--light, --specular), as the raycaster lights it.
  shadedOptions.shading.light = render::DvrLight::Directional;
  shadedOptions.lightInCamera = render::lightInCameraFromAngles(-50.0f, 40.0f);
  shadedOptions.shading.specular = 0.5f;
  render::ProjectedTetrahedra lit(source, shadedOptions);
  lit.render(camera, w, h);
  render::RenderOptions litRay = shadedRay;
  litRay.dvrShading = shadedOptions.shading;
  litRay.lightInCamera = shadedOptions.lightInCamera;
  const render::FrameImages litRayImage = renderSource(source, camera, w, h, litRay), litTetra = lit.readImages();
  EXPECT_GE(psnr(litTetra, pixelsOf(litRayImage)), kMinPsnrDb) << "under a directional light";
  EXPECT_NE(litTetra.rgba, tetra.rgba) << "the light must show";
  // And under the light kit.
  shadedOptions.shading.light = render::DvrLight::Kit;
  render::ProjectedTetrahedra kitLit(source, shadedOptions);
  kitLit.render(camera, w, h);
  litRay.dvrShading.light = render::DvrLight::Kit;
  const render::FrameImages kitRayImage = renderSource(source, camera, w, h, litRay), kitTetra = kitLit.readImages();
  EXPECT_GE(psnr(kitTetra, pixelsOf(kitRayImage)), kMinPsnrDb) << "under the light kit";
  EXPECT_NE(kitTetra.rgba, litTetra.rgba) << "the kit must show";
  // Other data, or another reconstruction: one line saying what it draws.
  const render::BccBrickSource sheared(path, findReconstruction("sheared-trilinear"));
  EXPECT_THROW(render::ProjectedTetrahedra(sheared, ptOptions), ValueError);
  // GL state is the caller's again after a frame (the viewer draws with it next).
  glEnable(GL_DEPTH_TEST);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE);
  pt.render(camera, w, h);
  EXPECT_TRUE(glIsEnabled(GL_DEPTH_TEST));
  EXPECT_FALSE(glIsEnabled(GL_BLEND));
  GLint src = 0, dst = 0;
  glGetIntegerv(GL_BLEND_SRC_RGB, &src);
  glGetIntegerv(GL_BLEND_DST_RGB, &dst);
  EXPECT_EQ(src, GL_SRC_ALPHA);
  EXPECT_EQ(dst, GL_ONE);
  glDisable(GL_DEPTH_TEST);
}

// The faces' culling far from the index origin (tetra.vert's margin grows with the eye's and the
// tetrahedron's index coordinates, whose rounding grows with them): the wavy BCC volume moved to sites
// kFarShift on, with the same world positions and values, draws the same image with and without the
// culling, bit for bit, and the near volume's image within kFarPsnrDb (the index coordinates' rounding,
// about 1e-3 of a unit there, moves the field's linear pieces a little).
TEST_F(RenderDvr, ProjectedTetrahedraCullingHoldsFarFromTheIndexOrigin) {
  const glm::ivec3 kFarShift(20000, -12000, 16000);  // even: the BCC lattice's own translations
  constexpr double kFarPsnrDb = 35.0;
  ASSERT_EQ(kFarShift % 2, glm::ivec3(0));
  TempDir dir;
  const int w = 48, h = 40;
  const double scale = 0.5;
  const openvdb::Vec3d origin(-3.0, 1.0, 2.0);
  render::ProjectedTetrahedra::Options options;
  options.transfer = std::make_shared<const TransferTable>(rampTable(0.0, 1.5, 4.0, /*cut=*/1.95));
  render::ProjectedTetrahedra::Options allFacesOptions = options;
  allFacesOptions.cullFaces = false;
  const std::string nearPath = dir / "near_bcc.vdb", farPath = dir / "far_bcc.vdb";
  test::writeBccFile(nearPath, test::wavy, scale, origin);
  test::writeBccFile(farPath, test::wavy, scale, origin, test::kBackground, kFarShift);
  const render::BccBrickSource nearSource(nearPath, findReconstruction("barycentric"));
  const render::BccBrickSource farSource(farPath, findReconstruction("barycentric"));
  const glm::dvec3 farCorner(farSource.worldFromIndex() * glm::dvec4(glm::dvec3(kFarShift), 1.0));
  ASSERT_LT(glm::distance(farCorner, glm::dvec3(origin[0], origin[1], origin[2])), 1e-6) << "the same world place";
  render::ProjectedTetrahedra nearPt(nearSource, options), farPt(farSource, options), farAllFaces(farSource, allFacesOptions);
  ASSERT_EQ(farPt.tetrahedronCount(), nearPt.tetrahedronCount());
  const glm::dvec3 lookat(nearSource.worldFromIndex() * glm::dvec4(24.0, 24.0, 24.0, 1.0));
  // World offsets of the eye from the volume's centre; the last two put it a thousandth of an index
  // unit (about the rounding of index coordinates there) off the lattice planes through the
  // site kFarShift + (84, 68, 96), which hold faces of the tetrahedra: faces seen edge-on, where the
  // host's eye and tetra.frag's round apart. (On llvmpipe this test passes without the margin too:
  // a face the margin guards is edge-on and covers no pixel's centre; it guards the rest.)
  for (const glm::dvec3 offset : {glm::dvec3(30.0, 22.0, 36.0), glm::dvec3(-14.0, -44.0, 20.0), glm::dvec3(0.0, 3.0, -40.0),
                                  scale * glm::dvec3(60.001, 44.0, 72.0), scale * glm::dvec3(60.0, 43.999, 72.0)}) {
    render::Camera camera;
    camera.lookat = lookat;
    camera.eye = lookat + offset;
    camera.fovYDegrees = 35.0;
    nearPt.render(camera, w, h);
    const render::FrameImages nearImage = nearPt.readImages();
    farPt.render(camera, w, h);
    const render::FrameImages culled = farPt.readImages();
    farAllFaces.render(camera, w, h);
    const render::FrameImages unculled = farAllFaces.readImages();
    ASSERT_EQ(culled.rgba.size(), unculled.rgba.size());
    std::size_t changed = 0;
    for (std::size_t i = 0; i < culled.rgba.size(); ++i) changed += culled.rgba[i] != unculled.rgba[i] ? 1 : 0;
    EXPECT_EQ(changed, 0u) << "components culling changed far from the origin, of " << culled.rgba.size()
                           << " (eye offset " << offset.x << ", " << offset.y << ", " << offset.z << ")";
    double opaque = 0.0;
    for (std::size_t i = 3; i < culled.rgba.size(); i += 4) opaque = std::max(opaque, double(culled.rgba[i]));
    const double db = psnr(culled, pixelsOf(nearImage));
    std::printf("far from the index origin: %.1f dB against the near volume's image, largest opacity %.3f\n", db, opaque);
    EXPECT_GE(db, kFarPsnrDb) << "eye offset " << offset.x << ", " << offset.y << ", " << offset.z;
    EXPECT_GT(opaque, 0.5) << "the volume must be seen";
  }
}

// A pool of a few slots changes no pixel, bit for bit. Skipping (bricks, nodes, cells, segments the
// transfer function maps to zero) changes none beyond kSkipTolerance: it integrates the same cells,
// but a cell passed over ends the chain of pieces (march_fcc.glsl), so the next cell's entry piece is
// gathered rather than carried across the face, the same cubic rounded another way (bit for bit on
// llvmpipe; NVIDIA's 580 driver differs in the last bits, docs/BENCHMARKS.md, session 23).
constexpr float kSkipTolerance = 1e-5f;

TEST_F(RenderDvr, SkippingAndSmallCachesChangeNothing) {
  const SmallBlobs blobs;
  const int w = 48, h = 48;
  const TransferTable table = rampTable(0.2, 1.0, 2.0);
  render::RenderOptions options = dvrOptions(table);
  render::FrameStats bigStats, smallStats;
  const render::FrameImages reference = renderSource(render::FccBrickSource(blobs.store, std::size_t(64) << 20), blobs.camera, w, h, options, &bigStats);
  render::RenderOptions noSkip = options;
  noSkip.skipEmpty = false;
  render::RenderOptions small = options;
  small.gpuCacheBytes = small.hostCacheBytes = test::kSmallPoolBytes;
  const render::FrameImages unskipped = renderSource(render::FccBrickSource(blobs.store, std::size_t(64) << 20), blobs.camera, w, h, noSkip);
  const render::FrameImages limited = renderSource(render::FccBrickSource(blobs.store, test::kSmallPoolBytes), blobs.camera, w, h, small, &smallStats);
  std::printf("unbounded: %d passes, %llu uploads; 1 MiB: %d passes, %llu uploads\n", bigStats.passes,
              (unsigned long long)bigStats.bricksUploaded, smallStats.passes, (unsigned long long)smallStats.bricksUploaded);
  EXPECT_GT(smallStats.bricksUploaded, bigStats.bricksUploaded) << "the small pool must have evicted bricks";
  int visible = 0;
  float skipDifference = 0.0f;
  for (std::size_t i = 0; i < reference.rgba.size(); ++i) {
    skipDifference = std::max(skipDifference, std::abs(reference.rgba[i] - unskipped.rgba[i]));
    ASSERT_LE(std::abs(reference.rgba[i] - unskipped.rgba[i]), kSkipTolerance)
        << "skipping changed component " << i << ": " << reference.rgba[i] << " against " << unskipped.rgba[i];
    ASSERT_EQ(reference.rgba[i], limited.rgba[i]) << "the small pool changed component " << i;
    ASSERT_EQ(reference.normalDepth[i], limited.normalDepth[i]) << "the small pool changed depth component " << i;
    visible += i % 4 == 3 && reference.rgba[i] > 0.05f;
  }
  EXPECT_GT(visible, w * h / 10);
  std::printf("skipping changed a component by at most %g\n", double(skipDifference));
}

// tfZeroOn's span of non-zero entries (no memory read where the table has no zero run inside it) gives
// the image of the prefix counts alone (FCC_TF_ZERO_SPAN=0), bit for bit, with zero runs at the ends
// and inside.
TEST_F(RenderDvr, ZeroSpanSkipsAsThePrefixCounts) {
  const SmallBlobs blobs;
  const int w = 48, h = 48;
  for (const TransferTable& table : {rampTable(0.2, 1.0, 2.0, 1.1), zeroRunsTable(0.0, 1.2)}) {
    const render::FrameImages span = renderSource(blobs.source, blobs.camera, w, h, dvrOptions(table));
    render::FrameImages counts;
    {
      const test::ScopedEnv env("FCCVDB_SHADER_DEFINES", "FCC_TF_ZERO_SPAN=0");
      counts = renderSource(blobs.source, blobs.camera, w, h, dvrOptions(table));
    }
    EXPECT_EQ(span.rgba, counts.rgba);
    EXPECT_EQ(span.normalDepth, counts.normalDepth);
    int visible = 0;
    for (std::size_t i = 3; i < span.rgba.size(); i += 4) visible += span.rgba[i] > 0.02f;
    EXPECT_GT(visible, w * h / 20);
  }
}

// The DVR walk's schedules (docs/DVR.md, "The walk in rounds": a round finds a cell, then integrates
// it; bricks and rounds in one loop) change when a ray does its work, not what it computes: the images
// of every schedule are the same bit for bit, with a pool that holds every brick and with one that
// must evict (several passes, rays resuming). Walking bricks one by one takes two gathers a cell (the
// chain of pieces is the flat walk's: march_fcc.glsl), so it is compared with the flat walk's two
// gathers.
TEST_F(RenderDvr, WalkSchedulesGiveTheSameImage) {
  const SmallBlobs blobs;
  const int w = 48, h = 48;
  const render::RenderOptions options = dvrOptions(rampTable(0.2, 1.0, 2.0));
  render::RenderOptions small = options;
  small.gpuCacheBytes = small.hostCacheBytes = test::kSmallPoolBytes;
  const render::RenderOptions* const pools[] = {&options, &small};
  render::FrameStats stats[2];
  for (const render::RenderOptions* o : pools) {
    const std::size_t hostBytes = o == &small ? test::kSmallPoolBytes : std::size_t(64) << 20;
    const render::FrameImages main = renderSource(render::FccBrickSource(blobs.store, hostBytes), blobs.camera, w, h, *o, &stats[o == &small]);
    int visible = 0;
    for (std::size_t i = 3; i < main.rgba.size(); i += 4) visible += main.rgba[i] > 0.05f;
    EXPECT_GT(visible, w * h / 10);
    render::FrameImages twoGathers;
    {
      const test::ScopedEnv defines("FCCVDB_SHADER_DEFINES", "FCC_DVR_CHAIN=0");
      twoGathers = renderSource(render::FccBrickSource(blobs.store, hostBytes), blobs.camera, w, h, *o);
    }
    // Each schedule against the flat walk with the same integration.
    const std::pair<const char*, const render::FrameImages*> schedules[] = {
        {"FCC_DVR_FIND_THEN_INTEGRATE=0", &main},
        {"FCC_DVR_BRICKS_FIRST=1", &main},
        {"FCC_DVR_FIND_THEN_INTEGRATE=0;FCC_DVR_CHAIN=0", &twoGathers},
        {"FCC_DVR_FLAT_WALK=0", &twoGathers}};
    for (const auto& [schedule, expected] : schedules) {
      const test::ScopedEnv defines("FCCVDB_SHADER_DEFINES", schedule);
      const render::FrameImages other = renderSource(render::FccBrickSource(blobs.store, hostBytes), blobs.camera, w, h, *o);
      ASSERT_EQ(expected->rgba, other.rgba) << schedule << (o == &small ? ", small pool" : "");
      ASSERT_EQ(expected->normalDepth, other.normalDepth) << schedule << (o == &small ? ", small pool" : "");
    }
    EXPECT_NE(main.rgba, twoGathers.rgba) << "the flat walk's chain was never taken";
  }
  EXPECT_GT(stats[1].bricksUploaded, stats[0].bricksUploaded) << "the small pool must have evicted bricks";
}

// The sub-step rule (shaders/dvr.glsl's dvrSteps) counted through the FCC_DVR_COUNT knob (colour =
// cells visited, cells integrated, sub-steps): a constant medium (one colour, one extinction: no kink,
// no colour change, nothing for the value's curving to change) takes one sub-step a chord, as the
// midpoint rule is exact for it, whatever the data; a step in the opacity takes more where chords
// cross it.
TEST_F(RenderDvr, SubStepsFollowTheTransferFunctionsKinks) {
  const SmallBlobs blobs;
  const int w = 48, h = 48;
  // The table spans more than the field's range, BB-coefficients included (the prefiltered blobs dip
  // below 0): past its ends a lookup is constant, a kink the rule rightly counts.
  const double vmin = -1.0, vmax = 3.0, unit = 2.0;
  const glm::dvec3 colour(0.8, 0.6, 0.3);
  const TransferFunction constant({{vmin, colour}}, {{vmin, 0.1}, {vmax, 0.1}});
  const TransferFunction stepped({{vmin, colour}}, {{vmin, 0.05}, {0.5, 0.05}, {0.5, 0.6}, {vmax, 0.6}});
  const test::ScopedEnv count("FCCVDB_SHADER_DEFINES", "FCC_DVR_COUNT=1");
  double steps[2] = {0.0, 0.0}, cells[2] = {0.0, 0.0};
  for (int f = 0; f < 2; ++f) {
    const TransferTable table(f == 0 ? constant : stepped, vmin, vmax, 256, OpticalScale{unit, 1.0});
    ASSERT_EQ(f == 0, table.kinkSumOn(vmin + 0.05, vmax - 0.05) < 1e-5) << "the table's kinks";
    const render::FrameImages img = renderSource(blobs.source, blobs.camera, w, h, dvrOptions(table));
    for (int i = 0; i < w * h; ++i) {
      const float integrated = img.rgba[4 * i + 1], subSteps = img.rgba[4 * i + 2];
      if (f == 0) {
        ASSERT_EQ(subSteps, integrated) << "pixel " << i << ": a constant medium, one sub-step a chord";
      }
      cells[f] += integrated;
      steps[f] += subSteps;
    }
  }
  std::printf("sub-steps per integrated cell: %.3f (constant medium), %.3f (a step)\n", steps[0] / cells[0], steps[1] / cells[1]);
  EXPECT_GT(cells[0], 1000.0);
  EXPECT_GT(steps[1], 1.02 * cells[1]) << "the step must cost sub-steps where chords cross it";
}

// A sub-step takes the medium at the field's mean over it (dvr.glsl; docs/DVR.md, "The value a sub-step
// takes"): where the table's extinction is linear in the value and the colour constant, that gives
// each chord's optical depth exactly however the box spline curves along it, so the rule asks one
// sub-step a chord and the image is a tight reference's (64 midpoint sub-steps a chord) within float
// rounding. One midpoint sub-step a chord (the value there is not the mean) is measurably worse on a
// field that curves within a cell (Marschner-Lobb on 32^3 points; on the smooth blobs the two differ
// by 5e-7). Rays do not stop early (a ray that stops after a whole chord or after a 64th of one
// differs by that).
TEST_F(RenderDvr, LinearMediumTakesOneMeanSubStepAChordAndIsExact) {
  TempDir dir;
  const std::string path = dir / "ml.vdb";
  ASSERT_EQ(test::runFccvdb("synth marschner-lobb " + path + " --dims 32,32,32 --quiet").status, 0);
  const io::BrickStore store(path);
  const render::FccBrickSource source(store, std::size_t(64) << 20);
  render::Camera camera;
  camera.lookat = glm::dvec3(store.worldFromIndex() * glm::dvec4(16.0, 16.0, 16.0, 1.0));
  camera.eye = glm::dvec3(store.worldFromIndex() * glm::dvec4(16.0 + 40.0, 16.0 + 30.0, 16.0 + 48.0, 1.0));
  camera.fovYDegrees = 30.0;
  const int w = 48, h = 48;
  // Extinction k (v - vmin) per world unit at every entry (opacity 1 - exp(-k (v - vmin) unit) for a
  // unit distance `unit`): linear over [vmin, vmax], which holds the field and its BB-coefficients.
  const double vmin = -1.0, vmax = 3.0, unit = 2.0, k = 0.25;
  constexpr int kEntries = 256;
  std::vector<OpacityPoint> opacity;
  for (int i = 0; i < kEntries; ++i) {
    const double v = i == kEntries - 1 ? vmax : vmin + (vmax - vmin) * double(i) / double(kEntries - 1);
    opacity.push_back({v, 1.0 - std::exp(-k * (v - vmin) * unit)});
  }
  const TransferTable table(TransferFunction({{vmin, {0.8, 0.6, 0.3}}}, opacity), vmin, vmax, kEntries,
                            OpticalScale{unit, 1.0});
  const double slopePerEntry = k * (vmax - vmin) / (kEntries - 1);  // extinction per world unit
  ASSERT_LT(table.kinkSumOn(vmin + 0.05, vmax - 0.05), 0.01 * slopePerEntry)
      << "the table's extinction must be linear inside its range (float rounding aside)";

  render::RenderOptions options = dvrOptions(table);
  options.terminationOpacity = 1.0f;
  auto imageWith = [&](const char* defines) {
    const test::ScopedEnv env("FCCVDB_SHADER_DEFINES", defines);
    return renderSource(source, camera, w, h, options);
  };
  const render::FrameImages count = imageWith("FCC_DVR_COUNT=1");
  double cells = 0.0, steps = 0.0;
  for (int i = 0; i < w * h; ++i) {
    cells += count.rgba[4 * i + 1];
    steps += count.rgba[4 * i + 2];
    ASSERT_LE(count.rgba[4 * i + 2], count.rgba[4 * i + 1]) << "pixel " << i << ": a linear medium, one sub-step a chord";
  }
  std::printf("%.0f cells integrated, %.0f sub-steps\n", cells, steps);
  EXPECT_GT(cells, 1000.0);
  const render::FrameImages reference = imageWith("FCC_DVR_MIDPOINT=1;FCC_DVR_FIXED_STEPS=64");
  const render::FrameImages meanImage = imageWith(""), midpointImage = imageWith("FCC_DVR_MIDPOINT=1;FCC_DVR_FIXED_STEPS=1");
  const ImageDifference mean = differenceOf(meanImage, reference);
  const ImageDifference midpoint = differenceOf(midpointImage, reference);
  std::printf("against 64 midpoint sub-steps a chord: one mean sub-step %.2e (PSNR %.1f dB), one midpoint sub-step "
              "%.2e (%.1f dB)\n", mean.worst, mean.psnrDb, midpoint.worst, midpoint.psnrDb);
  // Float rounding over a ray's ~130 chords, the reference's 64 sub-steps each (measured 1.9e-5; one
  // midpoint sub-step a chord 1.8e-4).
  constexpr double kFloatTol = 3e-5;
  EXPECT_LE(mean.worst, kFloatTol);
  EXPECT_GT(midpoint.worst, 4.0 * kFloatTol) << "the field must curve enough for the midpoint to miss";
}

// The chain of pieces (the default) against two gathers a cell (FCC_DVR_CHAIN=0), both with a tight
// sub-step tolerance (FCC_DVR_TOLERANCE 1e-4, so that where the sub-steps lie matters little): the
// images differ (the chain is taken), every component by at most 1e-4 (float rounding). Returns the
// chain's image.
render::FrameImages expectChainIsTwoGathers(const render::BrickSource& source, const render::Camera& camera, int w, int h,
                                            const render::RenderOptions& options, const char* what) {
  constexpr double kComponentTol = 1e-4;
  render::FrameImages chain, twoGathers;
  {
    const test::ScopedEnv tight("FCCVDB_SHADER_DEFINES", "FCC_DVR_TOLERANCE=0.0001");
    chain = renderSource(source, camera, w, h, options);
  }
  {
    const test::ScopedEnv tight("FCCVDB_SHADER_DEFINES", "FCC_DVR_TOLERANCE=0.0001;FCC_DVR_CHAIN=0");
    twoGathers = renderSource(source, camera, w, h, options);
  }
  const ImageDifference between = differenceOf(chain, twoGathers);
  std::printf("%s, chain against two gathers: %d of %zu components differ, by at most %.2e\n", what, between.differing,
              chain.rgba.size(), between.worst);
  EXPECT_GT(between.differing, 0) << what << ": the chain was never taken";
  EXPECT_LE(between.worst, kComponentTol) << what;
  return chain;
}

// The FCC chain of pieces (march_fcc.glsl's integrateCell, docs/DVR.md "One gather a cell"): most
// integrated cells gather only their exit piece (counted: FCC_DVR_COUNT=2's rounds that only gathered
// an entry piece are few), and the image is session 18's two gathers a cell (FCC_DVR_CHAIN=0) up to
// float rounding, sub-steps held fixed by a tight tolerance in both.
TEST_F(RenderDvr, ChainOfPiecesGathersOneACellAndGivesTheTwoGathersImage) {
  const SmallBlobs blobs;
  const int w = 48, h = 48;
  const TransferTable table = rampTable(0.05, 1.0, 2.0);
  double rounds = 0.0, cells = 0.0, entryOnly = 0.0;
  {
    const test::ScopedEnv count("FCCVDB_SHADER_DEFINES", "FCC_DVR_COUNT=2");
    const render::FrameImages img = renderSource(blobs.source, blobs.camera, w, h, dvrOptions(table));
    for (int i = 0; i < w * h; ++i) {
      rounds += img.rgba[4 * i];
      cells += img.rgba[4 * i + 1];
      entryOnly += img.rgba[4 * i + 2];
    }
  }
  std::printf("chain: %.0f cells integrated in %.0f rounds, %.0f of them gathering an entry piece alone\n", cells,
              rounds, entryOnly);
  EXPECT_GT(cells, 1000.0);
  EXPECT_EQ(rounds, cells + entryOnly);
  EXPECT_GT(entryOnly, 0.0) << "a brick's first cells start a chain";
  EXPECT_LT(entryOnly, 0.25 * cells) << "the chain is seldom broken";

  expectChainIsTwoGathers(blobs.source, blobs.camera, w, h, dvrOptions(table), "unclipped");
}

// Chords cut short inside a cell (rays start and stop at a clipping box's faces, which lie inside
// cells): the chain takes those that end in corner pieces, integrateCellPieces those that end in the
// central piece (march_fcc.glsl's integrateCell); the image is two gathers a cell's up to float
// rounding.
TEST_F(RenderDvr, ChainTakesChordsCutInsideACell) {
  const SmallBlobs blobs;
  const int w = 48, h = 48;
  render::RenderOptions options = dvrOptions(rampTable(0.05, 1.0, 2.0));
  options.clipLo = glm::dvec3(20.3, 15.7, 18.2);
  options.clipHi = glm::dvec3(70.6, 75.1, 66.45);
  const render::FrameImages chain = expectChainIsTwoGathers(blobs.source, blobs.camera, w, h, options, "clipped");
  int visible = 0;
  for (std::size_t i = 3; i < chain.rgba.size(); i += 4) visible += chain.rgba[i] > 0.05f;
  EXPECT_GT(visible, w * h / 20) << "the clipped volume must show";
}

// Another transfer function on a live renderer (the viewer's editor) gives the image a new renderer
// with it gives, bit for bit; one whose zero entries did not move (other colours, other non-zero
// opacities) uploads the table alone: no recomputation of the bricks needed. So do gradient shading
// and the stop opacity changed on it.
TEST_F(RenderDvr, TransferShadingAndStopChangedOnALiveRendererGiveAFreshOnesImage) {
  const SmallBlobs blobs;
  const int w = 48, h = 48;
  const TransferTable first = rampTable(0.2, 1.0, 2.0);
  // The same zeros (below 0.2), other colours and opacities above them.
  const TransferFunction recoloured({{0.2, {0.9, 0.1, 0.1}}, {1.0, {0.1, 0.9, 0.3}}}, {{0.2, 0.0}, {0.5, 0.9}, {1.0, 0.3}});
  const TransferTable second(recoloured, first.vmin(), first.vmax(), first.size(), OpticalScale{2.0, 1.0});
  ASSERT_EQ(second.nonZeroPrefix(), first.nonZeroPrefix());
  // Zero up to 0.5 over the same range: fewer bricks.
  const TransferFunction narrower({{0.2, {0.9, 0.1, 0.1}}, {1.0, {0.1, 0.9, 0.3}}}, {{0.5, 0.0}, {1.0, 0.6}});
  const TransferTable third(narrower, first.vmin(), first.vmax(), first.size(), OpticalScale{2.0, 1.0});
  ASSERT_NE(third.nonZeroPrefix(), first.nonZeroPrefix());

  render::Raycaster live(blobs.source, dvrOptions(first));
  live.render(blobs.camera, w, h);
  const render::FrameImages firstImage = live.readImages();
  const uint64_t updates = live.neededUpdates();
  live.setTransfer(std::make_shared<const TransferTable>(second));
  EXPECT_EQ(live.neededUpdates(), updates) << "the same zero entries: the bricks needed were recomputed";
  live.render(blobs.camera, w, h);
  const render::FrameImages secondImage = live.readImages();
  EXPECT_NE(secondImage.rgba, firstImage.rgba) << "the new colours must show";
  EXPECT_EQ(secondImage.rgba, renderSource(blobs.source, blobs.camera, w, h, dvrOptions(second)).rgba);
  live.setTransfer(std::make_shared<const TransferTable>(third));
  EXPECT_GT(live.neededUpdates(), updates) << "zero entries moved: the bricks needed must be recomputed";
  live.render(blobs.camera, w, h);
  EXPECT_EQ(live.readImages().rgba, renderSource(blobs.source, blobs.camera, w, h, dvrOptions(third)).rgba);

  // The viewer's other DVR settings on a live renderer: gradient shading (the programs built again)
  // and the stop opacity give a fresh renderer's image, and back off, the first again.
  render::RenderOptions shadedHalf = dvrOptions(third);
  shadedHalf.dvrShading.on = true;
  shadedHalf.terminationOpacity = 0.5f;
  live.setDvrShading(shadedHalf.dvrShading);
  live.setTerminationOpacity(0.5f);
  live.render(blobs.camera, w, h);
  const render::FrameImages liveShadedHalf = live.readImages();
  EXPECT_NE(liveShadedHalf.rgba, renderSource(blobs.source, blobs.camera, w, h, dvrOptions(third)).rgba);
  EXPECT_EQ(liveShadedHalf.rgba, renderSource(blobs.source, blobs.camera, w, h, shadedHalf).rgba);
  EXPECT_THROW(live.setTerminationOpacity(0.0f), ValueError);
  EXPECT_EQ(live.options().terminationOpacity, 0.5f) << "a refused stop opacity changes nothing";
  live.setDvrShading(render::DvrShading{});
  live.setTerminationOpacity(dvrOptions(third).terminationOpacity);
  live.render(blobs.camera, w, h);
  EXPECT_EQ(live.readImages().rgba, renderSource(blobs.source, blobs.camera, w, h, dvrOptions(third)).rgba);
}

// FCCVDB_DUMP_SHADERS (tools/shader-stats): each compute program's whole source as compiled, one file
// a program; the raycaster's DVR program there compiles again as it is, and shading toggled on a live
// renderer writes the program built again, with its define.
TEST_F(RenderDvr, DumpedProgramsAreTheSourcesAsCompiled) {
  const SmallBlobs blobs;
  TempDir dump;
  const std::string dumpDir = dump.path.string();
  const test::ScopedEnv dumping("FCCVDB_DUMP_SHADERS", dumpDir.c_str());
  render::Raycaster raycaster(blobs.source, dvrOptions(rampTable(0.2, 1.0, 2.0)));
  const auto raycastSources = [&dump] {
    std::vector<std::string> texts;
    for (const auto& entry : std::filesystem::directory_iterator(dump.path))
      if (entry.path().filename().string().find("_shaders_raycast.comp") != std::string::npos) {
        std::ifstream in(entry.path());
        texts.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      }
    return texts;
  };
  std::vector<std::string> texts = raycastSources();
  ASSERT_EQ(texts.size(), 1u);
  EXPECT_NE(texts[0].find("#define FCC_MODE_DVR 1"), std::string::npos);
  EXPECT_EQ(texts[0].find("#define FCC_DVR_SHADING 1"), std::string::npos);
  EXPECT_EQ(texts[0].find("#include"), std::string::npos) << "includes resolved";
  EXPECT_NO_THROW(GlProgram::compute(texts[0], "dumped raycast.comp"));
  render::DvrShading shaded;
  shaded.on = true;
  raycaster.setDvrShading(shaded);
  texts = raycastSources();
  ASSERT_EQ(texts.size(), 2u);
  EXPECT_EQ(std::count_if(texts.begin(), texts.end(),
                          [](const std::string& t) { return t.find("#define FCC_DVR_SHADING 1") != std::string::npos; }),
            1);
}

// Gradient shading whose program fails to build (here: a define that breaks the shaded code alone,
// set after the renderer was made) is one error, and the renderer goes on as it was: unshaded, the
// same image, and the highlight and light asked for with it not taken either.
TEST_F(RenderDvr, ShadingThatFailsToBuildLeavesTheRendererAsItWas) {
  const SmallBlobs blobs;
  const int w = 32, h = 32;
  render::Raycaster live(blobs.source, dvrOptions(rampTable(0.2, 1.0, 2.0)));
  live.render(blobs.camera, w, h);
  const render::FrameImages before = live.readImages();
  {
    const test::ScopedEnv broken("FCCVDB_SHADER_DEFINES", "kDvrAmbient=1");  // "const float 1 = ...": shaded only
    render::DvrShading shaded;
    shaded.on = true;
    shaded.specular = 0.5f;
    shaded.light = render::DvrLight::Kit;
    EXPECT_THROW(live.setDvrShading(shaded), GlError);
  }
  EXPECT_EQ(live.options().dvrShading, render::DvrShading{}) << "nothing of the refused shading is taken";
  live.render(blobs.camera, w, h);
  EXPECT_EQ(live.readImages().rgba, before.rgba);
}

// The shading tests' scenes: a Cartesian field through trilinear and tricubic, FCC blobs through the
// box spline, each with a camera and a table; and the CPU reference of a scene with given options.
struct ShadingScenes {
  struct Case {
    const char* name;
    const render::BrickSource* source;
    glm::dmat4 worldFromIndex;
    TransferTable table;
    double tMax;
    render::Camera camera;
  };
  static constexpr int w = 48, h = 40;
  TempDir dir;
  std::string ccPath = dir / "wavy.vdb", fccPath = dir / "blobs.vdb";
  std::unique_ptr<io::CartesianBrickStore> ccStore;
  std::unique_ptr<io::BrickStore> store;
  FccGrid::Ptr grid;
  std::unique_ptr<render::CartesianBrickSource> trilinear, tricubic;
  std::unique_ptr<render::FccBrickSource> boxSpline;
  std::vector<Case> cases;

  ShadingScenes() {
    test::writeCartesianFile(ccPath, test::wavy, 0.5, openvdb::Vec3d(-3.0, 1.0, 2.0));
    ccStore = std::make_unique<io::CartesianBrickStore>(ccPath);
    EXPECT_EQ(test::runFccvdb("synth blobs " + fccPath + " --dims 48,48,48 --quiet").status, 0);
    store = std::make_unique<io::BrickStore>(fccPath);
    grid = io::readFccGrid(fccPath);
    trilinear = std::make_unique<render::CartesianBrickSource>(*ccStore, findReconstruction("trilinear"));
    tricubic = std::make_unique<render::CartesianBrickSource>(*ccStore, findReconstruction("tricubic"));
    boxSpline = std::make_unique<render::FccBrickSource>(*store, std::size_t(64) << 20);
    cases = {{"trilinear", trilinear.get(), ccStore->worldFromIndex(), rampTable(0.0, 1.5, 4.0, 1.95), 200.0, {}},
             {"tricubic", tricubic.get(), ccStore->worldFromIndex(), rampTable(0.0, 1.5, 4.0, 1.95), 200.0, {}},
             {"boxspline", boxSpline.get(), store->worldFromIndex(), rampTable(0.1, 1.2, 4.0), 300.0, {}}};
    for (Case& c : cases) {
      c.camera.lookat = glm::dvec3(c.worldFromIndex * glm::dvec4(24.0, 24.0, 24.0, 1.0));
      c.camera.eye = c.camera.lookat + (c.source == boxSpline.get() ? glm::dvec3(60.0, 44.0, 72.0) : glm::dvec3(30.0, 22.0, 36.0));
      c.camera.fovYDegrees = 35.0;
    }
  }

  // The CPU reference of case c, shaded with the renderer's normals and `options`' shading terms.
  std::vector<DvrPixel> reference(const Case& c, DvrOptions options) const {
    const glm::dmat4 indexFromWorld = glm::inverse(c.worldFromIndex);
    const render::CameraFrame frame = render::cameraFrame(c.camera, double(w) / h);
    options.normalFromIndex = glm::transpose(glm::dmat3(indexFromWorld));
    const auto rayAt = [&](int x, int y) {
      return dvrRayFromWorld(indexFromWorld, c.camera.eye, render::pixelRay(frame, x, y, w, h), 0.0, c.tMax);
    };
    if (c.source == boxSpline.get()) {
      const SiteValue at = [&](const glm::ivec3& ijk) {
        const glm::ivec3 v = packedVoxelOfSite(ijk);
        return grid->tree().getValue(openvdb::Coord(v.x, v.y, v.z))[channelOfSite(ijk)];
      };
      options.step = 0.02;
      return renderDvrImage(w, h, rayAt, *makeReconstruction("boxspline"), at, nullptr, dvrMedium(c.table), options);
    }
    const ReconstructionInfo& info = findReconstruction(c.name);
    const int pad = kBSplinePrefilterReach + 4;
    LatticeSamples samples(Lattice::Cc, glm::ivec3(-pad), glm::ivec3(test::kDim + 2 * pad), test::kBackground);
    samples.fill([](const glm::ivec3& ijk) {
      const bool in = glm::all(glm::greaterThanEqual(ijk, glm::ivec3(0))) && glm::all(glm::lessThan(ijk, glm::ivec3(test::kDim)));
      return in ? test::wavy(ijk) : test::kBackground;
    });
    samples.prefilter(info.prefilter);
    const CellBounds bounds(samples);
    options.step = 0.01;
    return renderDvrImage(w, h, rayAt, *makeReconstruction(c.name), samples.accessor(), &bounds, dvrMedium(c.table), options);
  }
};

// Gradient shading (--shading on) multiplies each sub-step's emission by a factor in [ambient, 1] and
// leaves absorption alone: opacity and depth are those of the unshaded image with the same sub-steps
// (the shaded rule keeps its curvature term: FCC_DVR_BEND_TERM=1), bit for bit, and the default
// unshaded image's within the rule's error; every colour lies between ambient times and once the
// unshaded one, and it darkens where the gradient turns away from the view. On every lattice it agrees
// with the CPU reference shaded the same way, within the unshaded bound (45 dB).
TEST_F(RenderDvr, ShadingDarkensOnlyTheEmissionAndMatchesTheCpuReference) {
  const ShadingScenes scenes;
  const int w = scenes.w, h = scenes.h;
  for (const ShadingScenes::Case& c : scenes.cases) {
    SCOPED_TRACE(c.name);
    const render::Camera& camera = c.camera;
    render::RenderOptions off = dvrOptions(c.table), on = off;
    on.dvrShading.on = true;
    const render::FrameImages shaded = renderSource(*c.source, camera, w, h, on);
    const render::FrameImages unshaded = renderSource(*c.source, camera, w, h, off);
    render::FrameImages plain;  // with the shaded image's sub-steps
    {
      const test::ScopedEnv sameSteps("FCCVDB_SHADER_DEFINES", "FCC_DVR_BEND_TERM=1");
      plain = renderSource(*c.source, camera, w, h, off);
    }
    const ImageDifference fromDefault = differenceOf(shaded, unshaded);
    double worstOpacityFromDefault = 0.0;
    for (std::size_t i = 3; i < shaded.rgba.size(); i += 4)
      worstOpacityFromDefault = std::max(worstOpacityFromDefault, std::abs(double(shaded.rgba[i]) - unshaded.rgba[i]));
    std::printf("%s: opacity differs from the default unshaded image's by at most %.3g (%d components differ)\n",
                c.name, worstOpacityFromDefault, fromDefault.differing);
    EXPECT_LE(worstOpacityFromDefault, kSubStepOpacityTol) << "shading must not change the absorption beyond the rule's error";
    int darker = 0, shown = 0, alphaDiffers = 0;
    double worstAlpha = 0.0, sumAlpha = 0.0;
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
      const double dAlpha = std::abs(double(shaded.rgba[4 * i + 3]) - double(plain.rgba[4 * i + 3]));
      alphaDiffers += dAlpha > 0.0;
      worstAlpha = std::max(worstAlpha, dAlpha);
      sumAlpha += dAlpha;
      EXPECT_EQ(shaded.normalDepth[4 * i + 3], plain.normalDepth[4 * i + 3]) << "shading changed the depth of pixel " << i;
      const float slack = 1e-7f;
      for (int k = 0; k < 3; ++k) {
        const float a = shaded.rgba[4 * i + k], b = plain.rgba[4 * i + k];
        EXPECT_LE(a, b * (1.0f + 1e-5f) + slack) << "pixel " << i;
        EXPECT_GE(a, float(kDvrShadingAmbient) * b * (1.0f - 1e-5f) - slack) << "pixel " << i;
      }
      shown += plain.rgba[4 * i + 3] > 0.05f;
      darker += plain.rgba[4 * i + 3] > 0.05f && shaded.rgba[4 * i] < 0.95f * plain.rgba[4 * i];
    }
    std::printf("%s: shading darkened %d of %d pixels that show the volume; opacity differs in %d pixels, "
                "worst %.3g, mean %.3g\n", c.name, darker, shown, alphaDiffers, worstAlpha, sumAlpha / double(w * h));
    EXPECT_EQ(alphaDiffers, 0) << "shading must leave the opacity alone, bit for bit";
    EXPECT_GT(shown, w * h / 10);
    EXPECT_GT(darker, shown / 10) << "shading must show";

    // The CPU reference, shaded with the same normals.
    DvrOptions reference;
    reference.shading = true;
    const double db = psnr(shaded, scenes.reference(c, reference));
    std::printf("%s shaded: PSNR %.1f dB against the shaded CPU reference\n", c.name, db);
    EXPECT_GE(db, kMinPsnrDb);
  }
}

// The specular term (--specular K --specular-power P) adds white light in proportion to each
// sub-step's opacity: opacity and depth stay the shaded image's bit for bit, each pixel's three
// colours rise by the same amount (within float rounding), some visibly; on every lattice it agrees
// with the CPU reference lit the same way (45 dB). On a live renderer the setter gives a fresh one's
// image and refuses values outside the ranges.
TEST_F(RenderDvr, SpecularAddsWhiteLightOnlyAndMatchesTheCpuReference) {
  const ShadingScenes scenes;
  const int w = scenes.w, h = scenes.h;
  const float strength = 0.6f, power = 8.0f;
  for (const ShadingScenes::Case& c : scenes.cases) {
    SCOPED_TRACE(c.name);
    render::RenderOptions shadedOptions = dvrOptions(c.table);
    shadedOptions.dvrShading.on = true;
    render::RenderOptions litOptions = shadedOptions;
    litOptions.dvrShading.specular = strength;
    litOptions.dvrShading.specularPower = power;
    const render::FrameImages shaded = renderSource(*c.source, c.camera, w, h, shadedOptions);
    const render::FrameImages lit = renderSource(*c.source, c.camera, w, h, litOptions);
    int brighter = 0;
    double worstSpread = 0.0;
    for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
      EXPECT_EQ(lit.rgba[4 * i + 3], shaded.rgba[4 * i + 3]) << "the highlight changed the opacity of pixel " << i;
      EXPECT_EQ(lit.normalDepth[4 * i + 3], shaded.normalDepth[4 * i + 3]) << "the highlight changed the depth of pixel " << i;
      double rise[3];
      for (int k = 0; k < 3; ++k) rise[k] = double(lit.rgba[4 * i + k]) - double(shaded.rgba[4 * i + k]);
      for (int k = 0; k < 3; ++k) EXPECT_GE(rise[k], -1e-6) << "pixel " << i << " channel " << k;
      worstSpread = std::max({worstSpread, std::abs(rise[0] - rise[1]), std::abs(rise[0] - rise[2])});
      brighter += rise[0] > 0.02;
    }
    std::printf("%s: the highlight brightened %d of %d pixels; the channels' rises differ by at most %.3g\n", c.name,
                brighter, w * h, worstSpread);
    EXPECT_LE(worstSpread, 1e-5) << "the highlight must be white";
    EXPECT_GT(brighter, w * h / 50) << "the highlight must show";
    DvrOptions reference;
    reference.shading = true;
    reference.specular = strength;
    reference.specularPower = power;
    const double db = psnr(lit, scenes.reference(c, reference));
    std::printf("%s lit: PSNR %.1f dB against the lit CPU reference\n", c.name, db);
    EXPECT_GE(db, kMinPsnrDb);

    if (c.source != scenes.boxSpline.get()) continue;
    render::Raycaster live(*c.source, shadedOptions);
    live.setDvrShading(litOptions.dvrShading);
    live.render(c.camera, w, h);
    EXPECT_EQ(live.readImages().rgba, lit.rgba) << "a live change must give a fresh renderer's image";
    render::DvrShading bad = litOptions.dvrShading;
    bad.specular = 1.5f;
    EXPECT_THROW(live.setDvrShading(bad), ValueError);
    bad = litOptions.dvrShading;
    bad.specularPower = 0.0f;
    EXPECT_THROW(live.setDvrShading(bad), ValueError);
    EXPECT_EQ(live.options().dvrShading, litOptions.dvrShading) << "a refused value changes nothing";
    render::DvrShading none = litOptions.dvrShading;
    none.specular = 0.0f;
    live.setDvrShading(none);
    live.render(c.camera, w, h);
    EXPECT_EQ(live.readImages().rgba, shaded.rgba) << "strength 0: the shaded image";
  }
}

// A directional light fixed to the camera (--light AZIMUTH,ELEVATION: RenderOptions::dvrShading.light
// Directional, lightInCamera) and the light kit (--light kit: viewer/DvrLight.h) instead of the
// headlight: opacity and depth stay the headlight's bit for bit, the colours change (the light comes
// from elsewhere), and on every lattice each agrees with the CPU reference lit the same way (45 dB),
// the specular term's half vectors too. On a live renderer the setters give a fresh one's image, and
// the headlight again gives the headlight's image.
TEST_F(RenderDvr, ADirectionalLightAndTheLightKitMatchTheCpuReference) {
  const ShadingScenes scenes;
  const int w = scenes.w, h = scenes.h;
  const glm::vec3 lightInCamera = render::lightInCameraFromAngles(60.0f, 35.0f);
  const float strength = 0.6f, power = 8.0f;
  for (const ShadingScenes::Case& c : scenes.cases) {
    SCOPED_TRACE(c.name);
    render::RenderOptions headlightOptions = dvrOptions(c.table);
    headlightOptions.dvrShading.on = true;
    headlightOptions.dvrShading.specular = strength;
    headlightOptions.dvrShading.specularPower = power;
    const render::FrameImages headlit = renderSource(*c.source, c.camera, w, h, headlightOptions);
    const render::CameraFrame frame = render::cameraFrame(c.camera, double(w) / h);
    render::FrameImages litImages[2];
    for (render::DvrLight light : {render::DvrLight::Directional, render::DvrLight::Kit}) {
      const std::string lightName = render::dvrLightName(light);
      render::RenderOptions litOptions = headlightOptions;
      litOptions.dvrShading.light = light;
      litOptions.lightInCamera = lightInCamera;
      const render::FrameImages lit = renderSource(*c.source, c.camera, w, h, litOptions);
      int changed = 0;
      for (std::size_t i = 0; i < std::size_t(w) * h; ++i) {
        EXPECT_EQ(lit.rgba[4 * i + 3], headlit.rgba[4 * i + 3]) << lightName << " changed the opacity of pixel " << i;
        EXPECT_EQ(lit.normalDepth[4 * i + 3], headlit.normalDepth[4 * i + 3]) << lightName << " changed the depth of pixel " << i;
        changed += std::abs(lit.rgba[4 * i] - headlit.rgba[4 * i]) > 0.02f;
      }
      std::printf("%s: the %s light changed %d of %d pixels\n", c.name, lightName.c_str(), changed, w * h);
      EXPECT_GT(changed, w * h / 20) << "the " << lightName << " light must show";
      DvrOptions reference;
      reference.shading = true;
      reference.specular = strength;
      reference.specularPower = power;
      reference.light = DvrOptions::Light::Directional;
      reference.lightWorld = glm::dvec3(render::lightTowardsWorld(frame, lightInCamera));
      if (light == render::DvrLight::Kit) {
        const render::LightKit& kit = render::defaultLightKit();
        for (std::size_t k = 0; k < kit.inCamera.size(); ++k)
          reference.kit.push_back({glm::dvec3(render::lightTowardsWorld(frame, kit.inCamera[k])), double(kit.weight[k])});
        reference.kitHeadWeight = kit.headWeight;
        reference.light = DvrOptions::Light::Kit;
      }
      const double db = psnr(lit, scenes.reference(c, reference));
      std::printf("%s under the %s light: PSNR %.1f dB against the CPU reference lit the same way\n", c.name,
                  lightName.c_str(), db);
      EXPECT_GE(db, kMinPsnrDb) << lightName;
      litImages[light == render::DvrLight::Kit] = lit;
    }
    EXPECT_NE(litImages[0].rgba, litImages[1].rgba) << "the kit is not the directional light";

    if (c.source != scenes.boxSpline.get()) continue;
    render::Raycaster live(*c.source, headlightOptions);
    const auto lightOnly = [&headlightOptions](render::DvrLight light) {
      render::DvrShading shading = headlightOptions.dvrShading;
      shading.light = light;
      return shading;
    };
    live.setDvrShading(lightOnly(render::DvrLight::Directional));
    live.setLightInCamera(lightInCamera);
    live.render(c.camera, w, h);
    EXPECT_EQ(live.readImages().rgba, litImages[0].rgba) << "a live change must give a fresh renderer's image";
    live.setDvrShading(lightOnly(render::DvrLight::Kit));
    live.render(c.camera, w, h);
    EXPECT_EQ(live.readImages().rgba, litImages[1].rgba) << "the kit, live";
    live.setDvrShading(lightOnly(render::DvrLight::Headlight));
    live.render(c.camera, w, h);
    EXPECT_EQ(live.readImages().rgba, headlit.rgba) << "the headlight again";
  }
}

}  // namespace
}  // namespace fcc
