// The CPU reference of direct volume rendering (sparse/ReferenceDvr.h): exact against the analytic
// opacity of a sphere's chord (synth's sphere field, value = squared distance over R^2, with a transfer
// function of constant extinction inside r and none outside), second-order convergence when the step
// halves, skipping that changes nothing, early termination, the GPU table as the medium, and the world
// ray's mapping into index space.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "sparse/Error.h"
#include "sparse/LatticeSamples.h"
#include "sparse/ReferenceDvr.h"

namespace fcc {
namespace {

// Synth's sphere field in world units: f = |p - c|^2 / R^2 with R = 10 index units = 1 world unit
// (h = 0.1 world units per index unit), sampled on a lattice and prefiltered for `recon`.
constexpr double kH = 0.1;
const glm::dvec3 kCentreIndex(0.3, -0.2, 0.1);

struct SphereScene {
  LatticeSamples samples;
  CellBounds bounds;
  std::unique_ptr<Reconstruction> recon;
  glm::dmat4 indexFromWorld{1.0 / kH};

  explicit SphereScene(const ReconstructionInfo& info)
      : samples(makeSamples(info)), bounds(samples), recon(makeReconstruction(info.name)) {
    indexFromWorld[3][3] = 1.0;
  }
  static LatticeSamples makeSamples(const ReconstructionInfo& info) {
    // Background 9: beyond the box the field reads as far outside every sphere of the tests.
    LatticeSamples s(info.lattice, glm::ivec3(-24), glm::ivec3(49), 9.0f);
    s.fill([](const glm::ivec3& ijk) {
      const glm::dvec3 q = glm::dvec3(ijk) - kCentreIndex;
      return float(glm::dot(q, q) / 100.0);
    });
    s.prefilter(info.prefilter);
    return s;
  }
  glm::dvec3 centreWorld() const { return kH * kCentreIndex; }
};

// Rays through the sphere's centre region: direction d, passing at distance b from the centre,
// starting 2 world units before the closest point (t in [0, 4]).
struct TestRay {
  glm::dvec3 o, d;
  double b;
};
std::vector<TestRay> testRays(int count, double bMax, uint64_t seed, const glm::dvec3& centre) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), v(0.0, 1.0);
  std::vector<TestRay> rays;
  for (int i = 0; i < count; ++i) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
    glm::dvec3 side = glm::cross(d, glm::normalize(glm::dvec3(u(rng), u(rng), u(rng))));
    side = glm::normalize(side);
    const double b = bMax * std::sqrt(v(rng));
    rays.push_back({centre + b * side - 2.0 * d, d, b});
  }
  return rays;
}

TEST(ReferenceDvr, SphereChordOpacityIsExact) {
  // Opacity 0.1 per voxel (unit distance 0.1 world units) for values below r^2 (r = 0.7), none above:
  // sigma = -ln(0.9) / 0.1 = 1.054 per world unit inside the sphere of radius 0.7.
  const double r = 0.7, alpha0 = 0.1;
  const OpticalScale scale{kH, 1.0};
  const glm::dvec3 rgb(1.0, 0.5, 0.25);
  const TransferFunction tf({{0.0, rgb}}, {{0.0, alpha0}, {r * r, alpha0}, {r * r, 0.0}, {1.0, 0.0}});
  const double sigma = extinctionFromOpacity(alpha0, scale);
  const DvrMedium medium = dvrMedium(tf, scale);
  DvrOptions options;
  options.step = 2e-4;
  options.terminationOpacity = 1.0;
  // The bound (docs/DVR.md): the sub-step holding each of the two jumps of the transfer function takes
  // one side for all of it, so the optical depth is off by at most sigma step / 2 at each; plus float
  // rounding of the positions and values.
  const double tolerance = sigma * options.step + 2e-5;
  for (const ReconstructionInfo& info : reconstructionInfos()) {
    if (info.reproduces < 2) continue;  // the sphere is exact only where quadratics are reproduced
    const SphereScene scene(info);
    double worst = 0.0, worstDepth = 0.0;
    int crossing = 0;
    for (const TestRay& ray : testRays(40, 0.95, 5, scene.centreWorld())) {
      scene.recon->setView(glm::vec3(ray.d));
      const DvrRay indexRay = dvrRayFromWorld(scene.indexFromWorld, ray.o, ray.d, 0.0, 4.0);
      const DvrPixel pixel = integrateDvrRay(*scene.recon, scene.samples.accessor(), &scene.bounds, medium, indexRay, options);
      if (ray.b > 0.65 && ray.b < 0.75) continue;  // grazing: the chord is too sensitive to float rounding
      const double chord = ray.b < r ? 2.0 * std::sqrt(r * r - ray.b * ray.b) : 0.0;
      const double alpha = 1.0 - std::exp(-sigma * chord);
      const double error = std::abs(pixel.rgba.a - alpha);
      worst = std::max(worst, error);
      EXPECT_LT(error, tolerance) << info.name << " b = " << ray.b << " chord " << chord;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(pixel.rgba[k], rgb[k] * pixel.rgba.a, 1e-12);  // premultiplied
      if (sigma * chord > std::log(2.0) + 0.05) {
        const double depth = 2.0 - 0.5 * chord + std::log(2.0) / sigma;
        worstDepth = std::max(worstDepth, std::abs(pixel.depth - depth));
        EXPECT_NEAR(pixel.depth, depth, options.step + 1e-4) << info.name << " b = " << ray.b;
        ++crossing;
      } else if (sigma * chord < std::log(2.0) - 0.05) {
        EXPECT_TRUE(std::isinf(pixel.depth)) << info.name;
      }
    }
    std::printf("[   INFO   ] %s: worst opacity error %.3g (bound %.3g), worst depth error %.3g over %d rays\n",
                std::string(info.name).c_str(), worst, tolerance, worstDepth, crossing);
    EXPECT_GT(crossing, 5);
  }
}

