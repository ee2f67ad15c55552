#include "SvgPlot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace fcc::cli {
namespace {

// Colour-blind-safe (Okabe and Ito's palette), in the order series are drawn.
constexpr const char* kColors[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442"};

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  return text;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (!std::isfinite(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return !(lo <= hi); }
};

}  // namespace

std::string xmlEscaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default:
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\n' || c == '\t') out += c;  // XML refuses the other controls
    }
  }
  return out;
}

std::vector<double> niceTicks(double lo, double hi, int target) {
  if (!(std::isfinite(lo) && std::isfinite(hi))) return {};
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) {
    const double pad = lo == 0.0 ? 1.0 : std::abs(lo) * 0.5;
    lo -= pad;
    hi += pad;
  }
  const double rough = (hi - lo) / std::max(1, target);
  const int exponent = int(std::floor(std::log10(rough)));
  double mantissa = 10.0;
  for (double m : {1.0, 2.0, 5.0})
    if (m * std::pow(10.0, exponent) >= rough) {
      mantissa = m;
      break;
    }
  // A tick is k * mantissa * 10^exponent, computed from the integer k * mantissa and an exact power of
  // ten so that it is the double nearest its decimal value (3e-5, not 2.9999999999999997e-5).
  const double power = std::pow(10.0, std::abs(exponent));
  const auto tick = [&](long k) { return exponent < 0 ? double(k) * mantissa / power : double(k) * mantissa * power; };
  const double step = exponent < 0 ? mantissa / power : mantissa * power;
  std::vector<double> ticks;
  long first = long(std::floor(lo / step)), last = long(std::ceil(hi / step));
  while (tick(first) > lo) --first;  // rounding of the divisions
  while (tick(last) < hi) ++last;
  while (first < last && tick(first + 1) <= lo) ++first;
  while (last > first && tick(last - 1) >= hi) --last;
  for (long k = first; k <= last && ticks.size() < 100; ++k) ticks.push_back(tick(k));
  if (ticks.size() < 2) ticks.push_back(tick(last + 1));
  return ticks;
}

std::string tickLabel(double value, double step) {
  char text[40];
  step = std::abs(step);
  const double magnitude = std::max(std::abs(value), step);
  if (step > 0.0 && step >= 1e-4 && magnitude < 1e7) {
    // Fixed notation with as many decimals as the step needs (steps are 1, 2 or 5 x 10^k).
    const int decimals = std::max(0, int(-std::floor(std::log10(step) + 1e-9)));
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
  } else {
    std::snprintf(text, sizeof text, "%.3g", value);
  }
  return text;
}

