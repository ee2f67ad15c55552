// The edit model behind the viewer's transfer-function editor (docs/VIEWER.md, "Transfer function"),
// free of any GUI so that it is tested on its own: the opacity control points (sorted by value, each
// inside the editor's value range, opacities in [0, 1]) with insert, move and remove, the colour map
// the function takes its colours from, and that map's colour points edited one by one (the same
// invariants: sorted, inside the range, components in [0, 1]; at least one), with undo and redo of
// every edit. The panel (viewer/PanelTransfer.cpp) turns mouse events into these calls; the session
// rebuilds the GPU's table when revision() changes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sparse/TransferFunction.h"

namespace fcc::render {

class TransferFunctionEditor {
 public:
  // Starts from `tf` (data values: a preset already fitted to the source, or a file's function), which
  // `spec` names (what --tf and the panel's combo call it: a preset, a file). Points may lie in [lo, hi]
  // widened to tf's domain (the panel passes its histogram's axis). ValueError unless lo <= hi, both
  // finite.
  TransferFunctionEditor(const TransferFunction& tf, double lo, double hi, std::string spec = "");

  double lo() const { return lo_; }
  double hi() const { return hi_; }
  // Points may lie in [lo, hi] too (another reconstruction's histogram axis): the function, the
  // history and the revision stay. ValueError unless lo <= hi, both finite.
  void widen(double lo, double hi);
  const std::vector<OpacityPoint>& points() const { return points_; }
  const std::vector<ColorPoint>& colors() const { return colors_; }
  const std::string& colorMapName() const { return colorMapName_; }
  // Counts every change that altered the function (a move to where a point already is does not).
  uint64_t revision() const { return revision_; }
  // The starting point the edits began from (reset's or start's spec), and whether the points or the
  // colours now differ from its: false again once the edits are undone or edited back.
  const std::string& spec() const { return base_.spec; }
  bool edited() const;

  // A new point at value x with opacity alpha, both clamped (x into [lo, hi], alpha into [0, 1]),
  // placed after the points already at its value (so it is the step's upper side). Returns its index.
  int insert(double x, double alpha);
  // Point i to (x, alpha), clamped: x into [lo, hi] and between its neighbours' values (a drag never
  // reorders the points, so i stays the dragged point), alpha into [0, 1]. ValueError for a bad i.
  void move(int i, double x, double alpha);
  // The shape of the segment from point i to the next (ParaView's midpoint and sharpness: docs/DVR.md,
  // "Files"), each clamped into [0, 1] (NaN: unchanged). ValueError for a bad i.
  void setShape(int i, double midpoint, double sharpness);
  // Removes point i, unless it is the last one (a function needs an opacity point): false then.
  // ValueError for a bad i.
  bool remove(int i);
  // The point nearest (x, alpha) within `radius`, distances measured as hypot((dx) * xScale,
  // (dalpha) * alphaScale) (the panel passes pixels per unit of value and of opacity); -1 if none.
  int pick(double x, double alpha, double xScale, double alphaScale, double radius) const;

  // Another colour map (data values, e.g. a preset fitted to the source, or a ParaView file's map);
  // the opacity points stay. ValueError for an empty list.
  void setColors(std::vector<ColorPoint> colors, std::string name);
  // The colour points one by one. insertColor: a new point at x (clamped into [lo, hi]) in the colour
  // the function has there, so that it changes nothing until moved or recoloured; after the points at
  // its value. Returns its index. moveColor: point i to x, clamped into [lo, hi] and between its
  // neighbours. setColor: point i's colour (linear, as the function's), each component clamped into
  // [0, 1] (NaN: unchanged). removeColor: false for the last one. pickColor: the point nearest x
  // within `radius` (|dx| * xScale), -1 if none. A bad i: ValueError. Each edit that changes the
  // colours marks the map's name " (edited)".
  int insertColor(double x);
  void moveColor(int i, double x);
  void setColor(int i, const glm::dvec3& rgb);
  bool removeColor(int i);
  int pickColor(double x, double xScale, double radius) const;

  // Another starting point: everything from `tf`, named `spec` (a preset or a file chosen in the panel),
  // as one undo step, so that choosing a preset by mistake loses no edits.
  void start(const TransferFunction& tf, std::string spec);
  // The same, forgetting the undo and redo history (another session's function, or an edit undone
  // because the session could not apply it).
  void reset(const TransferFunction& tf, std::string spec);

  // Undo and redo: each edit that changed the function is a step, except that the edits of one gesture
  // are one: a point inserted and then moved, or moved again and again (a drag), the same segment's
  // shape or the same colour point's colour set again and again (a slider held), until closeStep().
  // The panel closes the step when the mouse is released. undo() and redo() return false when there
  // is nothing to undo or redo; a new edit forgets what could be redone. At most kUndoSteps are kept.
  static constexpr std::size_t kUndoSteps = 256;
  void closeStep() { gesture_ = Gesture{}; }
  bool undo();
  bool redo();
  bool canUndo() const { return !undo_.empty(); }
  // Another file's editor's history before this one's, with that editor's function as one more undo
  // step: an undo brings back the function the other file had (in data values; the axis widens to its
  // points, as it does to every function restored). This editor's function, axis and starting point
  // stay; what could be redone is forgotten.
  void continueHistory(const TransferFunctionEditor& previous);
  bool canRedo() const { return !redo_.empty(); }

  // The function edited: colours and opacity points, in data values (not normalized), named `name` or
  // as the starting point's function was.
  TransferFunction function(const std::string& name) const;
  TransferFunction function() const { return function(base_.functionName); }

 private:
  void checkIndex(int i) const;
  void checkColorIndex(int i) const;
  void colorsEdited();
  double clampX(double x) const;
  // The starting point: its spec, its function's name, and its points and colours (for edited()).
  struct Base {
    std::string spec, functionName;
    std::vector<OpacityPoint> points;
    std::vector<ColorPoint> colors;
  };
  // What undo brings back, and the gesture the last step belongs to (kind 0: none, a new step).
  struct State {
    std::vector<OpacityPoint> points;
    std::vector<ColorPoint> colors;
    std::string colorMapName;
    Base base;
  };
  struct Gesture {
    int kind = 0;
    int index = -1;
    bool operator==(const Gesture& o) const { return kind == o.kind && index == o.index; }
  };
  enum : int { kMove = 1, kShape, kMoveColor, kSetColor };
  State state() const { return State{points_, colors_, colorMapName_, base_}; }
  void take(const TransferFunction& tf, std::string spec);  // start's and reset's change
  void restore(State s);
  // Before an edit that changes the function: a new undo step, unless `g` continues the last one.
  void record(Gesture g);
  void record() { record(Gesture{0, -1}); }
  std::vector<State> undo_, redo_;
  Gesture gesture_;
  std::vector<OpacityPoint> points_;
  std::vector<ColorPoint> colors_;
  std::string colorMapName_;
  Base base_;
  double lo_, hi_;
  uint64_t revision_ = 0;
};

}  // namespace fcc::render
