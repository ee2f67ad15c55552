// The measurement behind `fccvdb compare`: the analytic fields' gradients, equal-density sampling,
// the reference raycaster's exactness (spheres from every reconstruction that reproduces quadratics;
// the interpolation bound for the others), and the comparison's rows.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "SplineTestData.h"
#include "sparse/Comparison.h"
#include "sparse/Error.h"
#include "sparse/LatticeSamples.h"
#include "sparse/ReferenceRaycast.h"

namespace fcc {
namespace {

TEST(AnalyticFields, GradientsMatchCentralDifferences) {
  for (const std::string& name : analyticFieldNames()) {
    const auto field = makeAnalyticField(name, 3);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int i = 0; i < 500; ++i) {
      const glm::dvec3 p(u(rng), u(rng), u(rng));
      constexpr double h = 1e-6;
      glm::dvec3 fd;
      for (int a = 0; a < 3; ++a) {
        glm::dvec3 e(0.0);
        e[a] = h;
        fd[a] = (field->value(p + e) - field->value(p - e)) / (2 * h);
      }
      const glm::dvec3 g = field->gradient(p);
      ASSERT_LT(glm::length(g - fd), 1e-6 * (1.0 + glm::length(g))) << name << " at " << p.x << " " << p.y << " " << p.z;
    }
  }
  EXPECT_THROW(makeAnalyticField("marschner"), ValueError);
}

TEST(Comparison, EveryLatticeGetsTheBudgetsDensity) {
  for (int64_t budget : {4000, 100000, 1000000}) {
    for (Lattice lattice : {Lattice::Cc, Lattice::Bcc, Lattice::Fcc}) {
      const LatticeSampling s = samplingFor(lattice, budget);
      // Density: budget / 8 sites per unit of world volume.
      EXPECT_NEAR(latticeDensity(lattice) / std::pow(s.worldPerIndex, 3.0), budget / 8.0, 1e-6 * budget);
      // The sites counted in the closed domain differ from the budget only by its boundary: a few
      // percent at large budgets (at 4000, up to 16%: one layer of 15 is a big share).
      if (budget >= 100000) {
        EXPECT_NEAR(double(s.samples), double(budget), 0.06 * budget) << latticeName(lattice) << " " << budget;
      }
    }
  }
}

TEST(Comparison, BudgetsBeyondMemoryAreRefusedInOneLine) {
  try {
    samplingFor(Lattice::Bcc, 200000000);
    FAIL() << "no error";
  } catch (const ValueError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bcc lattice"), std::string::npos) << what;
    // The budget it suggests fits.
    const size_t at = what.find("use budgets up to ");
    ASSERT_NE(at, std::string::npos) << what;
    const int64_t suggested = std::stoll(what.substr(at + 18));
    EXPECT_GT(suggested, 5000000);
    EXPECT_NO_THROW(samplingFor(Lattice::Bcc, suggested));
  }
}

TEST(Comparison, IsosurfacePointsLieOnTheIsosurface) {
  const auto field = makeAnalyticField("marschner-lobb");
  const auto points = isosurfacePoints(*field, 0.5, 300, 9);
  ASSERT_EQ(points.size(), 300u);
  for (const auto& p : points) {
    EXPECT_NEAR(field->value(p), 0.5, 1e-10);
    EXPECT_LE(std::abs(p.x), 0.95);
  }
}

// E, the largest error of each scheme that does not reproduce quadratics on f = |p|^2 (index units):
// an interpolant that is linear along an edge e misses the parabola by at most |e|^2 / 4 there.
double valueErrorBoundForSquaredRadius(std::string_view name) {
  if (name == "trilinear") return 3 * 0.25;                      // unit edges along x, y, z
  if (name == "tricubic-bspline") return 1.0;                     // exactly: sum of 1/3 per axis (its 2nd moment)
  if (name == "type6") return 3 * 0.25;                           // exactly: each pure square gains 1/4 (test_type6)
  if (name == "barycentric") return 1.25;                         // the Delaunay tetrahedron's circumradius^2
  if (name == "sheared-trilinear") return (4 + 4 + 3) * 0.25;     // edges (2,0,0), (0,2,0), (+-1,+-1,1)
  if (name == "bilinear-spatial") return (4 + 4) * 0.25 + 0.25;   // in-plane spacing 2, plane distance 1
  if (name == "bilinear") return (4 + 4) * 0.25 + 2 * 9.5 * 0.5;  // in-plane, and the step: z off by 1/2
  return 0.0;
}

// A sphere of radius r about c, the field |p - c|^2 sampled on each lattice: the reference raycaster's
// hit against the exact ray-sphere intersection.
TEST(ReferenceRaycast, SpheresAreExactWhereQuadraticsAreReproduced) {
  const glm::dvec3 c(0.3, -0.2, 0.1);
  const double r = 9.0;
  for (const ReconstructionInfo& info : reconstructionInfos()) {
    LatticeSamples samples(info.lattice, glm::ivec3(-40), glm::ivec3(81), 0.0f);
    samples.fill([&](const glm::ivec3& ijk) {
      const glm::dvec3 q = glm::dvec3(ijk) - c;
      return float(glm::dot(q, q));
    });
    samples.prefilter(info.prefilter);
    const CellBounds bounds(samples);
    const auto recon = makeReconstruction(info.name);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    double worst = 0.0;
    int hits = 0;
    for (int i = 0; i < 300; ++i) {
      // Aimed within r / 2 of the centre: the ray meets the sphere at 30 degrees from its normal at most.
      const glm::vec3 target = glm::vec3(c) + 0.5f * float(r) * std::abs(u(rng)) * glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
      const glm::vec3 o = glm::vec3(c) + 30.0f * glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
      const glm::vec3 d = glm::normalize(target - o);
      recon->setView(d);
      const RayHit hit = firstHit(*recon, samples.accessor(), bounds, o, d, 0.0f, 60.0f, float(r * r));
      // Exact: t^2 + 2 t (o - c).d + |o - c|^2 - r^2 = 0, first root.
      const glm::dvec3 oc = glm::dvec3(o) - c, dd(d);
      const double b = glm::dot(oc, dd), disc = b * b - (glm::dot(oc, oc) - r * r);
      if (disc <= 1.0) continue;  // grazing rays: skip
      const double tExact = -b - std::sqrt(disc);
      ASSERT_TRUE(hit.hit) << info.name << ": ray " << i << " missed the sphere";
      worst = std::max(worst, std::abs(double(hit.t) - tExact));
      ++hits;
    }
    // Quadratic reproduction: exact up to float rounding. Otherwise the stated bound: the interpolant of
    // |p|^2 is off by at most E (below), so the radius by about E / 2r, the hit by that over the cosine of
    // the hit angle (>= cos 30 degrees), with 10% for the approximation of the square root.
    const double bound = info.reproduces >= 2 ? 2e-4 : 1.1 * valueErrorBoundForSquaredRadius(info.name) / (2 * r) / 0.866;
    std::printf("[   INFO   ] %s: worst |t - t_exact| %.3g over %d hits (bound %.3g)\n", std::string(info.name).c_str(),
                worst, hits, bound);
    EXPECT_GT(hits, 200);
    EXPECT_LT(worst, bound) << info.name;
  }
}

TEST(Comparison, RowsAreCompleteAndConvergentMethodsImprove) {
  const auto field = makeAnalyticField("random-waves", 2);
  CompareOptions options;
  options.budgets = {4000, 64000};
  options.iso = 0.0;
  options.points = 2000;
  options.width = options.height = 24;
  const std::vector<CompareRow> rows = compareReconstructions(*field, options);
  ASSERT_EQ(rows.size(), 2 * reconstructionInfos().size());
  for (const CompareRow& row : rows) {
    EXPECT_TRUE(std::isfinite(row.valueRmsError) && row.valueRmsError > 0.0) << row.reconstruction;
    EXPECT_LE(row.valueRmsError, row.valueMaxError) << row.reconstruction;
    EXPECT_GE(row.normalErrorP95Deg, 0.0);
    EXPECT_EQ(row.surfacePoints, 2000);
    EXPECT_TRUE(row.renderNormalErrorMeanDeg.has_value()) << row.reconstruction;
    EXPECT_EQ(row.shaded.rgb.size(), 24u * 24u * 3u);
    EXPECT_FALSE(row.fps.has_value());
  }
  // Sixteen times the samples: every continuous method's value error falls.
  const size_t n = reconstructionInfos().size();
  for (size_t i = 0; i < n; ++i) {
    if (reconstructionInfos()[i].continuity < 0) continue;
    EXPECT_LT(rows[n + i].valueRmsError, rows[i].valueRmsError) << rows[i].reconstruction;
  }
  CompareOptions unknown = options;
  unknown.reconstructions = {"tricubix"};
  EXPECT_THROW(compareReconstructions(*field, unknown), ValueError);
}

}  // namespace
}  // namespace fcc