// I(step) for a smooth medium: viridis with its opacity ramp over the field's values [0, 8], unit
// distance 1 world unit (opacity up to about 0.5 per unit along the rays).
std::vector<DvrPixel> smoothRays(const SphereScene& scene, double step, bool skip) {
  const TransferFunction tf = transferFunctionPreset("viridis").stretchedTo(0.0, 8.0);
  const DvrMedium medium = dvrMedium(tf, {1.0, 1.0});
  DvrOptions options;
  options.step = step;
  options.terminationOpacity = 1.0;
  std::vector<DvrPixel> out;
  for (const TestRay& ray : testRays(12, 0.8, 9, scene.centreWorld())) {
    scene.recon->setView(glm::vec3(ray.d));
    out.push_back(integrateDvrRay(*scene.recon, scene.samples.accessor(), skip ? &scene.bounds : nullptr, medium,
                                  dvrRayFromWorld(scene.indexFromWorld, ray.o, ray.d, 0.0, 4.0), options));
  }
  return out;
}

double difference(const std::vector<DvrPixel>& a, const std::vector<DvrPixel>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 4; ++k) sum += std::abs(a[i].rgba[k] - b[i].rgba[k]);
  return sum / double(4 * a.size());
}

TEST(ReferenceDvr, HalvingTheStepConvergesAtSecondOrder) {
  const SphereScene scene(findReconstruction("boxspline"));
  // Steps 1/32, 1/64, 1/128, 1/256 of a world unit (uniform: no cell splits, so each halves the last).
  std::vector<std::vector<DvrPixel>> runs;
  for (int k = 5; k <= 8; ++k) runs.push_back(smoothRays(scene, std::ldexp(1.0, -k), false));
  const double e1 = difference(runs[0], runs[1]), e2 = difference(runs[1], runs[2]), e3 = difference(runs[2], runs[3]);
  std::printf("[   INFO   ] mean |I(h) - I(h/2)|: %.3g, %.3g, %.3g (ratios %.2f, %.2f)\n", e1, e2, e3, e1 / e2, e2 / e3);
  EXPECT_GT(e1, 1e-7);  // the test has something to measure
  EXPECT_GT(e1 / e2, 3.0);
  EXPECT_LT(e1 / e2, 5.0);
  EXPECT_GT(e2 / e3, 3.0);
  EXPECT_LT(e2 / e3, 5.0);
  // Richardson: the error at 1/256 is about e3 / 3; the reference's default step (1e-3) is smaller still.
  EXPECT_LT(e3 / 3.0, 1e-4);
}

