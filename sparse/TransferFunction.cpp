#include "TransferFunction.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "Error.h"

namespace fcc {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// The function through points (x(i), y(i)), i < n, sorted by x: constant beyond the ends; at a step
// (equal x) the last point's value; between points a and b, a.y + (b.y - a.y) shape(a, u) at u in
// [0, 1] of the segment (u itself: piecewise linear).
template <typename Point, typename Value, typename Shape>
Value piecewise(const std::vector<Point>& points, double v, Value Point::*y, Shape shape) {
  const auto above = std::upper_bound(points.begin(), points.end(), v, [](double a, const Point& p) { return a < p.x; });
  if (above == points.begin()) return points.front().*y;
  if (above == points.end()) return points.back().*y;
  const Point& a = *(above - 1);
  const Point& b = *above;  // b.x > v >= a.x
  return a.*y + (b.*y - a.*y) * shape(a, (v - a.x) / (b.x - a.x));
}

template <typename Point>
void checkAbscissae(const std::vector<Point>& points, const char* what) {
  if (points.empty()) throw ValueError(std::string("a transfer function needs at least one ") + what + " point");
  for (size_t i = 0; i < points.size(); ++i) {
    if (!std::isfinite(points[i].x))
      throw ValueError(std::string(what) + " point " + std::to_string(i + 1) + " has a value (x) that is not finite");
    if (i > 0 && points[i].x < points[i - 1].x)
      throw ValueError(std::string(what) + " points must be sorted by value: point " + std::to_string(i + 1) + " (x = " +
                       number(points[i].x) + ") comes after x = " + number(points[i - 1].x));
  }
}

bool inUnit(double v) { return std::isfinite(v) && v >= 0.0 && v <= 1.0; }

}  // namespace

double paraViewSegmentShape(double u, double midpoint, double sharpness) {
  if (midpoint == 0.5 && sharpness == 0.0) return u;  // the straight line, exactly
  // vtkPiecewiseFunction's curve: u moved so that the midpoint lands at 1/2 (the midpoint kept off
  // the segment's ends, where the division degenerates, as VTK does), then ...
  const double m = std::clamp(midpoint, 1e-5, 1.0 - 1e-5);
  double s = u < m ? 0.5 * u / m : 0.5 + 0.5 * (u - m) / (1.0 - m);
  if (sharpness > 0.99) return s < 0.5 ? 0.0 : 1.0;  // ... a step there,
  if (sharpness < 0.01) return s;                   // ... a line through it,
  // ... or a Hermite curve with both end slopes (1 - sharpness) of the line's, s first pushed towards
  // the ends (the sharper, the flatter the curve there and the steeper about the midpoint).
  const double power = 1.0 + 10.0 * sharpness;
  if (s < 0.5) s = 0.5 * std::pow(2.0 * s, power);
  else if (s > 0.5) s = 1.0 - 0.5 * std::pow(2.0 * (1.0 - s), power);
  const double ss = s * s, sss = ss * s;
  const double h2 = -2.0 * sss + 3.0 * ss, h34 = 2.0 * sss - 3.0 * ss + s;  // h3 + h4 of VTK's curve
  return std::clamp(h2 + (1.0 - sharpness) * h34, 0.0, 1.0);
}

// --- Optics ---

void validateOpticalScale(const OpticalScale& scale) {
  if (!std::isfinite(scale.unitDistance) || !(scale.unitDistance > 0.0))
    throw ValueError("the unit distance must be a positive number of world units, not " + number(scale.unitDistance));
  if (!std::isfinite(scale.densityScale) || !(scale.densityScale >= 0.0))
    throw ValueError("the density scale must be a finite number >= 0, not " + number(scale.densityScale));
}

double extinctionFromOpacity(double alpha, const OpticalScale& scale) {
  const double a = std::clamp(alpha, 0.0, kMaxOpacity);
  if (a <= 0.0 || scale.densityScale == 0.0) return 0.0;
  return -std::log1p(-a) / scale.unitDistance * scale.densityScale;
}

double opacityOfSegment(double extinction, double length) { return -std::expm1(-extinction * length); }

