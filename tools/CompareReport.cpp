#include "CompareReport.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

#include "JsonText.h"

namespace fcc::cli {
namespace {

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

// Methods in the order the rows first name them.
std::vector<std::pair<std::string, std::string>> methodsOf(const std::vector<CompareRow>& rows) {
  std::vector<std::pair<std::string, std::string>> methods;
  for (const auto& r : rows) {
    const auto m = std::make_pair(r.lattice, r.reconstruction);
    if (std::find(methods.begin(), methods.end(), m) == methods.end()) methods.push_back(m);
  }
  return methods;
}

// Text for an SVG element: the title may hold a file's path.
std::string xmlEscaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else out += c;
  }
  return out;
}

std::string optionalNumber(const std::optional<double>& v) { return v ? jsonNumber(*v) : std::string("null"); }

}  // namespace

RgbImage imageGrid(const RgbImage& truth, const std::vector<CompareRow>& rows, int64_t budget) {
  const int w = truth.width, h = truth.height, gap = 4;
  std::vector<const CompareRow*> picked;
  for (const auto& r : rows)
    if (r.budget == budget && r.shaded.width == w && r.shaded.height == h) picked.push_back(&r);
  RgbImage grid{2 * w + gap, int(picked.size() + 1) * (h + gap) - gap, {}};
  grid.rgb.assign(size_t(grid.width) * grid.height * 3, 255);
  auto blit = [&](const RgbImage& image, int x0, int y0) {
    for (int y = 0; y < h; ++y)
      std::copy_n(&image.rgb[size_t(y) * w * 3], size_t(w) * 3, &grid.rgb[(size_t(y0 + y) * grid.width + x0) * 3]);
  };
  blit(truth, 0, 0);
  for (size_t i = 0; i < picked.size(); ++i) {
    const int y0 = int(i + 1) * (h + gap);
    blit(picked[i]->shaded, 0, y0);
    blit(picked[i]->normalError, w + gap, y0);
  }
  return grid;
}

double convergenceSlope(const std::vector<CompareRow>& rows, const std::string& lattice, const std::string& reconstruction) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const auto& r : rows) {
    if (r.lattice != lattice || r.reconstruction != reconstruction) continue;
    if (!(r.valueRmsError > 0.0) || r.samples <= 0) return NAN;
    const double x = std::log(double(r.samples)), y = std::log(r.valueRmsError);
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double det = n * sxx - sx * sx;
  if (n < 2 || std::abs(det) < 1e-12) return NAN;
  return (n * sxy - sx * sy) / det;
}

std::string compareTable(const std::vector<CompareRow>& rows) {
  std::string out;
  char line[512];
  std::snprintf(line, sizeof line, "%-4s %-18s %9s %9s %8s %4s %10s %10s %9s %9s %9s %9s %9s %7s %6s %6s\n", "lat",
                "reconstruction", "budget", "samples", "spacing", "sten", "val_rms", "val_max", "grad_mean", "norm_mean",
                "norm_p95", "img_norm", "img_depth", "img_hm", "slope", "fps");
  out += line;
  for (const auto& r : rows) {
    const double slope = convergenceSlope(rows, r.lattice, r.reconstruction);
    std::snprintf(line, sizeof line, "%-4s %-18s %9lld %9lld %8.5f %4d %10.3e %10.3e %9.3f %9.3f %9.3f %9s %9s %7s %6s %6s\n",
                  r.lattice.c_str(), r.reconstruction.c_str(), (long long)r.budget, (long long)r.samples, r.spacing,
                  r.stencil, r.valueRmsError, r.valueMaxError, r.gradientErrorMeanDeg, r.normalErrorMeanDeg,
                  r.normalErrorP95Deg, r.renderNormalErrorMeanDeg ? format("%.3f", *r.renderNormalErrorMeanDeg).c_str() : "-",
                  r.renderDepthErrorMean ? format("%.2e", *r.renderDepthErrorMean).c_str() : "-",
                  r.shaded.width > 0 ? std::to_string(r.renderHitMissPixels).c_str() : "-",
                  std::isfinite(slope) ? format("%.2f", slope).c_str() : "-", r.fps ? format("%.3g", *r.fps).c_str() : "-");
    out += line;
  }
  return out;
}