TEST(ReferenceDvr, SkippingEmptyCellsChangesNothing) {
  // A medium that is empty above r^2: cells wholly outside the sphere are skipped.
  const double r = 0.6;
  const TransferFunction tf = TransferFunction({{0.0, glm::dvec3(0.2, 0.4, 0.9)}, {r * r, glm::dvec3(1.0, 0.8, 0.1)}},
                                               {{0.0, 0.02}, {0.8 * r * r, 0.08}, {r * r, 0.0}});
  const DvrMedium medium = dvrMedium(tf, {kH, 1.0});
  DvrOptions options;
  options.step = 1e-3;
  options.terminationOpacity = 1.0;
  const SphereScene scene(findReconstruction("boxspline"));
  long withSkip = 0, without = 0;
  for (const TestRay& ray : testRays(10, 0.9, 13, scene.centreWorld())) {
    const DvrRay indexRay = dvrRayFromWorld(scene.indexFromWorld, ray.o, ray.d, 0.0, 4.0);
    const DvrPixel a = integrateDvrRay(*scene.recon, scene.samples.accessor(), &scene.bounds, medium, indexRay, options);
    const DvrPixel b = integrateDvrRay(*scene.recon, scene.samples.accessor(), nullptr, medium, indexRay, options);
    // The two differ only in where the sub-steps fall (second order, smooth medium, continuous at r^2).
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(a.rgba[k], b.rgba[k], 1e-5) << "b = " << ray.b;
    withSkip += a.evaluations;
    without += b.evaluations;
  }
  std::printf("[   INFO   ] evaluations with skipping %ld, without %ld\n", withSkip, without);
  EXPECT_LT(withSkip, without / 2);
}

TEST(ReferenceDvr, TheTableMediumAgreesWithTheFunction) {
  const TransferFunction tf = transferFunctionPreset("inferno").stretchedTo(0.0, 2.0);
  const OpticalScale scale{0.5, 1.0};
  const DvrMedium exact = dvrMedium(tf, scale);
  const DvrMedium table = dvrMedium(TransferTable(tf, 0.0, 2.0, 1024, scale));
  DvrOptions options;
  options.step = 4e-3;
  const SphereScene scene(findReconstruction("boxspline"));
  for (const TestRay& ray : testRays(8, 0.9, 21, scene.centreWorld())) {
    const DvrRay indexRay = dvrRayFromWorld(scene.indexFromWorld, ray.o, ray.d, 0.0, 4.0);
    const DvrPixel a = integrateDvrRay(*scene.recon, scene.samples.accessor(), &scene.bounds, exact, indexRay, options);
    const DvrPixel b = integrateDvrRay(*scene.recon, scene.samples.accessor(), &scene.bounds, table, indexRay, options);
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(a.rgba[k], b.rgba[k], 2e-3) << "b = " << ray.b;
  }
}

TEST(ReferenceDvr, EarlyTerminationStopsAtTheOpacity) {
  // A dense medium everywhere: opacity 0.9 per 0.1 world units (sigma = 23 per world unit).
  const TransferFunction tf({{0.0, glm::dvec3(1.0)}}, {{0.0, 0.9}});
  const DvrMedium medium = dvrMedium(tf, {0.1, 1.0});
  const SphereScene scene(findReconstruction("boxspline"));
  const DvrRay ray = dvrRayFromWorld(scene.indexFromWorld, scene.centreWorld() - glm::dvec3(2.0, 0, 0),
                                     glm::dvec3(1.0, 0.0, 0.0), 0.0, 4.0);
  DvrOptions options;
  options.step = 1e-3;
  const DvrPixel early = integrateDvrRay(*scene.recon, scene.samples.accessor(), &scene.bounds, medium, ray, options);
  options.terminationOpacity = 1.0;
  const DvrPixel full = integrateDvrRay(*scene.recon, scene.samples.accessor(), &scene.bounds, medium, ray, options);
  EXPECT_GE(early.rgba.a, 0.995);
  EXPECT_LT(early.rgba.a, 0.9999);
  EXPECT_GT(full.rgba.a, 1.0 - 1e-12);
  EXPECT_GE(full.evaluations, 4000);  // every sub-step (4 / 0.001, and the cell splits): e^-92 is not 0
  EXPECT_LT(early.evaluations * 10, full.evaluations);
  // Opacity 0.5 is reached after ln 2 / sigma.
  EXPECT_NEAR(early.depth, std::log(2.0) / extinctionFromOpacity(0.9, {0.1, 1.0}), 1e-9);
  EXPECT_EQ(early.depth, full.depth);
}

