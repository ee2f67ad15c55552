// Every reconstruction of the layer (sparse/Reconstruction.h) by its properties: the polynomials it
// claims to reproduce (and that it reproduces no more: the claim is tight), continuity across every
// piece boundary its cellSplits reports (and that those are all of them), symmetry under a reflection,
// and the ray fast paths the raycasters use (Bernstein coefficients along a segment, the first root)
// against plain evaluation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "SplineTestData.h"
#include "sparse/BccBilinear.h"
#include "sparse/BccShearedTrilinear.h"
#include "sparse/CcTricubic.h"
#include "sparse/CcTrilinear.h"
#include "sparse/Error.h"
#include "sparse/LatticeSamples.h"
#include "sparse/Reconstruction.h"

namespace fcc {
namespace {

using test::hashedCoefficient;
using test::str;

// A random polynomial of total degree `degree` in xyz / scale, with its gradient.
struct Polynomial {
  struct Term {
    int a, b, c;
    double k;
  };
  std::vector<Term> terms;
  double scale = 8.0;
  double operator()(const glm::dvec3& p) const {
    const glm::dvec3 q = p / scale;
    double v = 0.0;
    for (const Term& t : terms) v += t.k * std::pow(q.x, t.a) * std::pow(q.y, t.b) * std::pow(q.z, t.c);
    return v;
  }
  glm::dvec3 gradient(const glm::dvec3& p) const {
    const glm::dvec3 q = p / scale;
    glm::dvec3 g(0.0);
    auto pw = [](double x, int e) { return e <= 0 ? (e == 0 ? 1.0 : 0.0) : std::pow(x, e); };
    for (const Term& t : terms) {
      g.x += t.k * t.a * pw(q.x, t.a - 1) * pw(q.y, t.b) * pw(q.z, t.c);
      g.y += t.k * t.b * pw(q.x, t.a) * pw(q.y, t.b - 1) * pw(q.z, t.c);
      g.z += t.k * t.c * pw(q.x, t.a) * pw(q.y, t.b) * pw(q.z, t.c - 1);
    }
    return g / scale;
  }
};

// All monomials up to `degree`, random coefficients in [-1, 1]; those of degree exactly `degree`
// scaled up so that the top degree matters.
Polynomial randomPolynomial(int degree, uint32_t seed, double scale) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Polynomial p;
  p.scale = scale;
  for (int a = 0; a <= degree; ++a)
    for (int b = 0; a + b <= degree; ++b)
      for (int c = 0; a + b + c <= degree; ++c) p.terms.push_back({a, b, c, u(rng) * (a + b + c == degree ? 2.0 : 1.0)});
  return p;
}

// The samples of `f` on the reconstruction's lattice in a box around [-kRegion, kRegion]^3, prefiltered.
constexpr int kRegion = 6;
constexpr int kPad = 24;  // beyond the B-spline prefilter's reach and every stencil
template <class F>
LatticeSamples sampled(const ReconstructionInfo& info, F&& f) {
  LatticeSamples s(info.lattice, glm::ivec3(-kRegion - kPad), glm::ivec3(2 * (kRegion + kPad) + 1), 0.0f);
  s.fill([&](const glm::ivec3& ijk) { return float(f(glm::dvec3(ijk))); });
  s.prefilter(info.prefilter);
  return s;
}

struct Errors {
  double value = 0.0, gradient = 0.0;
};

Errors reproductionErrors(const ReconstructionInfo& info, const Polynomial& p) {
  const auto recon = makeReconstruction(info.name);
  const LatticeSamples samples = sampled(info, p);
  const SiteValue at = samples.accessor();
  test::PointSource points(7, -kRegion, kRegion);
  Errors e;
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 xyz = points.next();
    const auto r = recon->evaluate(xyz, at);
    e.value = std::max(e.value, std::abs(double(r.value) - p(glm::dvec3(xyz))));
    e.gradient = std::max(e.gradient, glm::length(glm::dvec3(r.gradient) - p.gradient(glm::dvec3(xyz))));
  }
  return e;
}