std::string svgText(const SvgPlot& plot) {
  const double left = 78, right = 190, top = 44, bottom = 58;  // margins: the legend is at the right
  const double w = plot.width, h = plot.height;
  const double plotW = w - left - right, plotH = h - top - bottom;

  Range xr, yr;
  for (const PlotSeries& s : plot.series) {
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (plot.logX && !(s.x[i] > 0.0)) continue;
      if (!std::isfinite(s.y[i])) continue;
      xr.add(plot.logX ? std::log10(s.x[i]) : s.x[i]);
      yr.add(s.y[i]);
    }
  }
  for (const PlotReference& r : plot.references) yr.add(r.y);
  if (xr.empty()) xr.lo = 0.0, xr.hi = 1.0;
  if (yr.empty()) yr.lo = 0.0, yr.hi = 1.0;
  if (plot.yFromZero) yr.add(0.0);

  std::vector<double> xTicks;
  if (plot.logX) {  // decades and their 2 and 5, within the data's range padded to whole decades
    for (double e = std::floor(xr.lo); e <= std::ceil(xr.hi); e += 1.0)
      for (double m : {1.0, 2.0, 5.0}) {
        const double v = std::log10(m) + e;
        if (v >= std::floor(xr.lo) - 1e-9 && v <= std::ceil(xr.hi) + 1e-9) xTicks.push_back(v);
      }
    if (xr.hi - xr.lo < 1e-9) xTicks = {xr.lo};
    xr.lo = std::min(xr.lo, xTicks.front());
    xr.hi = std::max(xr.hi, xTicks.back());
    if (xr.hi == xr.lo) xr.lo -= 0.5, xr.hi += 0.5;
  } else {
    xTicks = niceTicks(xr.lo, xr.hi, 8);
    xr.lo = xTicks.front();
    xr.hi = xTicks.back();
  }
  const std::vector<double> yTicks = niceTicks(yr.lo, yr.hi, 6);
  yr.lo = std::min(yr.lo, yTicks.front());
  yr.hi = std::max(yr.hi, yTicks.back());
  const double xStep = xTicks.size() > 1 ? xTicks[1] - xTicks[0] : 1.0;
  const double yStep = yTicks.size() > 1 ? yTicks[1] - yTicks[0] : 1.0;

  const auto px = [&](double x) { return left + (x - xr.lo) / (xr.hi - xr.lo) * plotW; };
  const auto py = [&](double y) { return top + plotH - (y - yr.lo) / (yr.hi - yr.lo) * plotH; };

  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
                    num(w) + "\" height=\"" + num(h) + "\" viewBox=\"0 0 " + num(w) + " " + num(h) +
                    "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + num(left + plotW / 2) + "\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">" +
         xmlEscaped(plot.title) + "</text>\n";
  // Grid and ticks.
  for (double t : yTicks) {
    const double y = py(t);
    svg += "<line x1=\"" + num(left) + "\" y1=\"" + num(y) + "\" x2=\"" + num(left + plotW) + "\" y2=\"" + num(y) +
           "\" stroke=\"#e0e0e0\"/>\n";
    svg += "<text x=\"" + num(left - 6) + "\" y=\"" + num(y + 4) + "\" text-anchor=\"end\">" +
           xmlEscaped(tickLabel(t, yStep)) + "</text>\n";
  }
  for (double t : xTicks) {
    const double x = px(t);
    svg += "<line x1=\"" + num(x) + "\" y1=\"" + num(top) + "\" x2=\"" + num(x) + "\" y2=\"" + num(top + plotH) +
           "\" stroke=\"#e0e0e0\"/>\n";
    const std::string label = plot.logX ? tickLabel(std::pow(10.0, t), std::pow(10.0, t) * 0.1) : tickLabel(t, xStep);
    svg += "<text x=\"" + num(x) + "\" y=\"" + num(top + plotH + 18) + "\" text-anchor=\"middle\">" +
           xmlEscaped(label) + "</text>\n";
  }
  svg += "<rect x=\"" + num(left) + "\" y=\"" + num(top) + "\" width=\"" + num(plotW) + "\" height=\"" + num(plotH) +
         "\" fill=\"none\" stroke=\"#404040\"/>\n";
  svg += "<text x=\"" + num(left + plotW / 2) + "\" y=\"" + num(h - 14) + "\" text-anchor=\"middle\">" +
         xmlEscaped(plot.xLabel) + "</text>\n";
  svg += "<text transform=\"translate(18 " + num(top + plotH / 2) + ") rotate(-90)\" text-anchor=\"middle\">" +
         xmlEscaped(plot.yLabel) + "</text>\n";
  // Reference lines, then the series over them.
  for (const PlotReference& r : plot.references) {
    const double y = py(r.y);
    svg += "<line x1=\"" + num(left) + "\" y1=\"" + num(y) + "\" x2=\"" + num(left + plotW) + "\" y2=\"" + num(y) +
           "\" stroke=\"#808080\" stroke-dasharray=\"6 4\"/>\n";
    svg += "<text x=\"" + num(left + plotW - 4) + "\" y=\"" + num(y - 4) + "\" text-anchor=\"end\" fill=\"#606060\">" +
           xmlEscaped(r.name) + "</text>\n";
  }
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    const std::string color = kColors[k % (sizeof kColors / sizeof kColors[0])];
    std::string points;
    const auto flush = [&] {
      if (!points.empty())
        svg += "<polyline fill=\"none\" stroke=\"" + color + "\" stroke-width=\"1.5\" points=\"" + points + "\"/>\n";
      points.clear();
    };
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      const bool valid = std::isfinite(s.y[i]) && std::isfinite(s.x[i]) && (!plot.logX || s.x[i] > 0.0);
      if (!valid) {
        flush();  // a gap
        continue;
      }
      const double x = px(plot.logX ? std::log10(s.x[i]) : s.x[i]), y = py(s.y[i]);
      if (s.line) points += (points.empty() ? "" : " ") + num(x) + "," + num(y);
      if (s.points)
        svg += "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"3.5\" fill=\"" + color + "\"/>\n";
    }
    flush();
    // The legend entry.
    const double ly = top + 8 + 18.0 * double(k);
    svg += "<line x1=\"" + num(left + plotW + 10) + "\" y1=\"" + num(ly) + "\" x2=\"" + num(left + plotW + 30) +
           "\" y2=\"" + num(ly) + "\" stroke=\"" + color + "\" stroke-width=\"" + (s.line ? "2" : "0") + "\"/>\n";
    if (s.points)
      svg += "<circle cx=\"" + num(left + plotW + 20) + "\" cy=\"" + num(ly) + "\" r=\"3.5\" fill=\"" + color + "\"/>\n";
    svg += "<text x=\"" + num(left + plotW + 36) + "\" y=\"" + num(ly + 4) + "\">" + xmlEscaped(s.name) + "</text>\n";
  }
  return svg + "</svg>\n";
}

}  // namespace fcc::cli
