// The transfer function of direct volume rendering (issue 18; docs/DVR.md): colour and opacity as
// piecewise-linear functions of the data value, the presets, the optical convention that turns an
// opacity into an extinction, the sampled table the GPU reads, and the range queries behind empty-space
// skipping ("is the opacity zero everywhere on [lo, hi]?", "the largest extinction there").
//
// The convention is ParaView's scalar-opacity unit distance: an opacity alpha is the opacity of a
// segment `unitDistance` world units long, i.e. the extinction is sigma = -ln(1 - alpha) / unitDistance
// per world unit (times the density scale), and colour is emitted in proportion to it (premultiplied:
// emission per unit length = sigma * rgb). A segment of length L with constant sigma and rgb then has
// opacity 1 - exp(-sigma L) and colour rgb (1 - exp(-sigma L)).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace fcc {

struct ColorPoint {
  double x;        // data value
  glm::dvec3 rgb;  // each in [0, 1]
  bool operator==(const ColorPoint& o) const { return x == o.x && rgb == o.rgb; }
  bool operator!=(const ColorPoint& o) const { return !(*this == o); }
};

// ParaView's opacity point: the midpoint and sharpness shape the segment from this point to the next
// (vtkPiecewiseFunction's curve: docs/DVR.md, "Files"); 0.5 and 0 are a straight line.
struct OpacityPoint {
  double x;                 // data value
  double alpha;             // in [0, 1]: the opacity of a segment one unit distance long
  double midpoint = 0.5;    // in [0, 1]: where in the segment the opacity is halfway between the two
  double sharpness = 0.0;   // in [0, 1]: 0 linear, up to 1 a step at the midpoint
  bool operator==(const OpacityPoint& o) const {
    return x == o.x && alpha == o.alpha && midpoint == o.midpoint && sharpness == o.sharpness;
  }
  bool operator!=(const OpacityPoint& o) const { return !(*this == o); }
};

// The shape of a segment from 0 to 1 under ParaView's midpoint and sharpness, at u in [0, 1] of it:
// 0 at 0, 1 at 1, a half at the midpoint (below sharpness 0.99; a step there above), never
// decreasing. Exactly u for midpoint 0.5 and sharpness 0.
double paraViewSegmentShape(double u, double midpoint, double sharpness);

// The largest opacity taken as such; above it alpha is clamped (alpha = 1 would be an infinite
// extinction): a unit segment of it is 1 - 1e-6 opaque, sigma = ln(1e6) / unitDistance = 13.8 / unit.
inline constexpr double kMaxOpacity = 1.0 - 1e-6;

// Opacity -> extinction per world unit: -ln(1 - min(alpha, kMaxOpacity)) / unitDistance * densityScale.
struct OpticalScale {
  double unitDistance = 1.0;  // world units (the CLI's default: the grid's voxel size)
  double densityScale = 1.0;  // multiplies every extinction (0: transparent)
};
// ValueError for a unit distance that is not finite and positive, or a density scale that is not
// finite and non-negative.
void validateOpticalScale(const OpticalScale& scale);
double extinctionFromOpacity(double alpha, const OpticalScale& scale);
// The opacity of a segment of `length` world units with constant extinction: 1 - exp(-sigma length).
double opacityOfSegment(double extinction, double length);

// The largest value over ranges of a fixed array in O(1) (a sparse table: log2(n) levels of maxima
// of power-of-two windows), and the count of non-zero values by a prefix sum.
class RangeQueries {
 public:
  RangeQueries() = default;
  explicit RangeQueries(std::vector<double> values);
  int size() const { return int(values_.size()); }
  // Over the indices [first, last] (clamped to the array; empty when last < first: 0).
  double maxOn(int first, int last) const;
  int nonZeroOn(int first, int last) const;
  // prefix[i] = the count of non-zero values among [0, i), size() + 1 of them.
  const std::vector<int>& nonZeroPrefix() const { return nonZeroPrefix_; }
  // The sparse table maxOn reads: levels()[k][i] = max of the values [i, i + 2^k), size() - 2^k + 1 of
  // them at level k.
  const std::vector<std::vector<double>>& levels() const { return levels_; }