TEST(ReferenceDvr, WorldRaysKeepTheWorldDistance) {
  glm::dmat4 worldFromIndex(1.0);
  worldFromIndex[0] = glm::dvec4(0.5, 0.1, 0.0, 0.0);
  worldFromIndex[1] = glm::dvec4(0.0, 0.25, 0.0, 0.0);
  worldFromIndex[2] = glm::dvec4(0.0, 0.05, 2.0, 0.0);
  worldFromIndex[3] = glm::dvec4(3.0, -1.0, 7.0, 1.0);
  const glm::dvec3 o(1.0, 2.0, 3.0), d = glm::normalize(glm::dvec3(0.3, -0.4, 0.8));
  const DvrRay ray = dvrRayFromWorld(glm::inverse(worldFromIndex), o, d, 0.5, 9.0);
  EXPECT_EQ(ray.t0, 0.5);
  EXPECT_EQ(ray.t1, 9.0);
  for (double t : {0.0, 1.0, 4.5}) {
    const glm::dvec3 back = glm::dvec3(worldFromIndex * glm::dvec4(ray.o + t * ray.d, 1.0));
    EXPECT_NEAR(glm::length(back - (o + t * d)), 0.0, 1e-12) << t;
  }
}

TEST(ReferenceDvr, ImagesAreTheirRays) {
  const SphereScene scene(findReconstruction("boxspline"));
  const DvrMedium medium = dvrMedium(transferFunctionPreset("fog").stretchedTo(0.0, 1.0), {kH, 1.0});
  const auto rayAt = [&](int x, int y) {
    const glm::dvec3 o = scene.centreWorld() + glm::dvec3(-2.0, (x - 3.5) * 0.2, (y - 3.5) * 0.2);
    return dvrRayFromWorld(scene.indexFromWorld, o, glm::dvec3(1.0, 0.0, 0.0), 0.0, 4.0);
  };
  DvrOptions options;
  options.step = 5e-3;
  const std::vector<DvrPixel> image =
      renderDvrImage(8, 8, rayAt, *scene.recon, scene.samples.accessor(), &scene.bounds, medium, options);
  ASSERT_EQ(image.size(), 64u);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x)
      EXPECT_EQ(image[size_t(y) * 8 + x].rgba,
                integrateDvrRay(*scene.recon, scene.samples.accessor(), &scene.bounds, medium, rayAt(x, y), options).rgba);
  EXPECT_GT(image[0].rgba.a, 0.0);
  options.step = 0.0;
  EXPECT_THROW(integrateDvrRay(*scene.recon, scene.samples.accessor(), nullptr, medium, rayAt(0, 0), options), ValueError);
}

// Gradient shading's factor: 1 where the gradient is 0 (flat regions keep their colour), 1 when the
// gradient lies along the ray, the ambient floor across it, the Lambert term between; measured in world
// space, whatever the grid's (anisotropic) transform.
TEST(ReferenceDvr, ShadingIsAHeadlightLambertOverAnAmbientFloor) {
  const glm::dmat3 identity(1.0);
  EXPECT_EQ(dvrShade(glm::dvec3(0.0), glm::dvec3(0.0, 0.0, 1.0), identity), 1.0);
  EXPECT_DOUBLE_EQ(dvrShade(glm::dvec3(0.0, 0.0, -3.0), glm::dvec3(0.0, 0.0, 1.0), identity), 1.0);
  EXPECT_DOUBLE_EQ(dvrShade(glm::dvec3(2.0, 0.0, 0.0), glm::dvec3(0.0, 0.0, 1.0), identity), kDvrShadingAmbient);
  const glm::dvec3 d60(std::sin(M_PI / 3.0), 0.0, std::cos(M_PI / 3.0));
  EXPECT_NEAR(dvrShade(glm::dvec3(0.0, 0.0, 1.0), d60, identity), kDvrShadingAmbient + (1.0 - kDvrShadingAmbient) * 0.5, 1e-12);
  // Index x = 4 world x (indexFromWorld = diag(4, 1, 1)): a world ray at 45 degrees in x-z and the field
  // f = world x (index gradient (1/4, 0, 0)) meet at 45 degrees in world space.
  const glm::dmat3 indexFromWorld(glm::dvec3(4.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.0, 1.0));
  const glm::dvec3 dWorld = glm::normalize(glm::dvec3(1.0, 0.0, 1.0));
  EXPECT_NEAR(dvrShade(glm::dvec3(0.25, 0.0, 0.0), indexFromWorld * dWorld, glm::transpose(indexFromWorld)),
              kDvrShadingAmbient + (1.0 - kDvrShadingAmbient) * std::sqrt(0.5), 1e-12);
}

