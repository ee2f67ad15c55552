// Transfer functions for DVR (sparse/TransferFunction.h): evaluation through the control points,
// steps, presets and their stretch onto a range, the unit-distance convention, the GPU table against
// the evaluation, and the range queries behind skipping against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "sparse/Error.h"
#include "sparse/TransferFunction.h"

namespace fcc {
namespace {

// A random function on [-3, 5]: n points each list, some opacity runs of zeros, some steps.
// `shaped`: each opacity point also takes a random ParaView midpoint and sharpness (some a step).
TransferFunction randomFunction(std::mt19937_64& rng, int n, bool shaped = false) {
  std::uniform_real_distribution<double> x(-3.0, 5.0), u(0.0, 1.0);
  std::vector<double> xs(static_cast<size_t>(n));
  for (double& v : xs) v = x(rng);
  std::sort(xs.begin(), xs.end());
  for (int i = 1; i < n; ++i)
    if (u(rng) < 0.15 && (i < 2 || xs[size_t(i) - 1] != xs[size_t(i) - 2])) xs[size_t(i)] = xs[size_t(i) - 1];  // a step
  std::vector<ColorPoint> colors;
  std::vector<OpacityPoint> opacities;
  for (double v : xs) {
    colors.push_back({v, glm::dvec3(u(rng), u(rng), u(rng))});
    opacities.push_back({v, u(rng) < 0.5 ? 0.0 : u(rng)});
    if (shaped) {
      opacities.back().midpoint = u(rng);
      opacities.back().sharpness = u(rng) < 0.2 ? 1.0 : u(rng);
    }
  }
  return TransferFunction(colors, opacities, "random");
}

TEST(TransferFunction, InterpolationHitsControlPointsAndIsLinearBetween) {
  for (const std::string& name : transferFunctionPresetNames()) {
    const TransferFunction tf = transferFunctionPreset(name);
    const auto& c = tf.colors();
    for (size_t i = 0; i < c.size(); ++i) {
      if (i + 1 < c.size() && c[i + 1].x == c[i].x) continue;  // the left side of a step
      const glm::dvec3 rgb = tf.color(c[i].x);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(rgb[k], c[i].rgb[k], 1e-12) << name << " point " << i;
      if (i + 1 < c.size()) {
        const glm::dvec3 mid = tf.color(0.5 * (c[i].x + c[i + 1].x));
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(mid[k], 0.5 * (c[i].rgb[k] + c[i + 1].rgb[k]), 1e-12) << name;
      }
    }
    const auto& o = tf.opacities();
    for (size_t i = 0; i < o.size(); ++i) {
      if (i + 1 < o.size() && o[i + 1].x == o[i].x) continue;
      EXPECT_NEAR(tf.opacity(o[i].x), o[i].alpha, 1e-12) << name << " opacity point " << i;
      if (i + 1 < o.size()) {
        EXPECT_NEAR(tf.opacity(0.25 * o[i].x + 0.75 * o[i + 1].x), 0.25 * o[i].alpha + 0.75 * o[i + 1].alpha, 1e-12);
      }
    }
    // Beyond the points: the end values.
    EXPECT_EQ(tf.opacity(-10.0), o.front().alpha);
    EXPECT_EQ(tf.opacity(10.0), o.back().alpha);
    EXPECT_EQ(tf.color(10.0), c.back().rgb);
  }
}

TEST(TransferFunction, EqualValuesMakeAStepTakingTheLastPoint) {
  const TransferFunction tf({{0.0, glm::dvec3(0.0)}, {1.0, glm::dvec3(1.0)}},
                            {{0.0, 0.2}, {0.5, 0.2}, {0.5, 0.0}, {1.0, 0.0}});
  EXPECT_DOUBLE_EQ(tf.opacity(0.4999999), 0.2);
  EXPECT_DOUBLE_EQ(tf.opacity(0.5), 0.0);
  EXPECT_DOUBLE_EQ(tf.opacity(0.75), 0.0);
  // A closed range touching the step from the left sees its left value; one after it sees zero.
  EXPECT_DOUBLE_EQ(tf.maxOpacityOn(0.4, 0.5), 0.2);
  EXPECT_TRUE(tf.zeroOpacityOn(0.5000001, 3.0));
  EXPECT_FALSE(tf.zeroOpacityOn(0.3, 3.0));
}

// ParaView's opacity segments (vtkPiecewiseFunction's midpoint and sharpness): the line by default,
// bit for bit; otherwise from 0 to 1, a half at the midpoint, never decreasing, a step at sharpness 1,
// flatter at the ends the sharper; one value of VTK's curve worked by hand.
TEST(TransferFunction, ParaViewMidpointAndSharpnessShapeASegment) {
  for (int i = 0; i <= 100; ++i) EXPECT_EQ(paraViewSegmentShape(i / 100.0, 0.5, 0.0), i / 100.0);
  for (double midpoint : {0.0, 0.1, 0.3, 0.5, 0.8, 1.0})
    for (double sharpness : {0.0, 0.005, 0.3, 0.7, 0.98}) {
      SCOPED_TRACE("midpoint " + std::to_string(midpoint) + ", sharpness " + std::to_string(sharpness));
      EXPECT_NEAR(paraViewSegmentShape(0.0, midpoint, sharpness), 0.0, 1e-12);
      EXPECT_NEAR(paraViewSegmentShape(1.0, midpoint, sharpness), 1.0, 1e-12);
      if (midpoint > 0.0 && midpoint < 1.0) {
        EXPECT_NEAR(paraViewSegmentShape(midpoint, midpoint, sharpness), 0.5, 1e-12);
      }
      double previous = 0.0;
      for (int i = 0; i <= 1000; ++i) {
        const double shape = paraViewSegmentShape(i / 1000.0, midpoint, sharpness);
        ASSERT_GE(shape, previous - 1e-12) << "at u = " << i / 1000.0;  // rounding aside
        ASSERT_LE(shape, 1.0);
        previous = shape;
      }
    }
  // The midpoint alone moves the line's knee: 0.25 -> a half at u = 0.25, 0.75 at u = 0.625.
  EXPECT_DOUBLE_EQ(paraViewSegmentShape(0.125, 0.25, 0.0), 0.25);
  EXPECT_DOUBLE_EQ(paraViewSegmentShape(0.625, 0.25, 0.0), 0.75);
  // Sharpness 1: a step at the midpoint.
  EXPECT_EQ(paraViewSegmentShape(0.3 - 1e-9, 0.3, 1.0), 0.0);
  EXPECT_EQ(paraViewSegmentShape(0.3, 0.3, 1.0), 1.0);
  // Sharper: flatter near the ends.
  EXPECT_LT(paraViewSegmentShape(0.1, 0.5, 0.7), paraViewSegmentShape(0.1, 0.5, 0.3));
  EXPECT_LT(paraViewSegmentShape(0.1, 0.5, 0.3), 0.1);
  // u = 0.25, midpoint 0.5, sharpness 0.5: s = 0.5 (2 u)^6 = 1/128, then the Hermite curve with end
  // slopes half the line's: 3 s^2 - 2 s^3 + 0.5 (2 s^3 - 3 s^2 + s) = 0.0039973259.
  EXPECT_NEAR(paraViewSegmentShape(0.25, 0.5, 0.5), 0.0039973259, 1e-10);

  // In a function: the segment from the point that holds the shape.
  const std::vector<ColorPoint> gray = {{0.0, glm::dvec3(0.0)}, {1.0, glm::dvec3(1.0)}};
  const TransferFunction tf(gray, {{2.0, 0.2, 0.25, 0.6}, {6.0, 1.0}, {10.0, 0.0, 0.5, 1.0}, {12.0, 0.5}});
  EXPECT_NEAR(tf.opacity(3.0), 0.6, 1e-12);  // a quarter of the way: halfway between 0.2 and 1
  EXPECT_DOUBLE_EQ(tf.opacity(8.0), 0.5);     // the next segment is the line from 1 to 0
  EXPECT_EQ(tf.opacity(10.999), 0.0);         // a step at 11
  EXPECT_EQ(tf.opacity(11.0), 0.5);
}

TEST(TransferFunction, InvalidPointsAreValueErrors) {
  const std::vector<ColorPoint> gray = {{0.0, glm::dvec3(0.0)}, {1.0, glm::dvec3(1.0)}};
  EXPECT_THROW(TransferFunction({}, {{0.0, 1.0}}), ValueError);
  EXPECT_THROW(TransferFunction(gray, {}), ValueError);
  EXPECT_THROW(TransferFunction(gray, {{1.0, 0.5}, {0.0, 0.5}}), ValueError);  // decreasing
  EXPECT_THROW(TransferFunction(gray, {{0.0, 1.5}}), ValueError);              // opacity > 1
  EXPECT_THROW(TransferFunction({{0.0, glm::dvec3(0.0, -0.1, 0.0)}}, {{0.0, 0.5}}), ValueError);
  EXPECT_THROW(TransferFunction(gray, {{std::nan(""), 0.5}}), ValueError);
  EXPECT_THROW(TransferFunction(gray, {{0.0, 0.5, 1.5, 0.0}}), ValueError);           // midpoint > 1
  EXPECT_THROW(TransferFunction(gray, {{0.0, 0.5, 0.5, -0.1}}), ValueError);          // sharpness < 0
  EXPECT_THROW(TransferFunction(gray, {{0.0, 0.5, std::nan(""), 0.0}}), ValueError);  // midpoint NaN
  try {
    TransferFunction(gray, {{0.0, 0.1}, {2.0, 0.5}, {1.0, 0.5}});
    FAIL() << "no error";
  } catch (const ValueError& e) {
    EXPECT_NE(std::string(e.what()).find("sorted"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
  }
}

TEST(TransferFunction, PresetsByNameAndUnknownNamesListTheValidOnes) {
  const std::vector<std::string> expected = {"grayscale", "viridis", "inferno", "ct-bone", "fog"};
  EXPECT_EQ(transferFunctionPresetNames(), expected);
  for (const std::string& name : expected) {
    const TransferFunction tf = transferFunctionPreset(name);
    EXPECT_EQ(tf.name(), name);
    EXPECT_TRUE(tf.normalized());
    EXPECT_EQ(tf.domainMin(), 0.0) << name;
    EXPECT_EQ(tf.domainMax(), 1.0) << name;
    EXPECT_TRUE(isTransferFunctionPreset(name));
    // Transparent at the bottom, so empty space skips.
    EXPECT_EQ(tf.opacity(0.0), 0.0) << name;
    EXPECT_GT(tf.maxOpacityOn(0.0, 1.0), 0.0) << name;
  }
  // matplotlib's end colours.
  EXPECT_NEAR(transferFunctionPreset("viridis").color(0.0).g, 0.004874, 1e-12);
  EXPECT_NEAR(transferFunctionPreset("inferno").color(1.0).b, 0.644924, 1e-12);
  EXPECT_EQ(transferFunctionPreset("fog").color(0.3), transferFunctionPreset("fog").color(0.9));  // constant colour
  try {
    transferFunctionPreset("virdis");
    FAIL() << "no error";
  } catch (const ValueError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("virdis"), std::string::npos);
    for (const std::string& name : expected) EXPECT_NE(what.find(name), std::string::npos) << what;
  }
  EXPECT_FALSE(isTransferFunctionPreset("virdis"));
}

TEST(TransferFunction, StretchMapsTheDomainOntoTheRange) {
  for (const std::string& name : transferFunctionPresetNames()) {
    const TransferFunction tf = transferFunctionPreset(name);
    const double lo = -1024.0, hi = 3071.0;
    const TransferFunction s = tf.stretchedTo(lo, hi);
    EXPECT_FALSE(s.normalized());
    EXPECT_EQ(s.domainMin(), lo);
    EXPECT_EQ(s.domainMax(), hi);
    for (int i = 0; i <= 100; ++i) {
      const double u = i / 100.0;
      EXPECT_NEAR(s.opacity(lo + u * (hi - lo)), tf.opacity(u), 1e-9) << name << " at " << u;
      const glm::dvec3 a = s.color(lo + u * (hi - lo)), b = tf.color(u);
      EXPECT_NEAR(glm::length(a - b), 0.0, 1e-9) << name << " at " << u;
    }
  }
  const TransferFunction g = transferFunctionPreset("grayscale");
  EXPECT_EQ(g.stretchedTo(2.0, 2.0).domainMin(), 2.0);  // a single value: every point there
  EXPECT_THROW(g.stretchedTo(1.0, 0.0), ValueError);
  EXPECT_THROW(g.stretchedTo(0.0, INFINITY), ValueError);
}

TEST(TransferFunction, UnitDistanceConvention) {
  for (double unit : {0.01, 0.5, 1.0, 7.0}) {
    for (double alpha : {0.0, 0.01, 0.3, 0.9, 0.999}) {
      const OpticalScale scale{unit, 1.0};
      const double sigma = extinctionFromOpacity(alpha, scale);
      // A segment one unit distance long has the opacity of the transfer function.
      EXPECT_NEAR(opacityOfSegment(sigma, unit), alpha, 1e-12) << unit << " " << alpha;
      // Two half segments compose to the same: 1 - (1 - a_half)^2 = alpha.
      const double half = opacityOfSegment(sigma, unit / 2.0);
      EXPECT_NEAR(1.0 - (1.0 - half) * (1.0 - half), alpha, 1e-12);
      // The density scale multiplies the extinction: a scale of 2 is two segments.
      EXPECT_NEAR(opacityOfSegment(extinctionFromOpacity(alpha, {unit, 2.0}), unit), 1.0 - (1.0 - alpha) * (1.0 - alpha),
                  1e-12);
    }
  }
  // alpha = 1 is clamped to a finite extinction.
  EXPECT_TRUE(std::isfinite(extinctionFromOpacity(1.0, {1.0, 1.0})));
  EXPECT_NEAR(opacityOfSegment(extinctionFromOpacity(1.0, {1.0, 1.0}), 1.0), kMaxOpacity, 1e-12);
  EXPECT_EQ(extinctionFromOpacity(0.5, {1.0, 0.0}), 0.0);
  EXPECT_THROW(validateOpticalScale({0.0, 1.0}), ValueError);
  EXPECT_THROW(validateOpticalScale({-1.0, 1.0}), ValueError);
  EXPECT_THROW(validateOpticalScale({1.0, -1.0}), ValueError);
  EXPECT_THROW(validateOpticalScale({std::nan(""), 1.0}), ValueError);
}

TEST(RangeQueries, AgreeWithBruteForce) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n : {1, 2, 3, 7, 64, 100}) {
    std::vector<double> values(static_cast<size_t>(n));
    for (double& v : values) v = u(rng) < 0.4 ? 0.0 : u(rng);
    const RangeQueries q(values);
    for (int a = -2; a < n + 2; ++a)
      for (int b = a - 1; b < n + 2; ++b) {
        double m = 0.0;
        int nz = 0;
        for (int i = std::max(a, 0); i <= std::min(b, n - 1); ++i) m = std::max(m, values[size_t(i)]), nz += values[size_t(i)] != 0.0;
        ASSERT_EQ(q.maxOn(a, b), m) << n << " [" << a << ", " << b << "]";
        ASSERT_EQ(q.nonZeroOn(a, b), nz);
      }
  }
}

TEST(TransferFunction, RangeQueriesAgreeWithBruteForceOnRandomRanges) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(-4.0, 6.0);
  const OpticalScale scale{0.5, 1.0};
  int zeros = 0, nonZeros = 0;
  for (int f = 0; f < 40; ++f) {
    const TransferFunction tf = randomFunction(rng, 2 + f % 12, /*shaped=*/f % 2 == 1);
    for (int r = 0; r < 200; ++r) {
      double lo = x(rng), hi = x(rng);
      if (r % 4 == 0) hi = lo + 0.05 * (hi - lo);  // short ranges too
      if (hi < lo) std::swap(lo, hi);
      // Brute force: dense samples, every point inside and just left of it (a step's left side).
      double brute = std::max(tf.opacity(lo), tf.opacity(hi));
      for (int i = 0; i <= 400; ++i) brute = std::max(brute, tf.opacity(lo + (hi - lo) * i / 400.0));
      for (const OpacityPoint& p : tf.opacities())
        if (p.x >= lo && p.x <= hi) brute = std::max({brute, tf.opacity(p.x), tf.opacity(std::max(lo, p.x - 1e-12))});
      const double query = tf.maxOpacityOn(lo, hi);
      ASSERT_NEAR(query, brute, 1e-9) << "function " << f << " on [" << lo << ", " << hi << "]";
      ASSERT_EQ(tf.zeroOpacityOn(lo, hi), brute == 0.0) << "function " << f << " on [" << lo << ", " << hi << "]";
      ASSERT_NEAR(tf.maxExtinctionOn(lo, hi, scale), extinctionFromOpacity(brute, scale), 1e-8);
      ASSERT_EQ(tf.maxOpacityOn(hi, lo), query);  // swapped bounds
      (brute == 0.0 ? zeros : nonZeros)++;
    }
  }
  EXPECT_GT(zeros, 100);  // both answers were exercised
  EXPECT_GT(nonZeros, 100);
}