class EachReconstruction : public ::testing::TestWithParam<const ReconstructionInfo*> {};

// Float32 evaluation of O(1) values from O(1) coefficients (a 64-term sum at most).
constexpr double kReproductionTol = 2e-5;

TEST_P(EachReconstruction, ReproducesItsDegreeAndNoMore) {
  const ReconstructionInfo& info = *GetParam();
  for (int degree = 0; degree <= info.reproduces; ++degree) {
    const Polynomial p = randomPolynomial(degree, 11 + degree, 8.0);
    const Errors e = reproductionErrors(info, p);
    EXPECT_LT(e.value, kReproductionTol) << info.name << ": degree " << degree << " value";
    // The nearest-plane scheme's gradient has no component across its planes.
    if (info.continuity >= 0) {
      EXPECT_LT(e.gradient, kReproductionTol) << info.name << ": degree " << degree << " gradient";
    }
  }
  // One degree more is not reproduced: the error is far above round-off (a coarse scale makes it large).
  const Errors above = reproductionErrors(info, randomPolynomial(info.reproduces + 1, 29, 2.0));
  std::printf("[   INFO   ] %s: degree %d error %.3g (reproduces %d)\n", std::string(info.name).c_str(),
              info.reproduces + 1, above.value, info.reproduces);
  EXPECT_GT(above.value, 1e-3) << info.name << " reproduces degree " << info.reproduces + 1 << " too: its contract says "
                               << info.reproduces;
}

// A ray's boundaries in [0, tEnd]: unit-cell faces and the reconstruction's cuts inside each cell.
std::vector<float> boundariesAlong(const Reconstruction& recon, const glm::vec3& o, const glm::vec3& d, float tEnd) {
  std::vector<float> ts;
  for (int axis = 0; axis < 3; ++axis) {
    const float a = o[axis], b = o[axis] + tEnd * d[axis];
    for (float k = std::ceil(std::min(a, b)); k <= std::max(a, b); k += 1.0f) {
      const float t = (k - o[axis]) / d[axis];
      if (t > 0.0f && t < tEnd) ts.push_back(t);
    }
  }
  std::sort(ts.begin(), ts.end());
  std::vector<float> all = ts;
  float t0 = 0.0f;
  ts.push_back(tEnd);
  for (float t1 : ts) {
    const glm::ivec3 cell(glm::floor(o + (0.5f * (t0 + t1)) * d));
    const spline::FccSplits s = recon.cellSplits(cell, o, d, t0, t1);
    for (int i = 0; i < s.n; ++i) all.push_back(s.t[i]);
    t0 = t1;
  }
  std::sort(all.begin(), all.end());
  return all;
}