// The sphere's test rays (12 x 5 through its centre's neighbourhood), each integrated with options a and b.
std::vector<std::pair<DvrPixel, DvrPixel>> pixelPairs(const SphereScene& scene, const DvrMedium& medium,
                                                      const DvrOptions& a, const DvrOptions& b) {
  std::vector<std::pair<DvrPixel, DvrPixel>> pairs;
  for (const TestRay& ray : testRays(12, 0.9, 5, scene.centreWorld())) {
    const DvrRay indexRay = dvrRayFromWorld(scene.indexFromWorld, ray.o, ray.d, 0.0, 4.0);
    pairs.emplace_back(integrateDvrRay(*scene.recon, scene.samples.accessor(), &scene.bounds, medium, indexRay, a),
                       integrateDvrRay(*scene.recon, scene.samples.accessor(), &scene.bounds, medium, indexRay, b));
  }
  return pairs;
}

// Through the sphere with shading on: the same opacity and depth, colour between the ambient floor and
// the unshaded colour, and the unshaded colour exactly where it is off.
TEST(ReferenceDvr, ShadingChangesOnlyTheEmission) {
  const TransferFunction tf({{0.0, glm::dvec3(0.2, 0.4, 0.9)}, {1.0, glm::dvec3(1.0, 0.8, 0.1)}}, {{0.0, 0.05}, {1.0, 0.0}});
  const DvrMedium medium = dvrMedium(tf, {kH, 1.0});
  const SphereScene scene(findReconstruction("boxspline"));
  DvrOptions off, on;
  off.step = on.step = 2e-3;
  on.shading = true;
  on.normalFromIndex = glm::transpose(glm::dmat3(scene.indexFromWorld));
  int darker = 0;
  for (const auto& [a, b] : pixelPairs(scene, medium, off, on)) {
    EXPECT_EQ(a.rgba.a, b.rgba.a);
    EXPECT_EQ(a.depth, b.depth);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(b.rgba[k], a.rgba[k] * (1.0 + 1e-12));
      EXPECT_GE(b.rgba[k], kDvrShadingAmbient * a.rgba[k] * (1.0 - 1e-12));
    }
    darker += b.rgba.r < 0.99 * a.rgba.r;
  }
  EXPECT_GT(darker, 6) << "the sphere's gradient turns away from most rays somewhere";
}

// The specular term: the strength where the gradient lies along the ray, 0 across it and where the
// gradient is 0, strength |cos|^power between; in world space like the Lambert term.
TEST(ReferenceDvr, SpecularIsBlinnPhongWithTheLightAtTheEye) {
  const glm::dmat3 identity(1.0);
  const glm::dvec3 dz(0.0, 0.0, 1.0);
  EXPECT_EQ(dvrSpecular(glm::dvec3(0.0), dz, identity, 0.7, 10.0), 0.0);
  EXPECT_DOUBLE_EQ(dvrSpecular(glm::dvec3(0.0, 0.0, -3.0), dz, identity, 0.7, 10.0), 0.7);
  EXPECT_EQ(dvrSpecular(glm::dvec3(2.0, 0.0, 0.0), dz, identity, 0.7, 10.0), 0.0);
  EXPECT_EQ(dvrSpecular(glm::dvec3(0.0, 0.0, 1.0), dz, identity, 0.0, 10.0), 0.0) << "strength 0: none";
  const glm::dvec3 d60(std::sin(M_PI / 3.0), 0.0, std::cos(M_PI / 3.0));
  EXPECT_NEAR(dvrSpecular(glm::dvec3(0.0, 0.0, 1.0), d60, identity, 0.7, 3.0), 0.7 * 0.125, 1e-12);
  const glm::dmat3 indexFromWorld(glm::dvec3(4.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.0, 1.0));
  const glm::dvec3 dWorld = glm::normalize(glm::dvec3(1.0, 0.0, 1.0));
  EXPECT_NEAR(dvrSpecular(glm::dvec3(0.25, 0.0, 0.0), indexFromWorld * dWorld, glm::transpose(indexFromWorld), 1.0, 2.0),
              0.5, 1e-12);
}