TEST(TransferTable, EntriesAreTheEvaluationAndLookupsInterpolateThem) {
  const TransferFunction tf = transferFunctionPreset("viridis").stretchedTo(-2.0, 3.0);
  const OpticalScale scale{0.25, 1.5};
  const TransferTable table(tf, -2.0, 3.0, 256, scale);
  ASSERT_EQ(table.size(), 256);
  for (int i = 0; i < table.size(); ++i) {
    const double v = -2.0 + 5.0 * i / 255.0;
    const double sigma = extinctionFromOpacity(tf.opacity(v), scale);
    const glm::vec4 e = table.entries()[size_t(i)];
    ASSERT_NEAR(e.a, sigma, 1e-6 * (1.0 + sigma)) << i;
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(e[k], sigma * tf.color(v)[k], 1e-6 * (1.0 + sigma)) << i;
    const glm::vec4 l = table.lookup(v);
    for (int k = 0; k < 4; ++k) ASSERT_NEAR(l[k], e[k], 1e-5 * (1.0 + sigma)) << i;
  }
  // Between entries the table interpolates the extinction linearly, the function the opacity: they
  // differ most where the opacity nears 1 (sigma = -ln(1 - alpha) is steep there), but little in what is
  // seen, the opacity of a unit segment.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 3.0);
  const TransferTable fine(tf, -2.0, 3.0, 4096, scale);
  for (int i = 0; i < 2000; ++i) {
    const double v = u(rng);
    const double sigma = extinctionFromOpacity(tf.opacity(v), scale);
    ASSERT_NEAR(opacityOfSegment(fine.lookup(v).a, scale.unitDistance), opacityOfSegment(sigma, scale.unitDistance), 1e-3)
        << v;
  }
  EXPECT_EQ(table.lookup(-100.0), table.entries().front());
  EXPECT_EQ(table.lookup(100.0), table.entries().back());
  EXPECT_THROW(TransferTable(tf, 0.0, 0.0, 256, scale), ValueError);
  EXPECT_THROW(TransferTable(tf, 0.0, 1.0, 1, scale), ValueError);
  EXPECT_THROW(TransferTable(tf, 0.0, 1.0, 16, OpticalScale{0.0, 1.0}), ValueError);
}

