// Plots as SVG text, written by hand: Debian packages no C++ plotting library (matplot++, sciplot and
// the like are not in Debian 12), and a benchmark's plots need only lines and points on linear or
// logarithmic axes. One chart a plot: axes with "nice" ticks (1, 2, 5 x 10^k), labels, a title, a
// legend, series drawn as lines or points, and dashed horizontal reference lines (a budget, a size).
#pragma once

#include <string>
#include <vector>

namespace fcc::cli {

struct PlotSeries {
  std::string name;           // in the legend
  std::vector<double> x, y;   // same length; a non-finite y leaves a gap
  bool line = true;           // a polyline through the points
  bool points = false;        // a marker at each point
};

struct PlotReference {
  std::string name;  // drawn at the line's right end
  double y = 0.0;
};

struct SvgPlot {
  std::string title, xLabel, yLabel;
  std::vector<PlotSeries> series;
  std::vector<PlotReference> references;
  bool logX = false;      // base-10 axis (positive x only)
  bool yFromZero = true;  // the y axis includes 0
  int width = 720, height = 420;
};

// "Nice" tick values covering [lo, hi]: about `target` of them, steps 1, 2 or 5 x 10^k.
std::vector<double> niceTicks(double lo, double hi, int target);
// A tick's label: the shortest of %g that tells the ticks apart.
std::string tickLabel(double value, double step);
// The SVG document (UTF-8, standalone, parses as XML).
std::string svgText(const SvgPlot& plot);
// Text made safe for XML content and attribute values.
std::string xmlEscaped(const std::string& text);

}  // namespace fcc::cli