// --- RangeQueries ---

RangeQueries::RangeQueries(std::vector<double> values) : values_(std::move(values)) {
  const int n = int(values_.size());
  nonZeroPrefix_.assign(size_t(n) + 1, 0);
  for (int i = 0; i < n; ++i) nonZeroPrefix_[size_t(i) + 1] = nonZeroPrefix_[size_t(i)] + (values_[size_t(i)] != 0.0);
  if (n == 0) return;
  levels_.push_back(values_);
  for (int width = 2; width <= n; width *= 2) {
    const std::vector<double>& below = levels_.back();
    std::vector<double> level(size_t(n - width + 1));
    for (int i = 0; i + width <= n; ++i) level[size_t(i)] = std::max(below[size_t(i)], below[size_t(i + width / 2)]);
    levels_.push_back(std::move(level));
  }
}

double RangeQueries::maxOn(int first, int last) const {
  first = std::max(first, 0);
  last = std::min(last, size() - 1);
  if (last < first) return 0.0;
  int k = 0;
  while ((2 << k) <= last - first + 1) ++k;
  const std::vector<double>& level = levels_[size_t(k)];
  return std::max(level[size_t(first)], level[size_t(last - (1 << k) + 1)]);
}

int RangeQueries::nonZeroOn(int first, int last) const {
  first = std::max(first, 0);
  last = std::min(last, size() - 1);
  if (last < first) return 0;
  return nonZeroPrefix_[size_t(last) + 1] - nonZeroPrefix_[size_t(first)];
}

// --- TransferFunction ---

