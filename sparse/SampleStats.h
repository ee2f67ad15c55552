// What the grid builders learn about the samples while they build (one SampleStats per thread,
// merged at the end): their range and their distribution. The range is only known once every sample
// has been seen, and the file records the histogram in bins over that range, so the samples are
// first counted by value in bins that need no range: a float's sign, exponent and top 12 mantissa
// bits (integers up to 8192 each get their own bin, anything else is within 1/4096 of its bin's
// value), and binned over the range at the end (summarizeSamples).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "SampleField.h"
#include "SampleHistogram.h"

namespace fcc {

// Range of sample values seen (empty until a value is added).
struct SampleRange {
  float min = std::numeric_limits<float>::infinity();
  float max = -std::numeric_limits<float>::infinity();
  bool empty() const { return !(min <= max); }
  void add(float v) {
    min = std::min(min, v);
    max = std::max(max, v);
  }
  void add(const SampleRange& r) {
    min = std::min(min, r.min);
    max = std::max(max, r.max);
  }
  // What the metadata records: (background, background) for a field that holds no samples.
  SampleRange orBackground(float background) const { return empty() ? SampleRange{background, background} : *this; }
};

// Counts of values by their float's top 21 bits, in pages of one sign and exponent each, allocated
// when first met (32 KiB each; data of one order of magnitude touches one or two).
class ValueCounts {
 public:
  static constexpr int kDroppedBits = 11;  // of the 23 mantissa bits
  void add(float v, uint64_t count);
  void add(const ValueCounts& other);
  uint64_t total() const { return total_; }
  // Calls visit(value, count) for every value met: the value with its dropped bits cleared.
  template <class Visit>
  void forEach(Visit&& visit) const;

 private:
  static constexpr int kPageBits = 12;
  std::array<std::vector<uint64_t>, (1u << (32 - kDroppedBits - kPageBits))> pages_;
  uint64_t total_ = 0;
};

struct SampleStats {
  SampleRange range;
  ValueCounts counts;
  void add(float v, uint64_t sites = 1) {
    range.add(v);
    counts.add(v, sites);
  }
  void add(const SampleStats& other) {
    range.add(other.range);
    counts.add(other.counts);
  }
};

// Even-coordinate-sum points in `box` (its FCC sites).
uint64_t fccSiteCount(const SiteBox& box);

// The range and histogram (kSampleHistogramBins) of the samples at every FCC site of `bounds`: the
// ones in `stats`, and `background` at the sites the builder never visited (a field says which of its
// regions hold only the background, and those are skipped), so both builders give the same figures.
// An empty `bounds` gives (0, 0) and no histogram.
SampleSummary summarizeSamples(const SampleStats& stats, const SiteBox& bounds, float background);

template <class Visit>
void ValueCounts::forEach(Visit&& visit) const {
  for (uint32_t page = 0; page < pages_.size(); ++page) {
    const std::vector<uint64_t>& counts = pages_[page];
    for (uint32_t slot = 0; slot < counts.size(); ++slot) {
      if (counts[slot] == 0) continue;
      const uint32_t bits = ((page << kPageBits) | slot) << kDroppedBits;
      float v;
      static_assert(sizeof v == sizeof bits, "a float is 32 bits");
      std::copy_n(reinterpret_cast<const char*>(&bits), sizeof bits, reinterpret_cast<char*>(&v));
      visit(v, counts[slot]);
    }
  }
}

}  // namespace fcc
