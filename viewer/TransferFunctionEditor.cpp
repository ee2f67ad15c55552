#include "TransferFunctionEditor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sparse/Error.h"

namespace fcc::render {

namespace {
void checkRange(double lo, double hi) {
  if (!(std::isfinite(lo) && std::isfinite(hi) && lo <= hi))
    throw ValueError("transfer function editor: value range [" + std::to_string(lo) + ", " + std::to_string(hi) +
                     "] is not a finite interval");
}
}  // namespace

TransferFunctionEditor::TransferFunctionEditor(const TransferFunction& tf, double lo, double hi, std::string spec) {
  checkRange(lo, hi);
  lo_ = std::min(lo, tf.domainMin());
  hi_ = std::max(hi, tf.domainMax());
  reset(tf, std::move(spec));
  revision_ = 0;
}

void TransferFunctionEditor::widen(double lo, double hi) {
  checkRange(lo, hi);
  lo_ = std::min(lo_, lo);
  hi_ = std::max(hi_, hi);
}

void TransferFunctionEditor::take(const TransferFunction& tf, std::string spec) {
  lo_ = std::min(lo_, tf.domainMin());
  hi_ = std::max(hi_, tf.domainMax());
  points_ = tf.opacities();
  colors_ = tf.colors();
  colorMapName_ = tf.name();
  base_ = Base{std::move(spec), tf.name(), points_, colors_};
  gesture_ = Gesture{};
  ++revision_;
}

void TransferFunctionEditor::start(const TransferFunction& tf, std::string spec) {
  record();
  take(tf, std::move(spec));
}

void TransferFunctionEditor::reset(const TransferFunction& tf, std::string spec) {
  undo_.clear();
  redo_.clear();
  take(tf, std::move(spec));
}

bool TransferFunctionEditor::edited() const { return points_ != base_.points || colors_ != base_.colors; }

void TransferFunctionEditor::record(Gesture g) {
  const bool continues = g.kind != 0 && g == gesture_;
  gesture_ = g;
  if (continues) return;
  undo_.push_back(state());
  if (undo_.size() > kUndoSteps) undo_.erase(undo_.begin());
  redo_.clear();
}

void TransferFunctionEditor::restore(State s) {
  points_ = std::move(s.points);
  colors_ = std::move(s.colors);
  colorMapName_ = std::move(s.colorMapName);
  base_ = std::move(s.base);
  gesture_ = Gesture{};
  ++revision_;
  // A step from another file's history may lie beyond this axis (continueHistory).
  for (const OpacityPoint& p : points_) lo_ = std::min(lo_, p.x), hi_ = std::max(hi_, p.x);
  for (const ColorPoint& c : colors_) lo_ = std::min(lo_, c.x), hi_ = std::max(hi_, c.x);
}

void TransferFunctionEditor::continueHistory(const TransferFunctionEditor& previous) {
  std::vector<State> steps = previous.undo_;
  steps.push_back(previous.state());
  steps.insert(steps.end(), undo_.begin(), undo_.end());
  if (steps.size() > kUndoSteps) steps.erase(steps.begin(), steps.end() - std::ptrdiff_t(kUndoSteps));
  undo_ = std::move(steps);
  redo_.clear();
  gesture_ = Gesture{};
}

bool TransferFunctionEditor::undo() {
  if (undo_.empty()) return false;
  redo_.push_back(state());
  State back = std::move(undo_.back());
  undo_.pop_back();
  restore(std::move(back));
  return true;
}

bool TransferFunctionEditor::redo() {
  if (redo_.empty()) return false;
  undo_.push_back(state());
  State again = std::move(redo_.back());
  redo_.pop_back();
  restore(std::move(again));
  return true;
}

void TransferFunctionEditor::checkIndex(int i) const {
  if (i < 0 || i >= int(points_.size()))
    throw ValueError("transfer function editor: no opacity point " + std::to_string(i) + " (there are " +
                     std::to_string(points_.size()) + ")");
}

double TransferFunctionEditor::clampX(double x) const {
  if (std::isnan(x)) return lo_;
  return std::clamp(x, lo_, hi_);
}

int TransferFunctionEditor::insert(double x, double alpha) {
  x = clampX(x);
  alpha = std::isnan(alpha) ? 0.0 : std::clamp(alpha, 0.0, 1.0);
  // After every point at or below x: the new point is a step's upper side where values are equal.
  const auto at = std::upper_bound(points_.begin(), points_.end(), x,
                                   [](double v, const OpacityPoint& p) { return v < p.x; });
  const int index = int(at - points_.begin());
  record();
  points_.insert(at, OpacityPoint{x, alpha});
  gesture_ = Gesture{kMove, index};  // a drag that follows is the same step
  ++revision_;
  return index;
}

void TransferFunctionEditor::move(int i, double x, double alpha) {
  checkIndex(i);
  const double below = i > 0 ? points_[std::size_t(i) - 1].x : lo_;
  const double above = i + 1 < int(points_.size()) ? points_[std::size_t(i) + 1].x : hi_;
  x = std::clamp(clampX(x), below, above);
  alpha = std::isnan(alpha) ? points_[std::size_t(i)].alpha : std::clamp(alpha, 0.0, 1.0);
  OpacityPoint& p = points_[std::size_t(i)];
  if (p.x == x && p.alpha == alpha) return;
  record(Gesture{kMove, i});
  p.x = x;  // its midpoint and sharpness (the shape of the segment to the next point) stay
  p.alpha = alpha;
  ++revision_;
}

void TransferFunctionEditor::setShape(int i, double midpoint, double sharpness) {
  checkIndex(i);
  OpacityPoint& p = points_[std::size_t(i)];
  midpoint = std::isnan(midpoint) ? p.midpoint : std::clamp(midpoint, 0.0, 1.0);
  sharpness = std::isnan(sharpness) ? p.sharpness : std::clamp(sharpness, 0.0, 1.0);
  if (p.midpoint == midpoint && p.sharpness == sharpness) return;
  record(Gesture{kShape, i});
  p.midpoint = midpoint;
  p.sharpness = sharpness;
  ++revision_;
}

bool TransferFunctionEditor::remove(int i) {
  checkIndex(i);
  if (points_.size() <= 1) return false;
  record();
  points_.erase(points_.begin() + i);
  ++revision_;
  return true;
}

int TransferFunctionEditor::pick(double x, double alpha, double xScale, double alphaScale, double radius) const {
  int best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < points_.size(); ++k) {
    const double d = std::hypot((points_[k].x - x) * xScale, (points_[k].alpha - alpha) * alphaScale);
    // Ties (points on one another, a step) go to the later point, drawn on top.
    if (d <= radius && d <= bestDistance) {
      best = int(k);
      bestDistance = d;
    }
  }
  return best;
}

