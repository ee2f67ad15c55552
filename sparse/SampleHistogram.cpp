#include "SampleHistogram.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "FccGrid.h"

namespace fcc {

int SampleSummary::binOf(double v) const {
  const int bins = int(histogram.size());
  if (bins == 0 || !(max > min)) return 0;
  const double t = (v - double(min)) / (double(max) - double(min)) * bins;
  if (!(t >= 0.0)) return 0;  // also NaN
  return std::min(int(t), bins - 1);
}

uint64_t SampleSummary::total() const { return std::accumulate(histogram.begin(), histogram.end(), uint64_t(0)); }

double samplePercentile(const SampleSummary& s, double percent) {
  const uint64_t total = s.total();
  if (total == 0) return s.min;
  const double target = std::clamp(percent, 0.0, 100.0) / 100.0 * double(total);
  const double width = s.binWidth();
  double below = 0.0;
  for (size_t k = 0; k < s.histogram.size(); ++k) {
    const double count = double(s.histogram[k]);
    if (count > 0.0 && below + count >= target) {
      const double fraction = std::clamp((target - below) / count, 0.0, 1.0);
      return double(s.min) + (double(k) + fraction) * width;
    }
    below += count;
  }
  return s.max;
}

std::optional<double> otsuThreshold(const SampleSummary& s, float background) {
  std::vector<double> counts(s.histogram.begin(), s.histogram.end());
  if (counts.empty()) return std::nullopt;
  counts[size_t(s.binOf(background))] = 0.0;
  // Bin centres as the class values; the threshold lies on a boundary between bins.
  double total = 0.0, sum = 0.0;
  int occupied = 0;
  for (size_t k = 0; k < counts.size(); ++k) {
    total += counts[k];
    sum += double(k) * counts[k];
    occupied += counts[k] > 0.0;
  }
  if (occupied < 2) return std::nullopt;
  double w0 = 0.0, s0 = 0.0, best = -1.0;
  size_t bestK = 0;
  for (size_t k = 0; k + 1 < counts.size(); ++k) {
    w0 += counts[k];
    s0 += double(k) * counts[k];
    const double w1 = total - w0;
    if (w0 <= 0.0 || w1 <= 0.0) continue;
    const double d = s0 / w0 - (sum - s0) / w1;
    const double between = w0 * w1 * d * d;
    if (between > best) {
      best = between;
      bestK = k;
    }
  }
  // Empty bins after bestK leave the variance unchanged: the threshold goes to the gap's middle.
  size_t gapEnd = bestK + 1;  // first non-empty bin above the threshold
  while (gapEnd < counts.size() && counts[gapEnd] == 0.0) ++gapEnd;
  const double lo = double(bestK + 1), hi = double(gapEnd);
  return double(s.min) + 0.5 * (lo + hi) * s.binWidth();
}

void recordSampleHistogram(openvdb::GridBase& grid, const SampleSummary& samples) {
  if (samples.histogram.empty()) return;
  grid.insertMeta(meta::kSampleHistogram, openvdb::StringMetadata(histogramText(samples.histogram)));
}

std::optional<SampleSummary> recordedSamples(const openvdb::GridBase& grid) {
  const auto lo = grid.getMetadata<openvdb::FloatMetadata>(meta::kSampleMin);
  const auto hi = grid.getMetadata<openvdb::FloatMetadata>(meta::kSampleMax);
  if (!lo || !hi) return std::nullopt;
  SampleSummary s;
  s.min = lo->value();
  s.max = hi->value();
  if (const auto text = grid.getMetadata<openvdb::StringMetadata>(meta::kSampleHistogram))
    if (auto counts = parseHistogramText(text->value())) s.histogram = std::move(*counts);
  return s;
}

std::string histogramText(const std::vector<uint64_t>& counts) {
  std::string text;
  for (const uint64_t c : counts) {
    if (!text.empty()) text += ' ';
    text += std::to_string(c);
  }
  return text;
}

std::optional<std::vector<uint64_t>> parseHistogramText(const std::string& text) {
  std::vector<uint64_t> counts;
  const char* p = text.c_str();
  while (*p) {
    if (*p < '0' || *p > '9') return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const unsigned long long v = std::strtoull(p, &end, 10);
    if (errno != 0) return std::nullopt;
    counts.push_back(v);
    p = end;
    if (*p == ' ') ++p;
    else if (*p) return std::nullopt;
  }
  if (counts.empty()) return std::nullopt;
  return counts;
}

}  // namespace fcc