std::string compareJson(const std::vector<CompareRow>& rows) {
  std::string out = "[\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    out += "  {\"lattice\": " + jsonString(r.lattice) + ", \"reconstruction\": " + jsonString(r.reconstruction) +
           ", \"budget\": " + std::to_string(r.budget) + ", \"samples\": " + std::to_string(r.samples) +
           ", \"spacing\": " + jsonNumber(r.spacing) + ", \"stencil\": " + std::to_string(r.stencil) +
           ", \"value_rms_error\": " + jsonNumber(r.valueRmsError) + ", \"value_max_error\": " + jsonNumber(r.valueMaxError) +
           ", \"gradient_error_mean_deg\": " + jsonNumber(r.gradientErrorMeanDeg) +
           ", \"gradient_error_p95_deg\": " + jsonNumber(r.gradientErrorP95Deg) +
           ", \"gradient_error_max_deg\": " + jsonNumber(r.gradientErrorMaxDeg) +
           ", \"normal_error_mean_deg\": " + jsonNumber(r.normalErrorMeanDeg) +
           ", \"normal_error_p95_deg\": " + jsonNumber(r.normalErrorP95Deg) +
           ", \"normal_error_max_deg\": " + jsonNumber(r.normalErrorMaxDeg) +
           ", \"surface_points\": " + std::to_string(r.surfacePoints) +
           ", \"render_normal_error_mean_deg\": " + optionalNumber(r.renderNormalErrorMeanDeg) +
           ", \"render_normal_error_p95_deg\": " + optionalNumber(r.renderNormalErrorP95Deg) +
           ", \"render_depth_error_mean\": " + optionalNumber(r.renderDepthErrorMean) +
           ", \"render_hit_miss_pixels\": " + (r.shaded.width > 0 ? std::to_string(r.renderHitMissPixels) : "null") +
           ", \"render_both_hit_pixels\": " + (r.shaded.width > 0 ? std::to_string(r.renderBothHitPixels) : "null") +
           ", \"fps\": " + (r.fps ? jsonNumber(*r.fps) : std::string("null")) + "}";
    out += i + 1 < rows.size() ? ",\n" : "\n";
  }
  return out + "]\n";
}

std::string convergenceSvg(const std::vector<CompareRow>& rows, const std::string& title) {
  // Axes: log10(samples) across, log10(value RMS error) up, each padded to whole decades.
  double xMin = 1e300, xMax = -1e300, yMin = 1e300, yMax = -1e300;
  for (const auto& r : rows) {
    if (!(r.valueRmsError > 0.0)) continue;
    xMin = std::min(xMin, std::log10(double(r.samples)));
    xMax = std::max(xMax, std::log10(double(r.samples)));
    yMin = std::min(yMin, std::log10(r.valueRmsError));
    yMax = std::max(yMax, std::log10(r.valueRmsError));
  }
  if (xMin > xMax) xMin = 0, xMax = 1, yMin = -1, yMax = 0;
  xMin = std::floor(xMin), xMax = std::max(std::ceil(xMax), xMin + 1);
  yMin = std::floor(yMin), yMax = std::max(std::ceil(yMax), yMin + 1);
  const double left = 80, top = 40, width = 560, height = 420, legendX = left + width + 20;
  auto px = [&](double lx) { return left + (lx - xMin) / (xMax - xMin) * width; };
  auto py = [&](double ly) { return top + (yMax - ly) / (yMax - yMin) * height; };
  static const char* colours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  std::string svg;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" font-family=\"sans-serif\" font-size=\"12\">\n"
                "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                int(legendX + 260), int(top + height + 60));
  svg += buf;
  svg += "<text x=\"" + format("%.0f", left) + "\" y=\"24\" font-size=\"14\">" + xmlEscaped(title) + "</text>\n";
  for (double d = xMin; d <= xMax + 1e-9; d += 1) {
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/><text x=\"%.1f\" y=\"%.1f\" "
                  "text-anchor=\"middle\">1e%d</text>\n",
                  px(d), top, px(d), top + height, px(d), top + height + 18, int(d));
    svg += buf;
  }
  for (double d = yMin; d <= yMax + 1e-9; d += 1) {
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/><text x=\"%.1f\" y=\"%.1f\" "
                  "text-anchor=\"end\">1e%d</text>\n",
                  left, py(d), left + width, py(d), left - 6, py(d) + 4, int(d));
    svg += buf;
  }
  std::snprintf(buf, sizeof buf,
                "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"black\"/>\n"
                "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">samples</text>\n"
                "<text transform=\"translate(20,%.1f) rotate(-90)\" text-anchor=\"middle\">value RMS error</text>\n",
                left, top, width, height, left + width / 2, top + height + 40, top + height / 2);
  svg += buf;
  const auto methods = methodsOf(rows);
  for (size_t m = 0; m < methods.size(); ++m) {
    const char* colour = colours[m % 10];
    std::string points;
    for (const auto& r : rows) {
      if (r.lattice != methods[m].first || r.reconstruction != methods[m].second || !(r.valueRmsError > 0.0)) continue;
      const double x = px(std::log10(double(r.samples))), y = py(std::log10(r.valueRmsError));
      points += format("%.1f,", x) + format("%.1f ", y);
      std::snprintf(buf, sizeof buf, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"%s\"/>\n", x, y, colour);
      svg += buf;
    }
    svg += "<polyline fill=\"none\" stroke=\"" + std::string(colour) + "\" stroke-width=\"1.5\" points=\"" + points + "\"/>\n";
    const double slope = convergenceSlope(rows, methods[m].first, methods[m].second);
    std::snprintf(buf, sizeof buf,
                  "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"2\"/>"
                  "<text x=\"%.1f\" y=\"%.1f\">%s %s%s</text>\n",
                  legendX, top + 10 + 18 * m, legendX + 20, top + 10 + 18 * m, colour, legendX + 26, top + 14 + 18 * m,
                  methods[m].first.c_str(), methods[m].second.c_str(),
                  std::isfinite(slope) ? format(" (slope %.2f)", slope).c_str() : "");
    svg += buf;
  }
  return svg + "</svg>\n";
}

}  // namespace fcc::cli