TEST_P(EachReconstruction, ContinuousAcrossEveryBoundaryAndTheSplitsAreComplete) {
  const ReconstructionInfo& info = *GetParam();
  const auto recon = makeReconstruction(info.name);
  recon->setView(glm::vec3(0.3f, -0.4f, 0.87f));
  const SiteValue at = [](const glm::ivec3& ijk) { return hashedCoefficient(ijk, 5); };
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  constexpr float kEta = 2e-3f, kTol = 2e-4f;
  double largestJump = 0.0;
  int boundaries = 0, pieces = 0;
  for (int ray = 0; ray < 60; ++ray) {
    const glm::vec3 o(4.0f * u(rng), 4.0f * u(rng), 4.0f * u(rng));
    const glm::vec3 d = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
    const float tEnd = 8.0f;
    const std::vector<float> ts = boundariesAlong(*recon, o, d, tEnd);
    for (size_t i = 0; i < ts.size(); ++i) {
      const float before = i == 0 ? 0.0f : ts[i - 1], after = i + 1 < ts.size() ? ts[i + 1] : tEnd;
      if (ts[i] - before < 2 * kEta || after - ts[i] < 2 * kEta) continue;  // a sliver: skip
      const glm::vec3 p = o + ts[i] * d;
      const auto lo = recon->evaluateInPiece(o + (ts[i] - kEta) * d, p, at);
      const auto hi = recon->evaluateInPiece(o + (ts[i] + kEta) * d, p, at);
      ++boundaries;
      largestJump = std::max(largestJump, double(std::abs(lo.value - hi.value)));
      if (info.continuity >= 0) {
        ASSERT_NEAR(lo.value, hi.value, kTol) << info.name << ": value jumps at " << str(p) << " on ray " << ray;
      }
      if (info.continuity >= 1) {
        ASSERT_LT(glm::length(lo.gradient - hi.gradient), kTol)
            << info.name << ": gradient jumps at " << str(p) << ": " << str(lo.gradient) << " vs " << str(hi.gradient);
      }
    }
    // Between consecutive boundaries one polynomial holds: no cut is missing.
    float t0 = 0.0f;
    std::vector<float> ends = ts;
    ends.push_back(tEnd);
    for (float t1 : ends) {
      if (t1 - t0 > 2 * kEta) {
        const glm::vec3 mid = o + (0.5f * (t0 + t1)) * d;
        for (float w : {0.1f, 0.9f}) {
          const glm::vec3 p = o + (t0 + w * (t1 - t0)) * d;
          const auto viaMid = recon->evaluateInPiece(mid, p, at);
          const auto own = recon->evaluate(p, at);
          ASSERT_NEAR(viaMid.value, own.value, kTol) << info.name << ": a piece boundary between " << str(mid) << " and "
                                                     << str(p) << " is missing from cellSplits";
        }
        ++pieces;
      }
      t0 = t1;
    }
  }
  std::printf("[   INFO   ] %s: %d boundaries, %d pieces, largest jump %.3g\n", std::string(info.name).c_str(), boundaries,
              pieces, largestJump);
  ASSERT_GT(boundaries, 500);
  if (info.continuity < 0) {
    EXPECT_GT(largestJump, 1e-2) << info.name << " claims to be discontinuous but is not";
  }
}

TEST_P(EachReconstruction, SymmetricUnderAReflection) {
  // Reflecting the data through x = 0 reflects the reconstruction (the view too, for the stack schemes).
  const ReconstructionInfo& info = *GetParam();
  const auto recon = makeReconstruction(info.name), mirrored = makeReconstruction(info.name);
  const glm::vec3 view(0.3f, -0.4f, 0.87f), flip(-1.0f, 1.0f, 1.0f);
  recon->setView(view);
  mirrored->setView(view * flip);
  const SiteValue at = [](const glm::ivec3& ijk) { return hashedCoefficient(ijk, 6); };
  const SiteValue atMirrored = [](const glm::ivec3& ijk) { return hashedCoefficient(ijk * glm::ivec3(-1, 1, 1), 6); };
  test::PointSource points(8, -5.0f, 5.0f);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 p = points.next();
    const auto a = recon->evaluate(p, at);
    const auto b = mirrored->evaluate(p * flip, atMirrored);
    // The nearest-plane scheme is discontinuous: a point within rounding of a step may land on either side.
    if (info.continuity < 0 && std::abs(a.value - b.value) > 1e-4f) continue;
    ASSERT_NEAR(a.value, b.value, 1e-5f) << info.name << " at " << str(p);
    ASSERT_LT(glm::length(a.gradient - b.gradient * flip), 1e-4f) << info.name << " at " << str(p);
  }
}

std::vector<const ReconstructionInfo*> allInfos() {
  std::vector<const ReconstructionInfo*> v;
  for (const auto& info : reconstructionInfos()) v.push_back(&info);
  return v;
}