// What the DVR sub-step rule (shaders/dvr.glsl's dvrSteps) takes from the table, checked as properties
// of the lookups it stands for over [lo, hi]: the lookup at the midpoint of two values there is off
// the straight line between their lookups by at most the kinks' sum times a quarter of their distance
// in entries (so exactly on it where the sum is 0: the lookups are linear there), and the colours (rgb,
// not premultiplied) of two lookups there differ by at most the colour variation.
TEST(TransferTable, KinksAndColourStepsBoundTheLookups) {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int linear = 0, kinked = 0;
  for (int f = 0; f < 24; ++f) {
    const TransferFunction tf = f < 20 ? randomFunction(rng, 3 + f)
                                       : transferFunctionPreset(transferFunctionPresetNames()[size_t(f - 20)]).stretchedTo(-3.0, 5.0);
    const TransferTable table(tf, -3.0, 5.0, 32 + 11 * f, {0.5, 1.0});
    const double entryWidth = 8.0 / (table.size() - 1);
    for (int r = 0; r < 400; ++r) {
      double lo = -3.5 + 9.0 * unit(rng), hi = lo + (r % 2 ? 0.05 : 2.0) * unit(rng);
      const double kink = table.kinkSumOn(lo, hi), colourVariation = table.colourVariationOn(lo, hi);
      const double v1 = lo + (hi - lo) * unit(rng), v2 = lo + (hi - lo) * unit(rng);
      const glm::dvec4 a(table.lookup(v1)), b(table.lookup(v2)), mid(table.lookup(0.5 * (v1 + v2)));
      const double spanEntries = std::abs(v2 - v1) / entryWidth;
      const glm::dvec4 off = glm::abs(mid - 0.5 * (a + b));
      const double rounding = 1e-5 * (1.0 + std::max(std::max(a.w, b.w), mid.w));
      const double bound = kink * spanEntries / 4.0 + rounding;
      for (int c = 0; c < 4; ++c)
        ASSERT_LE(off[c], bound) << "function " << f << ", channel " << c << ", v " << v1 << ", " << v2 << " in [" << lo
                                 << ", " << hi << "]: kinks " << kink;
      (kink == 0.0 ? linear : kinked)++;
      if (a.w > 0.0 && b.w > 0.0) {
        const glm::dvec3 colourStepOff = glm::abs(glm::dvec3(b) / b.w - glm::dvec3(a) / a.w);
        const double most = colourVariation + 1e-5;
        for (int c = 0; c < 3; ++c)
          ASSERT_LE(colourStepOff[c], most) << "function " << f << ", v " << v1 << ", " << v2 << ": colour variation "
                                            << colourVariation;
      }
    }
  }
  EXPECT_GT(linear, 50);  // both cases met (random functions have flat and straight runs)
  EXPECT_GT(kinked, 1000);
}

