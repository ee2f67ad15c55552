#include "SampleStats.h"

#include <cmath>
#include <cstring>

namespace fcc {

void ValueCounts::add(float v, uint64_t count) {
  if (!std::isfinite(v) || count == 0) return;
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  const uint32_t key = bits >> kDroppedBits;
  std::vector<uint64_t>& page = pages_[key >> kPageBits];
  if (page.empty()) page.assign(size_t(1) << kPageBits, 0);
  page[key & ((1u << kPageBits) - 1)] += count;
  total_ += count;
}

void ValueCounts::add(const ValueCounts& other) {
  for (size_t p = 0; p < pages_.size(); ++p) {
    const std::vector<uint64_t>& theirs = other.pages_[p];
    if (theirs.empty()) continue;
    std::vector<uint64_t>& ours = pages_[p];
    if (ours.empty()) ours.assign(theirs.size(), 0);
    for (size_t i = 0; i < theirs.size(); ++i) ours[i] += theirs[i];
  }
  total_ += other.total_;
}

uint64_t fccSiteCount(const SiteBox& box) {
  if (box.empty()) return 0;
  const glm::ivec3 d = box.dim();
  const uint64_t points = uint64_t(d.x) * uint64_t(d.y) * uint64_t(d.z);
  // With an even side the points pair up (one site each); with all sides odd the corner decides.
  if (points % 2 == 0) return points / 2;
  const bool cornerIsSite = ((box.min.x + box.min.y + box.min.z) & 1) == 0;
  return cornerIsSite ? (points + 1) / 2 : (points - 1) / 2;
}

SampleSummary summarizeSamples(const SampleStats& stats, const SiteBox& bounds, float background) {
  SampleSummary s;
  const uint64_t sites = fccSiteCount(bounds);
  if (sites == 0) return s;
  const uint64_t counted = stats.counts.total();
  const uint64_t unvisited = sites > counted ? sites - counted : 0;
  SampleRange range = stats.range;
  if (unvisited > 0) range.add(background);
  range = range.orBackground(background);
  s.min = range.min;
  s.max = range.max;
  s.histogram.assign(kSampleHistogramBins, 0);
  stats.counts.forEach([&](float v, uint64_t count) { s.histogram[size_t(s.binOf(v))] += count; });
  if (unvisited > 0) s.histogram[size_t(s.binOf(background))] += unvisited;
  return s;
}

}  // namespace fcc