// A directional light: the Lambert term by the angle with the light (two-sided: ambient across it, 1
// along it either way), the highlight by the angle with the half vector between the light and the eye
// (none where they are opposite), (1, 0) where the gradient is 0; the headlight's terms where light and
// eye are the reversed ray; in world space (a stretched index space changes the angles as it does the
// headlight's).
TEST(ReferenceDvr, ADirectionalLightShadesByItsAngleAndTheHalfVector) {
  const glm::dmat3 identity(1.0);
  const glm::dvec3 x(1.0, 0.0, 0.0), y(0.0, 1.0, 0.0), z(0.0, 0.0, 1.0);
  const double strength = 0.7, power = 10.0;
  EXPECT_EQ(dvrShadeLit(glm::dvec3(0.0), identity, x, z, strength, power), glm::dvec2(1.0, 0.0));
  EXPECT_DOUBLE_EQ(dvrShadeLit(glm::dvec3(0.0, 0.0, 2.0), identity, x, z, strength, power).x, kDvrShadingAmbient);
  EXPECT_DOUBLE_EQ(dvrShadeLit(glm::dvec3(-3.0, 0.0, 0.0), identity, x, z, strength, power).x, 1.0);
  const glm::dvec3 half = glm::normalize(x + z);
  EXPECT_NEAR(dvrShadeLit(half * 5.0, identity, x, z, strength, power).y, strength, 1e-12) << "along the half vector";
  EXPECT_NEAR(dvrShadeLit(y, identity, x, z, strength, power).y, 0.0, 1e-15) << "across it";
  EXPECT_EQ(dvrShadeLit(x, identity, x, -x, strength, power).y, 0.0) << "light and eye opposite";
  EXPECT_EQ(dvrShadeLit(half, identity, x, z, 0.0, power).y, 0.0) << "strength 0: none";
  const glm::dvec3 d60(std::sin(M_PI / 3.0), 0.0, std::cos(M_PI / 3.0));
  const glm::dvec2 at60 = dvrShadeLit(z, identity, d60, d60, strength, 3.0);
  EXPECT_NEAR(at60.x, kDvrShadingAmbient + (1.0 - kDvrShadingAmbient) * 0.5, 1e-12);
  EXPECT_NEAR(at60.y, strength * 0.125, 1e-12);
  // The headlight's terms where the light and the eye are the reversed ray, in a stretched index space.
  const glm::dmat3 indexFromWorld(glm::dvec3(4.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.3, 2.0));
  const glm::dmat3 normalFromIndex = glm::transpose(indexFromWorld);
  const glm::dvec3 dWorld = glm::normalize(glm::dvec3(1.0, -0.4, 1.0)), gIndex(0.25, 0.5, -0.1);
  const glm::dvec2 reversed = dvrShadeLit(gIndex, normalFromIndex, -dWorld, -dWorld, strength, power);
  EXPECT_NEAR(reversed.x, dvrShade(gIndex, indexFromWorld * dWorld, normalFromIndex), 1e-12);
  EXPECT_NEAR(reversed.y, dvrSpecular(gIndex, indexFromWorld * dWorld, normalFromIndex, strength, power), 1e-12);
}