TransferFunction::TransferFunction(std::vector<ColorPoint> colors, std::vector<OpacityPoint> opacities, std::string name,
                                   bool normalized)
    : colors_(std::move(colors)), opacities_(std::move(opacities)), name_(std::move(name)), normalized_(normalized) {
  checkAbscissae(colors_, "colour");
  checkAbscissae(opacities_, "opacity");
  for (size_t i = 0; i < colors_.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (!inUnit(colors_[i].rgb[c]))
        throw ValueError("colour point " + std::to_string(i + 1) + " (x = " + number(colors_[i].x) + ") has a component " +
                         number(colors_[i].rgb[c]) + " outside [0, 1]");
  std::vector<double> alphas(opacities_.size());
  for (size_t i = 0; i < opacities_.size(); ++i) {
    if (!inUnit(opacities_[i].alpha))
      throw ValueError("opacity point " + std::to_string(i + 1) + " (x = " + number(opacities_[i].x) + ") has an opacity " +
                       number(opacities_[i].alpha) + " outside [0, 1]");
    if (!inUnit(opacities_[i].midpoint) || !inUnit(opacities_[i].sharpness))
      throw ValueError("opacity point " + std::to_string(i + 1) + " (x = " + number(opacities_[i].x) + ") has midpoint " +
                       number(opacities_[i].midpoint) + " and sharpness " + number(opacities_[i].sharpness) +
                       "; each must lie in [0, 1]");
    alphas[i] = opacities_[i].alpha;
  }
  opacityQueries_ = RangeQueries(std::move(alphas));
}

double TransferFunction::domainMin() const { return std::min(colors_.front().x, opacities_.front().x); }
double TransferFunction::domainMax() const { return std::max(colors_.back().x, opacities_.back().x); }

glm::dvec3 TransferFunction::color(double v) const {
  return piecewise(colors_, v, &ColorPoint::rgb, [](const ColorPoint&, double u) { return u; });
}
double TransferFunction::opacity(double v) const {
  return piecewise(opacities_, v, &OpacityPoint::alpha,
                   [](const OpacityPoint& a, double u) { return paraViewSegmentShape(u, a.midpoint, a.sharpness); });
}

TransferFunction TransferFunction::stretchedTo(double lo, double hi) const {
  if (!std::isfinite(lo) || !std::isfinite(hi) || hi < lo)
    throw ValueError("a transfer function's range must be finite with min <= max, not [" + number(lo) + ", " + number(hi) +
                     "]");
  const double d0 = domainMin(), d1 = domainMax();
  auto map = [&](double x) {
    if (!(d1 > d0)) return lo;
    return std::clamp(lo + (x - d0) / (d1 - d0) * (hi - lo), lo, hi);
  };
  std::vector<ColorPoint> colors = colors_;
  std::vector<OpacityPoint> opacities = opacities_;
  for (ColorPoint& p : colors) p.x = map(p.x);
  for (OpacityPoint& p : opacities) p.x = map(p.x);
  return TransferFunction(std::move(colors), std::move(opacities), name_, false);
}

double TransferFunction::maxOpacityOn(double lo, double hi) const {
  if (std::isnan(lo) || std::isnan(hi)) return opacityQueries_.maxOn(0, opacityQueries_.size() - 1);
  if (hi < lo) std::swap(lo, hi);
  double m = std::max(opacity(lo), opacity(hi));
  const auto byX = [](const OpacityPoint& p, double v) { return p.x < v; };
  const int first = int(std::lower_bound(opacities_.begin(), opacities_.end(), lo, byX) - opacities_.begin());
  const int last =
      int(std::upper_bound(opacities_.begin(), opacities_.end(), hi, [](double v, const OpacityPoint& p) { return v < p.x; }) -
          opacities_.begin()) -
      1;
  return std::max(m, opacityQueries_.maxOn(first, last));
}

// --- Presets ---

namespace {

// Default opacity (ParaView's): a ramp from 0 to `top` over [0, 1].
std::vector<OpacityPoint> ramp(double top) { return {{0.0, 0.0}, {1.0, top}}; }

// matplotlib's colour maps (CC0), entries 0, 16, 32, ..., 240 and 255 of their 256, at x = entry / 255.
std::vector<ColorPoint> sampledMap(const double (&rgb)[17][3]) {
  std::vector<ColorPoint> points;
  for (int i = 0; i < 17; ++i) {
    const int entry = i < 16 ? 16 * i : 255;
    points.push_back({entry / 255.0, glm::dvec3(rgb[i][0], rgb[i][1], rgb[i][2])});
  }
  return points;
}

constexpr double kViridis[17][3] = {
    {0.267004, 0.004874, 0.329415}, {0.282327, 0.094955, 0.417331}, {0.278826, 0.175490, 0.483397},
    {0.258965, 0.251537, 0.524736}, {0.229739, 0.322361, 0.545706}, {0.199430, 0.387607, 0.554642},
    {0.172719, 0.448791, 0.557885}, {0.149039, 0.508051, 0.557250}, {0.127568, 0.566949, 0.550556},
    {0.120638, 0.625828, 0.533488}, {0.157851, 0.683765, 0.501686}, {0.246070, 0.738910, 0.452024},
    {0.369214, 0.788888, 0.382914}, {0.515992, 0.831158, 0.294279}, {0.678489, 0.863742, 0.189503},
    {0.845561, 0.887322, 0.099702}, {0.993248, 0.906157, 0.143936}};

constexpr double kInferno[17][3] = {
    {0.001462, 0.000466, 0.013866}, {0.042253, 0.028139, 0.141141}, {0.129285, 0.047293, 0.290788},
    {0.238273, 0.036621, 0.396353}, {0.341500, 0.062325, 0.429425}, {0.441207, 0.099338, 0.431594},
    {0.540920, 0.134729, 0.415123}, {0.640135, 0.171438, 0.381065}, {0.735683, 0.215906, 0.330245},
    {0.822386, 0.275197, 0.266085}, {0.894305, 0.353399, 0.193584}, {0.946965, 0.449191, 0.115272},
    {0.978422, 0.557937, 0.034931}, {0.987874, 0.675267, 0.065257}, {0.974638, 0.797692, 0.206332},
    {0.947594, 0.917399, 0.410665}, {0.988362, 0.998364, 0.644924}};

// CT in Hounsfield units, [0, 1] standing for [-1024, 3071] (a 12-bit scan): air and lung transparent,
// fat and soft tissue (-100 to 150 HU) faint and warm, bone (from 300 HU) opaque and white.
TransferFunction ctBone() {
  const auto hu = [](double h) { return (h + 1024.0) / 4095.0; };
  std::vector<ColorPoint> colors = {{0.0, {0.0, 0.0, 0.0}},           {hu(-300), {0.55, 0.25, 0.15}},
                                    {hu(-100), {0.73, 0.39, 0.25}},   {hu(40), {0.88, 0.60, 0.29}},
                                    {hu(150), {0.90, 0.72, 0.55}},    {hu(300), {1.0, 0.95, 0.85}},
                                    {hu(1000), {1.0, 1.0, 1.0}},      {1.0, {1.0, 1.0, 1.0}}};
  std::vector<OpacityPoint> opacities = {{0.0, 0.0},       {hu(-100), 0.0}, {hu(40), 0.01},  {hu(150), 0.01},
                                         {hu(300), 0.25},  {hu(1000), 0.6}, {1.0, 0.8}};
  return TransferFunction(std::move(colors), std::move(opacities), "ct-bone", true);
}

}  // namespace

const std::vector<std::string>& transferFunctionPresetNames() {
  static const std::vector<std::string> names = {"grayscale", "viridis", "inferno", "ct-bone", "fog"};
  return names;
}

bool isTransferFunctionPreset(std::string_view name) {
  const auto& names = transferFunctionPresetNames();
  return std::find(names.begin(), names.end(), name) != names.end();
}

TransferFunction transferFunctionPreset(std::string_view name) {
  if (name == "grayscale")
    return TransferFunction({{0.0, glm::dvec3(0.0)}, {1.0, glm::dvec3(1.0)}}, ramp(1.0), "grayscale", true);
  if (name == "viridis") return TransferFunction(sampledMap(kViridis), ramp(1.0), "viridis", true);
  if (name == "inferno") return TransferFunction(sampledMap(kInferno), ramp(1.0), "inferno", true);
  if (name == "ct-bone") return ctBone();
  if (name == "fog") return TransferFunction({{0.0, glm::dvec3(0.85, 0.87, 0.9)}}, ramp(0.2), "fog", true);
  std::string valid;
  for (const std::string& n : transferFunctionPresetNames()) valid += (valid.empty() ? "" : ", ") + n;
  throw ValueError("unknown transfer function preset '" + std::string(name) + "' (valid: " + valid +
                   "; or a .json or .txt file)");
}

// --- TransferTable ---

TransferTable::TransferTable(const TransferFunction& tf, double vmin, double vmax, int size, const OpticalScale& scale)
    : vmin_(vmin), vmax_(vmax) {
  if (size < 2) throw ValueError("a transfer function table needs at least 2 entries, not " + std::to_string(size));
  if (!std::isfinite(vmin) || !std::isfinite(vmax) || !(vmax > vmin))
    throw ValueError("a transfer function table's range must be finite with min < max, not [" + number(vmin) + ", " +
                     number(vmax) + "]");
  validateOpticalScale(scale);
  entries_.resize(size_t(size));
  std::vector<double> sigmas(static_cast<size_t>(size));
  // The function's colour at each entry: defined where the extinction is 0 too (the colour steps below).
  std::vector<glm::dvec3> colours(static_cast<size_t>(size));
  for (int i = 0; i < size; ++i) {
    const double v = i == size - 1 ? vmax : vmin + (vmax - vmin) * double(i) / double(size - 1);
    const double sigma = extinctionFromOpacity(tf.opacity(v), scale);
    colours[size_t(i)] = tf.color(v);
    entries_[size_t(i)] = glm::vec4(glm::vec3(sigma * colours[size_t(i)]), float(sigma));
    sigmas[size_t(i)] = double(entries_[size_t(i)].a);
  }
  std::vector<double> negated(sigmas.size());
  for (size_t i = 0; i < sigmas.size(); ++i) negated[i] = -sigmas[i];
  extinctionQueries_ = RangeQueries(std::move(sigmas));
  negatedExtinctionQueries_ = RangeQueries(std::move(negated));

  // The sub-step rule's measures: kinks from the float entries the GPU reads, colour steps from the
  // function's colours.
  const auto at = [&](int i) { return glm::dvec4(entries_[size_t(std::clamp(i, 0, size - 1))]); };
  const auto largest = [](const glm::dvec4& v) { return std::max(std::max(v.x, v.y), std::max(v.z, v.w)); };
  kinks_.resize(entries_.size());
  colourSteps_.assign(entries_.size(), 0.0);
  for (int i = 0; i < size; ++i) {
    kinks_[size_t(i)] = largest(glm::abs(at(i + 1) - 2.0 * at(i) + at(i - 1)));  // clamped: the flat extension
    if (i + 1 == size) break;
    const glm::dvec3 step = glm::abs(colours[size_t(i) + 1] - colours[size_t(i)]);
    colourSteps_[size_t(i)] = std::max(std::max(step.x, step.y), step.z);
  }
  kinkPrefix_.assign(entries_.size() + 1, 0.0);
  colourPrefix_.assign(entries_.size() + 1, 0.0);
  for (size_t i = 0; i < entries_.size(); ++i) {
    kinkPrefix_[i + 1] = kinkPrefix_[i] + kinks_[i];
    colourPrefix_[i + 1] = colourPrefix_[i] + colourSteps_[i];
  }
}

double TransferTable::position(double v) const {
  const double p = (v - vmin_) / (vmax_ - vmin_) * double(size() - 1);
  if (std::isnan(p)) return 0.0;
  return std::clamp(p, 0.0, double(size() - 1));
}

glm::vec4 TransferTable::lookup(double v) const {
  const double p = position(v);
  const int i = std::min(int(std::floor(p)), size() - 2);
  const float u = float(p - double(i));
  return entries_[size_t(i)] * (1.0f - u) + entries_[size_t(i) + 1] * u;
}

void TransferTable::entriesOn(double lo, double hi, int& first, int& last) const {
  if (std::isnan(lo) || std::isnan(hi)) {  // nothing known: every entry
    first = 0;
    last = size() - 1;
    return;
  }
  if (hi < lo) std::swap(lo, hi);
  first = int(std::floor(position(lo)));
  last = int(std::ceil(position(hi)));
}

bool TransferTable::zeroOn(double lo, double hi) const {
  int first, last;
  entriesOn(lo, hi, first, last);
  return extinctionQueries_.nonZeroOn(first, last) == 0;
}

double TransferTable::maxExtinctionOn(double lo, double hi) const {
  int first, last;
  entriesOn(lo, hi, first, last);
  return extinctionQueries_.maxOn(first, last);
}

double TransferTable::minExtinctionOn(double lo, double hi) const {
  int first, last;
  entriesOn(lo, hi, first, last);
  return -negatedExtinctionQueries_.maxOn(first, last);
}

void TransferTable::kinkEntriesOn(double lo, double hi, int& first, int& last) const {
  if (std::isnan(lo) || std::isnan(hi)) {  // nothing known: every entry
    first = 0;
    last = size() - 1;
    return;
  }
  if (hi < lo) std::swap(lo, hi);
  const double scale = double(size() - 1) / (vmax_ - vmin_);
  // Unclamped positions, kept within a step of the table so that the integers below stay small.
  const double pl = std::clamp((lo - vmin_) * scale, -1.0, double(size())), ph = std::clamp((hi - vmin_) * scale, -1.0, double(size()));
  first = std::max(int(std::floor(pl)) + 1, 0);
  last = std::min(int(std::ceil(ph)) - 1, size() - 1);
}

double TransferTable::kinkSumOn(double lo, double hi) const {
  int first, last;
  kinkEntriesOn(lo, hi, first, last);
  return last < first ? 0.0 : kinkPrefix_[size_t(last) + 1] - kinkPrefix_[size_t(first)];
}

double TransferTable::colourVariationOn(double lo, double hi) const {
  int first, last;
  entriesOn(lo, hi, first, last);
  return colourPrefix_[size_t(last)] - colourPrefix_[size_t(first)];
}

}  // namespace fcc