void TransferFunctionEditor::checkColorIndex(int i) const {
  if (i < 0 || i >= int(colors_.size()))
    throw ValueError("transfer function editor: no colour point " + std::to_string(i) + " (there are " +
                     std::to_string(colors_.size()) + ")");
}

void TransferFunctionEditor::colorsEdited() {
  static const std::string kEdited = " (edited)";
  const bool marked = colorMapName_.size() >= kEdited.size() &&
                      colorMapName_.compare(colorMapName_.size() - kEdited.size(), kEdited.size(), kEdited) == 0;
  if (!marked) colorMapName_ += kEdited;
  ++revision_;
}

int TransferFunctionEditor::insertColor(double x) {
  x = clampX(x);
  const glm::dvec3 rgb = function("").color(x);
  const auto at = std::upper_bound(colors_.begin(), colors_.end(), x, [](double v, const ColorPoint& p) { return v < p.x; });
  const int index = int(at - colors_.begin());
  record();
  colors_.insert(at, ColorPoint{x, rgb});
  colorsEdited();
  gesture_ = Gesture{kMoveColor, index};
  return index;
}

void TransferFunctionEditor::moveColor(int i, double x) {
  checkColorIndex(i);
  const double below = i > 0 ? colors_[std::size_t(i) - 1].x : lo_;
  const double above = i + 1 < int(colors_.size()) ? colors_[std::size_t(i) + 1].x : hi_;
  x = std::clamp(clampX(x), below, above);
  ColorPoint& p = colors_[std::size_t(i)];
  if (p.x == x) return;
  record(Gesture{kMoveColor, i});
  p.x = x;
  colorsEdited();
}

void TransferFunctionEditor::setColor(int i, const glm::dvec3& rgb) {
  checkColorIndex(i);
  ColorPoint& p = colors_[std::size_t(i)];
  glm::dvec3 clamped = p.rgb;
  for (int c = 0; c < 3; ++c)
    if (!std::isnan(rgb[c])) clamped[c] = std::clamp(rgb[c], 0.0, 1.0);
  if (clamped == p.rgb) return;
  record(Gesture{kSetColor, i});
  p.rgb = clamped;
  colorsEdited();
}

bool TransferFunctionEditor::removeColor(int i) {
  checkColorIndex(i);
  if (colors_.size() <= 1) return false;
  record();
  colors_.erase(colors_.begin() + i);
  colorsEdited();
  return true;
}

int TransferFunctionEditor::pickColor(double x, double xScale, double radius) const {
  int best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < colors_.size(); ++k) {
    const double d = std::abs(colors_[k].x - x) * xScale;
    if (d <= radius && d <= bestDistance) {  // ties to the later point, drawn on top
      best = int(k);
      bestDistance = d;
    }
  }
  return best;
}

void TransferFunctionEditor::setColors(std::vector<ColorPoint> colors, std::string name) {
  if (colors.empty()) throw ValueError("transfer function editor: a colour map without points");
  record();
  colors_ = std::move(colors);
  colorMapName_ = std::move(name);
  ++revision_;
}

TransferFunction TransferFunctionEditor::function(const std::string& name) const {
  return TransferFunction(colors_, points_, name, /*normalized=*/false);
}

}  // namespace fcc::render