// A light kit's terms are its lights' weighted: one light of weight 1 is dvrShadeLit, the headlight of
// weight 1 the headlight's dvrShade and dvrSpecular, a kit whose lights are all the reversed ray the
// headlight again; weights adding up to 1 keep the emission's factor in [ambient, 1]; no gradient, no
// shading.
TEST(ReferenceDvr, ALightKitIsItsLightsWeighted) {
  constexpr double kTol = 1e-12;
  const glm::dmat3 indexFromWorld(glm::dvec3(4.0, 0.0, 0.0), glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.3, 2.0));
  const glm::dmat3 normalFromIndex = glm::transpose(indexFromWorld);
  const glm::dvec3 dWorld = glm::normalize(glm::dvec3(1.0, -0.4, 1.0)), dIndex = indexFromWorld * dWorld;
  const double strength = 0.7, power = 10.0;
  const glm::dvec3 a = glm::normalize(glm::dvec3(0.3, 0.8, -0.2)), b = glm::normalize(glm::dvec3(-0.9, 0.1, 0.4));
  for (const glm::dvec3& gIndex : {glm::dvec3(0.25, 0.5, -0.1), glm::dvec3(-1.0, 0.2, 3.0), glm::dvec3(0.0, 0.0, 0.7)}) {
    SCOPED_TRACE(testing::Message() << "gradient " << gIndex.x << ", " << gIndex.y << ", " << gIndex.z);
    const glm::dvec2 one = dvrShadeKit(gIndex, dIndex, normalFromIndex, {{a, 1.0}}, 0.0, -dWorld, strength, power);
    const glm::dvec2 lit = dvrShadeLit(gIndex, normalFromIndex, a, -dWorld, strength, power);
    EXPECT_NEAR(one.x, lit.x, kTol);
    EXPECT_NEAR(one.y, lit.y, kTol);
    const glm::dvec2 head = dvrShadeKit(gIndex, dIndex, normalFromIndex, {}, 1.0, -dWorld, strength, power);
    EXPECT_NEAR(head.x, dvrShade(gIndex, dIndex, normalFromIndex), kTol);
    EXPECT_NEAR(head.y, dvrSpecular(gIndex, dIndex, normalFromIndex, strength, power), kTol);
    const glm::dvec2 reversed =
        dvrShadeKit(gIndex, dIndex, normalFromIndex, {{-dWorld, 0.5}, {-dWorld, 0.2}}, 0.3, -dWorld, strength, power);
    EXPECT_NEAR(reversed.x, head.x, kTol);
    EXPECT_NEAR(reversed.y, head.y, kTol);
    // Weights 0.5, 0.3 and the head 0.2: between the ambient floor and 1, and the weighted sum of the
    // three lights' own terms.
    const glm::dvec2 kit = dvrShadeKit(gIndex, dIndex, normalFromIndex, {{a, 0.5}, {b, 0.3}}, 0.2, -dWorld, strength, power);
    EXPECT_GE(kit.x, kDvrShadingAmbient - kTol);
    EXPECT_LE(kit.x, 1.0 + kTol);
    const glm::dvec2 sum = 0.5 * lit + 0.3 * dvrShadeLit(gIndex, normalFromIndex, b, -dWorld, strength, power) + 0.2 * head;
    EXPECT_NEAR(kit.x, sum.x, kTol);
    EXPECT_NEAR(kit.y, sum.y, kTol);
  }
  EXPECT_EQ(dvrShadeKit(glm::dvec3(0.0), dIndex, normalFromIndex, {{a, 0.5}, {b, 0.3}}, 0.2, -dWorld, strength, power),
            glm::dvec2(1.0, 0.0));
}

// Through the sphere with the highlight: opacity and depth as without it, each colour channel up by
// the same amount (white light), by at most the strength times the opacity, and visibly somewhere.
TEST(ReferenceDvr, SpecularAddsWhiteLightOnly) {
  const TransferFunction tf({{0.0, glm::dvec3(0.2, 0.4, 0.9)}, {1.0, glm::dvec3(1.0, 0.8, 0.1)}}, {{0.0, 0.05}, {1.0, 0.0}});
  const DvrMedium medium = dvrMedium(tf, {kH, 1.0});
  const SphereScene scene(findReconstruction("boxspline"));
  DvrOptions shaded, lit;
  shaded.step = lit.step = 2e-3;
  shaded.shading = lit.shading = true;
  shaded.normalFromIndex = lit.normalFromIndex = glm::transpose(glm::dmat3(scene.indexFromWorld));
  lit.specular = 0.5;
  lit.specularPower = 4.0;
  int brighter = 0;
  for (const auto& [a, b] : pixelPairs(scene, medium, shaded, lit)) {
    EXPECT_EQ(a.rgba.a, b.rgba.a);
    EXPECT_EQ(a.depth, b.depth);
    const glm::dvec3 rise = glm::dvec3(b.rgba) - glm::dvec3(a.rgba);
    EXPECT_NEAR(rise.r, rise.g, 1e-12);
    EXPECT_NEAR(rise.r, rise.b, 1e-12);
    EXPECT_GE(rise.r, 0.0);
    EXPECT_LE(rise.r, lit.specular * b.rgba.a * (1.0 + 1e-12));
    brighter += rise.r > 0.01 * b.rgba.a;
  }
  EXPECT_GT(brighter, 6) << "the sphere's gradient lies along most rays somewhere";
}

}  // namespace
}  // namespace fcc
