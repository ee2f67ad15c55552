// The viewer's transfer-function edit model (viewer/TransferFunctionEditor.h): points stay sorted,
// inside the value range and [0, 1] whatever is asked, and the function made from them is what the
// points say.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sparse/Error.h"
#include "viewer/TransferFunctionEditor.h"

namespace fcc {
namespace {

using render::TransferFunctionEditor;

TransferFunction viridisOn(double lo, double hi) { return transferFunctionPreset("viridis").stretchedTo(lo, hi); }

// The invariants every edit keeps.
void expectValid(const TransferFunctionEditor& e) {
  ASSERT_FALSE(e.points().empty());
  for (std::size_t i = 0; i < e.points().size(); ++i) {
    const OpacityPoint& p = e.points()[i];
    EXPECT_GE(p.x, e.lo());
    EXPECT_LE(p.x, e.hi());
    EXPECT_GE(p.alpha, 0.0);
    EXPECT_LE(p.alpha, 1.0);
    if (i > 0) {
      EXPECT_LE(e.points()[i - 1].x, p.x) << "point " << i << " out of order";
    }
  }
}

TEST(TransferFunctionEditor, StartsFromTheFunctionAndGivesItBack) {
  const TransferFunction tf = viridisOn(2.0, 6.0);
  TransferFunctionEditor e(tf, 0.0, 8.0);
  EXPECT_EQ(e.lo(), 0.0);
  EXPECT_EQ(e.hi(), 8.0);
  const TransferFunction back = e.function("edited");
  EXPECT_FALSE(back.normalized());
  for (double v = -1.0; v <= 9.0; v += 0.137) {
    EXPECT_EQ(back.opacity(v), tf.opacity(v)) << v;
    EXPECT_EQ(back.color(v), tf.color(v)) << v;
  }
  // A range narrower than the function widens to hold its points.
  TransferFunctionEditor narrow(tf, 3.0, 4.0);
  EXPECT_EQ(narrow.lo(), 2.0);
  EXPECT_EQ(narrow.hi(), 6.0);
  EXPECT_THROW(TransferFunctionEditor(tf, 1.0, 0.0), ValueError);
}

TEST(TransferFunctionEditor, InsertKeepsOrderClampsAndChangesTheFunctionThere) {
  TransferFunctionEditor e(viridisOn(0.0, 1.0), 0.0, 1.0);
  const uint64_t before = e.revision();
  const int i = e.insert(0.25, 0.9);
  EXPECT_GT(e.revision(), before);
  expectValid(e);
  EXPECT_EQ(e.points()[std::size_t(i)].x, 0.25);
  EXPECT_EQ(e.function("f").opacity(0.25), 0.9) << "the function passes through the new point";
  // Outside the range and [0, 1]: clamped, not refused.
  const int low = e.insert(-5.0, -1.0), high = e.insert(7.0, 3.0);
  expectValid(e);
  EXPECT_EQ(e.points()[std::size_t(low)].x, 0.0);
  EXPECT_EQ(e.points()[std::size_t(low)].alpha, 0.0);
  EXPECT_EQ(e.points()[std::size_t(high)].x, 1.0);
  EXPECT_EQ(e.points()[std::size_t(high)].alpha, 1.0);
  // At a value already taken: after it, so the new point is the step's upper side.
  const int step = e.insert(0.25, 0.1);
  EXPECT_EQ(e.points()[std::size_t(step) - 1].x, 0.25);
  EXPECT_EQ(e.function("f").opacity(0.25), 0.1) << "the value at a step is its last point's";
}

TEST(TransferFunctionEditor, MoveStaysBetweenTheNeighboursAndInsideTheRange) {
  TransferFunctionEditor e(viridisOn(0.0, 10.0), 0.0, 10.0);  // points at 0 and 10
  const int mid = e.insert(5.0, 0.5);
  ASSERT_EQ(mid, 1);
  e.move(mid, 7.5, 0.25);
  EXPECT_EQ(e.points()[1].x, 7.5);
  EXPECT_EQ(e.points()[1].alpha, 0.25);
  e.move(mid, 20.0, 2.0);  // past the last point: stops at it
  EXPECT_EQ(e.points()[1].x, 10.0);
  EXPECT_EQ(e.points()[1].alpha, 1.0);
  e.move(mid, -3.0, -0.5);
  EXPECT_EQ(e.points()[1].x, 0.0);
  EXPECT_EQ(e.points()[1].alpha, 0.0);
  e.move(0, -7.0, 0.3);  // the first point: the range's low end
  EXPECT_EQ(e.points()[0].x, 0.0);
  expectValid(e);
  const uint64_t r = e.revision();
  e.move(0, e.points()[0].x, e.points()[0].alpha);
  EXPECT_EQ(e.revision(), r) << "a move to where the point is changes nothing";
  EXPECT_THROW(e.move(5, 0.0, 0.0), ValueError);
  EXPECT_THROW(e.move(-1, 0.0, 0.0), ValueError);
}

// A ParaView function's point keeps its midpoint and sharpness (the shape of its segment) when dragged.
TEST(TransferFunctionEditor, MoveKeepsAPointsParaViewShape) {
  const TransferFunction shaped({{0.0, glm::dvec3(0.0)}, {10.0, glm::dvec3(1.0)}},
                                {{0.0, 0.0, 0.25, 0.6}, {10.0, 1.0}});
  TransferFunctionEditor e(shaped, 0.0, 10.0);
  e.move(0, 2.0, 0.1);
  EXPECT_EQ(e.points()[0].midpoint, 0.25);
  EXPECT_EQ(e.points()[0].sharpness, 0.6);
  EXPECT_NEAR(e.function("edited").opacity(4.0), 0.55, 1e-12);  // halfway at the midpoint of [2, 10]
  const int added = e.insert(5.0, 0.5);  // a new point is ParaView's line
  EXPECT_EQ(e.points()[std::size_t(added)].midpoint, 0.5);
  EXPECT_EQ(e.points()[std::size_t(added)].sharpness, 0.0);
}

// The panel's shape sliders: a segment's midpoint and sharpness, clamped, NaN leaving one as it was.
TEST(TransferFunctionEditor, SetShapeShapesTheSegmentToTheNextPoint) {
  TransferFunctionEditor e(viridisOn(0.0, 10.0), 0.0, 10.0);  // points at 0 (opacity 0) and 10 (1)
  const uint64_t r = e.revision();
  e.setShape(0, 0.25, 0.0);
  EXPECT_GT(e.revision(), r);
  EXPECT_NEAR(e.function("shaped").opacity(2.5), 0.5, 1e-12);  // halfway at a quarter of the way
  e.setShape(0, std::nan(""), 2.0);
  EXPECT_EQ(e.points()[0].midpoint, 0.25);
  EXPECT_EQ(e.points()[0].sharpness, 1.0);
  EXPECT_EQ(e.function("step").opacity(2.4), 0.0);
  EXPECT_EQ(e.function("step").opacity(2.5), 1.0);
  const uint64_t same = e.revision();
  e.setShape(0, 0.25, 1.0);
  EXPECT_EQ(e.revision(), same) << "no change, no revision";
  EXPECT_THROW(e.setShape(2, 0.5, 0.0), ValueError);
}

TEST(TransferFunctionEditor, RemoveKeepsAtLeastOnePoint) {
  TransferFunctionEditor e(viridisOn(0.0, 1.0), 0.0, 1.0);
  const int i = e.insert(0.5, 1.0);
  EXPECT_TRUE(e.remove(i));
  EXPECT_EQ(e.points().size(), 2u);
  EXPECT_NEAR(e.function("f").opacity(0.5), 0.5, 1e-12) << "the ramp is back";
  EXPECT_TRUE(e.remove(0));
  const uint64_t r = e.revision();
  EXPECT_FALSE(e.remove(0)) << "the last point stays";
  EXPECT_EQ(e.revision(), r);
  EXPECT_EQ(e.points().size(), 1u);
  EXPECT_THROW(e.remove(3), ValueError);
}

TEST(TransferFunctionEditor, PickFindsTheNearestPointWithinTheRadius) {
  TransferFunctionEditor e(viridisOn(0.0, 100.0), 0.0, 100.0);  // (0, 0) and (100, 1)
  e.insert(50.0, 0.5);
  // 2 pixels per value unit, 100 pixels per unit of opacity.
  EXPECT_EQ(e.pick(51.0, 0.52, 2.0, 100.0, 5.0), 1);
  EXPECT_EQ(e.pick(53.0, 0.5, 2.0, 100.0, 5.0), -1) << "6 pixels away";
  EXPECT_EQ(e.pick(99.0, 0.99, 2.0, 100.0, 5.0), 2);
  EXPECT_EQ(e.pick(25.0, 0.25, 2.0, 100.0, 5.0), -1);
}

TEST(TransferFunctionEditor, ColourMapChangesColoursOnly) {
  TransferFunctionEditor e(viridisOn(0.0, 1.0), 0.0, 1.0);
  e.insert(0.3, 0.7);
  const TransferFunction before = e.function("f");
  const TransferFunction inferno = transferFunctionPreset("inferno");
  e.setColors(inferno.colors(), "inferno");
  EXPECT_EQ(e.colorMapName(), "inferno");
  const TransferFunction after = e.function("f");
  for (double v = 0.0; v <= 1.0; v += 0.05) {
    EXPECT_EQ(after.opacity(v), before.opacity(v));
    EXPECT_EQ(after.color(v), inferno.color(v));
  }
  EXPECT_THROW(e.setColors({}, "none"), ValueError);
}

// The invariants of the colour points.
void expectValidColors(const TransferFunctionEditor& e) {
  ASSERT_FALSE(e.colors().empty());
  for (std::size_t i = 0; i < e.colors().size(); ++i) {
    const ColorPoint& p = e.colors()[i];
    EXPECT_GE(p.x, e.lo());
    EXPECT_LE(p.x, e.hi());
    for (int c = 0; c < 3; ++c) {
      EXPECT_GE(p.rgb[c], 0.0) << "colour point " << i;
      EXPECT_LE(p.rgb[c], 1.0) << "colour point " << i;
    }
    if (i > 0) {
      EXPECT_LE(e.colors()[i - 1].x, p.x) << "colour point " << i << " out of order";
    }
  }
}

// A colour point inserted takes the function's colour there (the function stays what it was, within
// rounding), recoloured and moved it changes the function there and only between its neighbours, and
// removed gives the first colours back exactly.
TEST(TransferFunctionEditor, ColourPointsInsertRecolourMoveAndRemove) {
  TransferFunctionEditor e(viridisOn(0.0, 16.0), 0.0, 16.0);
  const TransferFunction first = e.function("first");
  const std::vector<ColorPoint> firstColors = e.colors();
  const uint64_t r0 = e.revision();
  const int i = e.insertColor(4.5);
  EXPECT_GT(e.revision(), r0);
  EXPECT_EQ(e.colorMapName(), "viridis (edited)");
  ASSERT_EQ(e.colors().size(), firstColors.size() + 1);
  ASSERT_GT(i, 0);
  ASSERT_LT(i + 1, int(e.colors().size()));
  EXPECT_EQ(e.colors()[std::size_t(i)].x, 4.5);
  const double below = e.colors()[std::size_t(i) - 1].x, above = e.colors()[std::size_t(i) + 1].x;
  ASSERT_LT(below, 4.5);
  ASSERT_GT(above, 4.5);
  for (double v = -1.0; v <= 17.0; v += 0.173) {
    const glm::dvec3 a = e.function("f").color(v), b = first.color(v);
    EXPECT_NEAR(glm::length(a - b), 0.0, 1e-12) << "at " << v;
  }

  e.setColor(i, glm::dvec3(1.0, 2.0, -1.0));  // clamped
  EXPECT_EQ(e.colors()[std::size_t(i)].rgb, glm::dvec3(1.0, 1.0, 0.0));
  EXPECT_EQ(e.function("f").color(4.5), glm::dvec3(1.0, 1.0, 0.0));
  const double left = below - 0.01, right = above + 0.01;
  EXPECT_EQ(e.function("f").color(left), first.color(left)) << "left of the neighbour below: untouched";
  EXPECT_EQ(e.function("f").color(right), first.color(right)) << "right of the neighbour above: untouched";
  e.setColor(i, glm::dvec3(std::nan(""), 0.5, std::nan("")));
  EXPECT_EQ(e.colors()[std::size_t(i)].rgb, glm::dvec3(1.0, 0.5, 0.0)) << "NaN leaves a component";
  EXPECT_EQ(e.colorMapName(), "viridis (edited)") << "marked once";

  e.moveColor(i, 4.8);
  EXPECT_EQ(e.colors()[std::size_t(i)].x, 4.8);
  e.moveColor(i, 9.0);  // past the neighbour above: stops there
  EXPECT_EQ(e.colors()[std::size_t(i)].x, above);
  e.moveColor(i, -3.0);
  EXPECT_EQ(e.colors()[std::size_t(i)].x, below);
  e.moveColor(0, -3.0);
  EXPECT_EQ(e.colors()[0].x, 0.0) << "the first point: the range's low end";
  const uint64_t r1 = e.revision();
  e.moveColor(0, 0.0);
  e.setColor(0, e.colors()[0].rgb);
  EXPECT_EQ(e.revision(), r1) << "no change, no revision";
  expectValidColors(e);

  EXPECT_TRUE(e.removeColor(i));
  ASSERT_EQ(e.colors().size(), firstColors.size());
  for (std::size_t k = 0; k < firstColors.size(); ++k) {
    EXPECT_EQ(e.colors()[k].x, firstColors[k].x);
    EXPECT_EQ(e.colors()[k].rgb, firstColors[k].rgb);
  }
  while (e.colors().size() > 1) EXPECT_TRUE(e.removeColor(0));
  EXPECT_FALSE(e.removeColor(0)) << "the last colour point stays";
  EXPECT_THROW(e.removeColor(1), ValueError);
  EXPECT_THROW(e.moveColor(-1, 0.0), ValueError);
  EXPECT_THROW(e.setColor(3, glm::dvec3(0.0)), ValueError);
  EXPECT_NO_THROW(e.function("one colour"));
}

TEST(TransferFunctionEditor, PickColourFindsTheNearestPointWithinTheRadius) {
  // Three points at 0, 1 and 2 on [0, 4]; 10 pixels per value unit.
  TransferFunction tf = viridisOn(0.0, 4.0);
  TransferFunctionEditor e(tf, 0.0, 4.0);
  e.setColors({{0.0, glm::dvec3(0.0)}, {1.0, glm::dvec3(0.5)}, {2.0, glm::dvec3(1.0)}}, "grey");
  EXPECT_EQ(e.pickColor(1.2, 10.0, 4.0), 1);
  EXPECT_EQ(e.pickColor(1.5, 10.0, 4.0), -1) << "5 pixels from either";
  EXPECT_EQ(e.pickColor(2.3, 10.0, 4.0), 2);
  EXPECT_EQ(e.pickColor(3.9, 10.0, 4.0), -1);
  const int added = e.insertColor(1.0);  // on point 1: the later one wins the tie
  EXPECT_EQ(added, 2);
  EXPECT_EQ(e.pickColor(1.0, 10.0, 4.0), added);
}

// Undo: each edit a step, a drag (insert then moves of that point, or moves of one point) one step
// until closeStep; undo gives each earlier state back exactly, redo the later ones; a new edit forgets
// the redo; reset forgets everything.
TEST(TransferFunctionEditor, UndoAndRedoStepThroughEditsAndGestures) {
  TransferFunctionEditor e(viridisOn(0.0, 16.0), 0.0, 16.0);
  EXPECT_FALSE(e.canUndo());
  EXPECT_FALSE(e.undo());
  EXPECT_FALSE(e.redo());
  const auto snapshot = [&] { return e.function("s"); };
  const auto same = [](const TransferFunction& a, const TransferFunction& b) {
    return a.opacities() == b.opacities() && a.colors() == b.colors();
  };
  std::vector<TransferFunction> states{snapshot()};
  std::vector<std::string> names{e.colorMapName()};
  // A click and a drag: one step.
  const int i = e.insert(5.0, 0.5);
  e.move(i, 5.5, 0.6);
  e.move(i, 6.0, 0.7);
  e.closeStep();
  states.push_back(snapshot());
  names.push_back(e.colorMapName());
  // The same point dragged again after the release: another step.
  e.move(i, 6.5, 0.2);
  e.move(i, 6.6, 0.25);
  e.closeStep();
  states.push_back(snapshot());
  names.push_back(e.colorMapName());
  // A slider held on its segment's shape, then a colour point recoloured twice: two steps.
  e.setShape(i, 0.3, 0.1);
  e.setShape(i, 0.35, 0.2);
  states.push_back(snapshot());
  names.push_back(e.colorMapName());
  e.setColor(2, glm::dvec3(1.0, 0.0, 0.0));
  e.setColor(2, glm::dvec3(1.0, 0.5, 0.0));
  e.closeStep();
  states.push_back(snapshot());
  names.push_back(e.colorMapName());
  // A no-op is no step.
  e.move(i, e.points()[std::size_t(i)].x, e.points()[std::size_t(i)].alpha);
  e.closeStep();
  EXPECT_TRUE(e.remove(0));
  states.push_back(snapshot());
  names.push_back(e.colorMapName());

  for (std::size_t k = states.size() - 1; k-- > 0;) {
    const uint64_t r = e.revision();
    ASSERT_TRUE(e.undo()) << "undo to state " << k;
    EXPECT_GT(e.revision(), r) << "an undo must rebuild the table";
    EXPECT_TRUE(same(snapshot(), states[k])) << "state " << k;
    EXPECT_EQ(e.colorMapName(), names[k]) << "state " << k;
  }
  EXPECT_FALSE(e.undo()) << "back at the start";
  for (std::size_t k = 1; k < states.size(); ++k) {
    ASSERT_TRUE(e.redo());
    EXPECT_TRUE(same(snapshot(), states[k])) << "redo to state " << k;
  }
  EXPECT_FALSE(e.redo());
  ASSERT_TRUE(e.undo());
  ASSERT_TRUE(e.undo());
  e.insertColor(8.0);  // a new edit: the undone ones are gone
  EXPECT_FALSE(e.canRedo());
  ASSERT_TRUE(e.undo());
  EXPECT_TRUE(same(snapshot(), states[states.size() - 3]));
  e.reset(viridisOn(0.0, 16.0), "viridis");
  EXPECT_FALSE(e.canUndo());
  EXPECT_FALSE(e.canRedo());
}

// A starting point chosen (a preset, a file) is one undo step: undone, the spec, the function's name
// and the edits made before it come back. edited() says whether the points and colours differ from
// the starting point's: false once the edits are undone or edited back, true across an undone start.
TEST(TransferFunctionEditor, StartingPointsAreUndoStepsAndEditedFollowsThem) {
  const TransferFunction viridis = viridisOn(0.0, 16.0);
  TransferFunctionEditor e(viridis, 0.0, 16.0, "viridis");
  EXPECT_EQ(e.spec(), "viridis");
  EXPECT_FALSE(e.edited());
  const int i = e.insert(5.0, 0.5);
  e.closeStep();
  EXPECT_TRUE(e.edited());
  const std::vector<OpacityPoint> editedPoints = e.points();
  // Moved away and back: the same function, so not edited (though two more undo steps).
  e.move(i, 6.0, 0.5);
  e.closeStep();
  e.move(i, 5.0, 0.5);
  e.closeStep();
  EXPECT_TRUE(e.edited()) << "the inserted point is still there";
  EXPECT_TRUE(e.remove(i));
  EXPECT_FALSE(e.edited()) << "the point removed: the starting point's function again";
  ASSERT_TRUE(e.undo());
  EXPECT_TRUE(e.edited());

  TransferFunction inferno = transferFunctionPreset("inferno").stretchedTo(0.0, 16.0);
  const uint64_t r = e.revision();
  e.start(inferno, "inferno");
  EXPECT_GT(e.revision(), r);
  EXPECT_EQ(e.spec(), "inferno");
  EXPECT_FALSE(e.edited());
  EXPECT_EQ(e.function().name(), inferno.name());
  EXPECT_EQ(e.points().size(), inferno.opacities().size());
  EXPECT_FALSE(e.canRedo());

  ASSERT_TRUE(e.undo()) << "the start must be undoable";
  EXPECT_EQ(e.spec(), "viridis");
  EXPECT_EQ(e.function().name(), viridis.name());
  EXPECT_TRUE(e.edited()) << "the edits made before the start are back";
  ASSERT_EQ(e.points().size(), editedPoints.size());
  for (std::size_t k = 0; k < editedPoints.size(); ++k) EXPECT_EQ(e.points()[k].x, editedPoints[k].x) << k;
  while (e.undo()) {
  }
  EXPECT_EQ(e.spec(), "viridis");
  EXPECT_FALSE(e.edited()) << "every edit undone";
  while (e.redo()) {
  }
  EXPECT_EQ(e.spec(), "inferno");
  EXPECT_FALSE(e.edited());

  // reset takes another starting point and forgets the history.
  e.insertColor(3.0);
  EXPECT_TRUE(e.edited());
  e.reset(viridis, "file.json");
  EXPECT_EQ(e.spec(), "file.json");
  EXPECT_FALSE(e.edited());
  EXPECT_FALSE(e.canUndo());
}

// widen lets points go further (another reconstruction's axis) and changes nothing else: the
// function, the revision and the history stay; a narrower range narrows nothing.
TEST(TransferFunctionEditor, WidenKeepsTheFunctionAndItsHistory) {
  TransferFunctionEditor e(viridisOn(0.0, 16.0), 0.0, 16.0, "viridis");
  e.insert(5.0, 0.5);
  e.closeStep();
  const std::vector<OpacityPoint> before = e.points();
  const uint64_t r = e.revision();
  e.widen(-4.0, 20.0);
  EXPECT_EQ(e.lo(), -4.0);
  EXPECT_EQ(e.hi(), 20.0);
  EXPECT_EQ(e.revision(), r);
  EXPECT_TRUE(e.canUndo());
  EXPECT_EQ(e.points().size(), before.size());
  e.widen(1.0, 2.0);
  EXPECT_EQ(e.lo(), -4.0);
  EXPECT_EQ(e.hi(), 20.0);
  const int i = e.insert(19.0, 0.25);
  EXPECT_EQ(e.points()[std::size_t(i)].x, 19.0) << "a point beyond the first axis, inside the widened one";
  EXPECT_THROW(e.widen(3.0, 2.0), ValueError);
  EXPECT_THROW(e.widen(0.0, std::nan("")), ValueError);
  EXPECT_TRUE(e.undo());
  EXPECT_EQ(e.points().size(), before.size());
}

TEST(TransferFunctionEditor, UndoKeepsABoundedHistory) {
  TransferFunctionEditor e(viridisOn(0.0, 16.0), 0.0, 16.0);
  for (std::size_t k = 0; k < TransferFunctionEditor::kUndoSteps + 10; ++k) {
    e.move(0, 0.0, double(k % 2));  // alternating: every move changes the function
    e.closeStep();
  }
  std::size_t undone = 0;
  while (e.undo()) ++undone;
  EXPECT_EQ(undone, TransferFunctionEditor::kUndoSteps);
}

// Random edits of every kind keep the invariants, and the function always constructs.
TEST(TransferFunctionEditor, RandomEditsKeepTheInvariants) {
  std::mt19937 rng(18);
  std::uniform_real_distribution<double> x(-2.0, 12.0), a(-0.5, 1.5);
  TransferFunctionEditor e(viridisOn(2.0, 8.0), 0.0, 10.0);
  for (int step = 0; step < 2000; ++step) {
    const int n = int(e.points().size());
    const int nc = int(e.colors().size());
    switch (rng() % 10) {
      case 0: e.insert(x(rng), a(rng)); break;
      case 1: e.move(int(rng() % unsigned(n)), x(rng), a(rng)); break;
      case 2: e.remove(int(rng() % unsigned(n))); break;
      case 3: e.insertColor(x(rng)); break;
      case 4: e.moveColor(int(rng() % unsigned(nc)), x(rng)); break;
      case 5: e.setColor(int(rng() % unsigned(nc)), glm::dvec3(a(rng), a(rng), a(rng))); break;
      case 6: e.removeColor(int(rng() % unsigned(nc))); break;
      case 7: e.undo(); break;
      case 8: e.redo(); break;
      case 9:
        if (rng() % 4 == 0) e.start(viridisOn(x(rng), 12.0), "viridis");
        else e.closeStep();
        break;
    }
    expectValid(e);
    expectValidColors(e);
    if (HasFailure()) FAIL() << "after step " << step;
    EXPECT_NO_THROW(e.function("f"));
  }
}

}  // namespace
}  // namespace fcc