INSTANTIATE_TEST_SUITE_P(Layer, EachReconstruction, ::testing::ValuesIn(allInfos()),
                         [](const ::testing::TestParamInfo<const ReconstructionInfo*>& p) {
                           std::string n(p.param->name);
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

TEST(ReconstructionLayer, UnknownNameListsTheValidOnes) {
  try {
    findReconstruction("tricubc");
    FAIL() << "no error";
  } catch (const ValueError& e) {
    EXPECT_NE(std::string(e.what()).find("valid: trilinear, tricubic"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("boxspline"), std::string::npos) << e.what();
  }
}

// The multi-affine blossom (trilinear, sheared trilinear, bilinear-spatial on the GPU) and the tricubic
// degree-9 form along a segment equal the function along it.
TEST(ReconstructionRay, SegmentBernsteinFormsEqualTheFunction) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int trial = 0; trial < 200; ++trial) {
    spline::FccCorners8 corners;
    for (float& v : corners.v) v = 2.0f * u(rng) - 1.0f;
    spline::FccCoeffs64 coeffs;
    for (float& v : coeffs.v) v = 2.0f * u(rng) - 1.0f;
    const spline::FccCoeffs64 bezier = spline::cc_tricubic_bezier(coeffs);
    const glm::vec3 fa(u(rng), u(rng), u(rng)), fb(u(rng), u(rng), u(rng));
    const float iso = 0.1f;
    const glm::vec4 b3 = spline::fcc_multiaffine_segment_bernstein(corners, fa, fb, iso);
    const spline::FccBernstein9 b9 = spline::cc_tricubic_segment_bernstein(bezier, fa, fb, iso);
    for (float w : {0.0f, 0.21f, 0.5f, 0.83f, 1.0f}) {
      const glm::vec3 f = fa + w * (fb - fa);
      ASSERT_NEAR(spline::fcc_bernstein3(b3, w) + iso, spline::fcc_multiaffine(corners, f), 1e-5f) << "trial " << trial;
      const float direct = spline::cc_tricubic_value_gradient(coeffs, glm::ivec3(0), f).value;
      ASSERT_NEAR(spline::fcc_bernstein9_at(b9, w) + iso, direct, 1e-5f) << "trial " << trial << " w " << w;
    }
    // The cell's Bezier coefficients bound the spline on it.
    const spline::FccRange range = spline::cc_tricubic_range(bezier);
    for (int i = 0; i < 20; ++i) {
      const float v = spline::cc_tricubic_value_gradient(coeffs, glm::ivec3(0), glm::vec3(u(rng), u(rng), u(rng))).value;
      ASSERT_GE(v, range.lo - 1e-6f);
      ASSERT_LE(v, range.hi + 1e-6f);
    }
  }
}

// The degree-9 first root against a dense scan of the same polynomial.
TEST(ReconstructionRay, FirstRootOfDegreeNineMatchesADenseScan) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int withRoot = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    spline::FccBernstein9 p;
    p.n = 9;
    const float shift = 0.8f * u(rng);
    for (float& b : p.b) b = u(rng) + shift;
    const float root = spline::fcc_first_root_bernstein9(p);
    // The first sign change on a fine grid.
    constexpr int kSteps = 20000;
    float firstChange = -1.0f;
    float prev = spline::fcc_bernstein9_at(p, 0.0f);
    for (int i = 1; i <= kSteps && firstChange < 0.0f; ++i) {
      const float v = spline::fcc_bernstein9_at(p, float(i) / kSteps);
      if ((v < 0.0f) != (prev < 0.0f)) firstChange = float(i) / kSteps;
      prev = v;
    }
    if (firstChange < 0.0f) {
      // No crossing on the grid: at most a tangent root, which must then be a near-zero.
      if (root >= 0.0f) {
        ASSERT_LT(std::abs(spline::fcc_bernstein9_at(p, root)), 1e-3f) << "trial " << trial;
      }
      continue;
    }
    ++withRoot;
    ASSERT_GE(root, 0.0f) << "trial " << trial << ": missed the root near " << firstChange;
    ASSERT_LE(root, firstChange + 1e-4f) << "trial " << trial << ": a later root";
    // Not before the first crossing, unless it is a root (touching zero) the grid stepped over.
    if (root < firstChange - 2.0f / kSteps) {
      ASSERT_LT(std::abs(spline::fcc_bernstein9_at(p, root)), 1e-4f) << "trial " << trial << " root " << root;
    }
  }
  ASSERT_GT(withRoot, 300);
}

}  // namespace
}  // namespace fcc
