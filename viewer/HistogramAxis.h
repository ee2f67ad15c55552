// The value axis of the panel's histogram: equal bins over [min, max], and what a position along the
// plot (0 at its left edge, 1 at its right) means.
#pragma once

#include <algorithm>

namespace fcc::render {

struct HistogramAxis {
  float min = 0.0f, max = 0.0f;
  int bins = 1;

  // The bin at position t (clamped into the plot).
  int binAt(float t) const { return std::clamp(int(t * float(bins)), 0, std::max(bins, 1) - 1); }
  float binLow(int bin) const { return min + (max - min) * float(bin) / float(bins); }
  float binHigh(int bin) const { return min + (max - min) * float(bin + 1) / float(bins); }
  // The value at position t, and the position of value v (both clamped into the plot).
  float valueAt(float t) const { return min + (max - min) * std::clamp(t, 0.0f, 1.0f); }
  float positionOf(float v) const { return max > min ? std::clamp((v - min) / (max - min), 0.0f, 1.0f) : 0.5f; }
};

}  // namespace fcc::render