TEST(TransferTable, RangeQueriesAgreeWithBruteForceOverLookups) {
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> x(-5.0, 7.0);
  int zeros = 0, nonZeros = 0;
  for (int f = 0; f < 20; ++f) {
    const TransferFunction tf = randomFunction(rng, 3 + f);
    const TransferTable table(tf, -3.0, 5.0, 64 + 7 * f, {0.5, 1.0});
    for (int r = 0; r < 300; ++r) {
      double lo = x(rng), hi = x(rng);
      if (r % 3 == 0) hi = lo + 0.02 * (hi - lo);
      if (hi < lo) std::swap(lo, hi);
      // The lookups over [lo, hi] are linear between entries: their largest is at lo, hi or an entry inside.
      double brute = std::max(table.lookup(lo).a, table.lookup(hi).a);
      for (int i = 0; i < table.size(); ++i) {
        const double v = -3.0 + 8.0 * i / (table.size() - 1);
        if (v >= lo && v <= hi) brute = std::max(brute, double(table.entries()[size_t(i)].a));
      }
      ASSERT_EQ(table.zeroOn(lo, hi), brute == 0.0) << f << " [" << lo << ", " << hi << "]";
      // The max query is an upper bound: the largest entry the lookups involve.
      int first, last;
      table.entriesOn(lo, hi, first, last);
      double entries = 0.0;
      for (int i = first; i <= last; ++i) entries = std::max(entries, double(table.entries()[size_t(i)].a));
      ASSERT_EQ(table.maxExtinctionOn(lo, hi), entries);
      double smallest = 1e300;
      for (int i = first; i <= last; ++i) smallest = std::min(smallest, double(table.entries()[size_t(i)].a));
      ASSERT_EQ(table.minExtinctionOn(lo, hi), smallest);
      const std::vector<int>& prefix = table.nonZeroPrefix();
      ASSERT_EQ(prefix[size_t(last) + 1] == prefix[size_t(first)], table.zeroOn(lo, hi));
      ASSERT_GE(table.maxExtinctionOn(lo, hi), brute * (1.0 - 1e-6));  // float interpolation rounds
      (brute == 0.0 ? zeros : nonZeros)++;
    }
  }
  EXPECT_GT(zeros, 100);
  EXPECT_GT(nonZeros, 100);
}

}  // namespace
}  // namespace fcc