 private:
  std::vector<double> values_;
  std::vector<std::vector<double>> levels_;  // levels_[k][i] = max of values_[i, i + 2^k)
  std::vector<int> nonZeroPrefix_;           // count of non-zero values_[0, i)
};

// Colour and opacity over data values, each piecewise linear between its control points (sorted by x;
// points at one x make a step: the value at that x is the last one's), the opacity shaped by each
// point's midpoint and sharpness as ParaView shapes it (linear by default); outside the points' range
// each keeps its end value. Immutable once made.
class TransferFunction {
 public:
  // ValueError: no colour or no opacity point, x not finite or decreasing, a colour, opacity, midpoint
  // or sharpness outside [0, 1] or not finite.
  TransferFunction(std::vector<ColorPoint> colors, std::vector<OpacityPoint> opacities, std::string name = "",
                   bool normalized = false);

  const std::string& name() const { return name_; }
  // Presets are defined on [0, 1] and meant to be stretched onto the data's range (stretchedTo);
  // a file's points are data values (normalized() false).
  bool normalized() const { return normalized_; }
  const std::vector<ColorPoint>& colors() const { return colors_; }
  const std::vector<OpacityPoint>& opacities() const { return opacities_; }
  // The smallest and largest x of all points.
  double domainMin() const;
  double domainMax() const;

  glm::dvec3 color(double v) const;
  double opacity(double v) const;
  glm::dvec4 rgba(double v) const { return glm::dvec4(color(v), opacity(v)); }

  // The same function with its domain [domainMin, domainMax] mapped affinely onto [lo, hi] (the
  // colour and opacity points together); normalized() is false afterwards. ValueError unless lo and
  // hi are finite with lo <= hi. A single-valued domain, or lo == hi, puts every point at lo (steps
  // there keep their order).
  TransferFunction stretchedTo(double lo, double hi) const;

  // Exact range queries on the opacity over the closed interval [lo, hi] (lo <= hi; swapped otherwise;
  // a NaN bound: the whole function), O(log n): the largest opacity (at lo, at hi or at a control point
  // inside: both sides of a step inside count; each segment is monotone between its points, whatever
  // its midpoint and sharpness), and whether it is zero everywhere.
  double maxOpacityOn(double lo, double hi) const;
  bool zeroOpacityOn(double lo, double hi) const { return maxOpacityOn(lo, hi) <= 0.0; }
  double maxExtinctionOn(double lo, double hi, const OpticalScale& scale) const {
    return extinctionFromOpacity(maxOpacityOn(lo, hi), scale);
  }

 private:
  std::vector<ColorPoint> colors_;
  std::vector<OpacityPoint> opacities_;
  std::string name_;
  bool normalized_;
  RangeQueries opacityQueries_;  // over opacities_[i].alpha
};

// The presets, all on [0, 1] (normalized): "grayscale" (black to white), "viridis", "inferno"
// (matplotlib's, 17 points each), "ct-bone" (CT: soft tissue faint and warm, bone opaque and white;
// see docs/DVR.md for the Hounsfield units it assumes), "fog" (one colour, opacity rising with the
// value). Every preset but ct-bone has ParaView's default opacity, a ramp from 0 to 1.
const std::vector<std::string>& transferFunctionPresetNames();
bool isTransferFunctionPreset(std::string_view name);
// ValueError listing the valid names for an unknown one.
TransferFunction transferFunctionPreset(std::string_view name);

// The transfer function sampled for the GPU: `size` entries over [vmin, vmax], entry i at the value
// vmin + i (vmax - vmin) / (size - 1), each (sigma r, sigma g, sigma b, sigma): extinction per world
// unit in alpha and premultiplied emission per world unit in rgb (OpticalScale applied). A value
// between entries is their linear interpolation (a texture of `size` texels with linear filtering,
// read at texel coordinate (v - vmin) / (vmax - vmin) * (size - 1) + 0.5, clamped to the edge: values
// outside [vmin, vmax] take the end entries). A segment of length L at an interpolated entry e has
// opacity 1 - exp(-e.a L) and colour (e.rgb / e.a) (1 - exp(-e.a L)) (e.rgb L where e.a is 0).
class TransferTable {
 public:
  // ValueError: size < 2, vmin/vmax not finite or vmax <= vmin, a bad OpticalScale.
  TransferTable(const TransferFunction& tf, double vmin, double vmax, int size, const OpticalScale& scale);

  double vmin() const { return vmin_; }
  double vmax() const { return vmax_; }
  int size() const { return int(entries_.size()); }
  // size() RGBA32F texels, as uploaded.
  const std::vector<glm::vec4>& entries() const { return entries_; }
  // The interpolated entry at v, as the GPU reads it.
  glm::vec4 lookup(double v) const;
  // The entries the lookups over [lo, hi] interpolate: from the one at or below lo to the one at or
  // above hi (clamped); lo <= hi (swapped otherwise).
  void entriesOn(double lo, double hi, int& first, int& last) const;
  // Whether every lookup in [lo, hi] has zero extinction (then it emits nothing either), O(1) by a
  // prefix count of non-zero entries: a brick or cell whose value range this holds for is skipped.
  bool zeroOn(double lo, double hi) const;
  // The largest extinction of a lookup in [lo, hi] (an upper bound: the largest entry involved), O(1).
  double maxExtinctionOn(double lo, double hi) const;
  // For a shader that answers zeroOn itself: size() + 1 counts, prefix[i] = non-zero entries among
  // [0, i); entries [first, last] are all zero iff prefix[last + 1] == prefix[first].
  const std::vector<int>& nonZeroPrefix() const { return extinctionQueries_.nonZeroPrefix(); }
  // For a shader that answers maxExtinctionOn itself: RangeQueries::levels of the entries' extinction.
  const std::vector<std::vector<double>>& extinctionMaxLevels() const { return extinctionQueries_.levels(); }

  // What the DVR sub-step rule needs of the table besides the largest extinction (docs/DVR.md, "How
  // many sub-steps"), over the lookups in [lo, hi]:
  // - minExtinctionOn: the smallest extinction of the entries they read (a lower bound), O(1);
  // - kinkSumOn: the slope changes they cross, at the entries strictly inside [lo, hi] (positions in
  //   entries, not clamped), each entry's the largest over the four channels of |e[i+1] - 2 e[i] +
  //   e[i-1]| (per world unit, as the entries; past the ends the lookup is constant, so the end
  //   entries' are |e[1] - e[0]| and |e[n-1] - e[n-2]|, crossed where [lo, hi] reaches past them): 0
  //   where the lookups are linear in v;
  // - colourVariationOn: how far the function's colour (rgb, not premultiplied; largest channel) moves
  //   from entry to entry over the pairs the lookups interpolate (entriesOn's first to last): an upper
  //   bound of the lookups' colour change, whose e.rgb / e.a lies between its two entries' colours.
  double minExtinctionOn(double lo, double hi) const;
  double kinkSumOn(double lo, double hi) const;
  double colourVariationOn(double lo, double hi) const;
  // The entries strictly inside [lo, hi] (kinkSumOn's), as first..last (last < first: none).
  void kinkEntriesOn(double lo, double hi, int& first, int& last) const;
  // The per-entry terms those sum (size() each; colourSteps()[i] is the step from entry i to i + 1),
  // for a shader that sums them itself.
  const std::vector<double>& kinks() const { return kinks_; }
  const std::vector<double>& colourSteps() const { return colourSteps_; }
  // RangeQueries::levels of the entries' negated extinction (minExtinctionOn's sparse table).
  const std::vector<std::vector<double>>& negatedExtinctionMaxLevels() const { return negatedExtinctionQueries_.levels(); }

 private:
  double position(double v) const;  // in entries, clamped to [0, size - 1]
  double vmin_, vmax_;
  std::vector<glm::vec4> entries_;
  RangeQueries extinctionQueries_, negatedExtinctionQueries_;
  std::vector<double> kinks_, colourSteps_;
  std::vector<double> kinkPrefix_, colourPrefix_;  // size() + 1 sums of the first i terms
};

}  // namespace fcc
